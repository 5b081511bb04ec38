#include "plan/arc_transition.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "plan/tolerances.h"

namespace lcnc {

void set_blend_arc(const Segment& a, const Segment& b, const Pose& q0, const Pose& q2, Segment& arc) {
  arc = a;
  arc.kind = MotionKind::Arc;
  arc.clockwise = false;
  arc.extra_turns = 0;
  arc.start = q0;
  arc.end = q2;
  arc.line = b.line;
}

bool arc_transition(const Segment& a, const Segment& b, double la, double lb, double tolerance_mm,
                    double max_trim_a, double max_trim_b, ArcTransition& t, Segment& arc,
                    SegmentGeometry& geo) {
  t.blended = false;
  if (la <= plan::kMinSegmentLength || lb <= plan::kMinSegmentLength || tolerance_mm <= 0.0) return false;
  const Vec3 p = b.start.head<3>();
  const double inv_la = 1.0 / la, inv_lb = 1.0 / lb;
  // The unit directions and their cross product coordinate by coordinate:
  // Eigen's 3-vectors would go through memory in halves, and each whole
  // read of them wait for both halves' stores.
  double u1[3], u2[3];
  for (int i = 0; i < 3; ++i) {
    u1[i] = (a.end[i] - a.start[i]) * inv_la;
    u2[i] = (b.end[i] - b.start[i]) * inv_lb;
  }
  const double cx = u1[1] * u2[2] - u1[2] * u2[1];
  const double cy = u1[2] * u2[0] - u1[0] * u2[2];
  const double cz = u1[0] * u2[1] - u1[1] * u2[0];
  const Vec3 d1(u1[0], u1[1], u1[2]), d2(u2[0], u2[1], u2[2]), cross(cx, cy, cz);
  // The turning angle θ by its sine and cosine (of unit vectors: no
  // normalising), and the half angle's from them without trigonometric
  // calls: each formula where it is well conditioned (θ near 0 and near π).
  // Divisions are by sin θ and sin(θ/2) once each, off the roots' path.
  const double sin_t = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double cos_t = u1[0] * u2[0] + u1[1] * u2[1] + u1[2] * u2[2];
  if (cos_t > 0.0 ? sin_t < std::sin(plan::kMinBlendAngle)
                  : sin_t < std::sin(std::numbers::pi - plan::kMaxBlendAngle))
    return false;  // (nearly) straight on, or (nearly) reversed
  const double inv_sin_t = 1.0 / sin_t;
  double cos_h, inv_sin_h;
  if (cos_t > 0.0) {
    cos_h = std::sqrt(0.5 * (1.0 + cos_t));
    inv_sin_h = 2.0 * cos_h * inv_sin_t;  // sin(θ/2) = sin θ / (2·cos(θ/2))
  } else {
    inv_sin_h = 1.0 / std::sqrt(0.5 * (1.0 - cos_t));
    cos_h = 0.5 * sin_t * inv_sin_h;
  }
  // l_c = E·sin(θ/2) / (1 − cos(θ/2)) = E·(1 + cos(θ/2)) / sin(θ/2)
  const double l_c = tolerance_mm * (1.0 + cos_h) * inv_sin_h;
  const double l = std::min({l_c, max_trim_a, max_trim_b});
  if (l <= plan::kMinSegmentLength) return false;
  const double r = l * cos_h * inv_sin_h;

  t.blended = true;
  t.trim = l;
  t.q0 = a.start + (a.end - a.start) * ((la - l) * inv_la);
  t.q2 = b.start + (b.end - b.start) * (l * inv_lb);
  t.q0.head<3>() = p - l * d1;  // exact on the line, whatever the rounding above
  t.q2.head<3>() = p + l * d2;

  set_blend_arc(a, b, t.q0, t.q2, arc);
  arc.plane = Plane::Free;
  arc.normal = cross * inv_sin_t;
  // the centre lies r / cos(θ/2) from P along d2 − d1, whose length is
  // 2·sin(θ/2): (d2 − d1)·r / (2·sin(θ/2)·cos(θ/2)) = (d2 − d1)·r / sin θ
  arc.center = p + (d2 - d1) * (r * inv_sin_t);
  // it starts along d1, about the centre at u = d1 × n from it (w = n × u = d1)
  geo.set_circular_arc(t.q0, t.q2, arc.center, d1.cross(arc.normal), d1, r, sin_t, cos_t);
  return true;
}

ArcTransition arc_transition(const Segment& a, const Segment& b, double tolerance_mm, double max_trim_a,
                             double max_trim_b) {
  ArcTransition t;
  SegmentGeometry geo{Segment{}};
  const double la = (a.end.head<3>() - a.start.head<3>()).norm();
  const double lb = (b.end.head<3>() - b.start.head<3>()).norm();
  (void)arc_transition(a, b, la, lb, tolerance_mm, max_trim_a, max_trim_b, t, t.arc, geo);
  return t;
}

}  // namespace lcnc
