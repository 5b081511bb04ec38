#include <algorithm>
#include <cmath>
#include <optional>

#include "path/segment_geometry.h"
#include "plan/arc_transition.h"
#include "plan/tolerances.h"

namespace lcnc {
namespace {

using V2 = Eigen::Vector2d;

V2 perp(const V2& v) { return V2(-v.y(), v.x()); }  // +90°
double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

// One neighbour of the corner, in the plane's 2D coordinates.
struct Curve {
  bool line = true;
  V2 d = V2::Zero();  // line: unit direction of travel
  V2 c = V2::Zero();  // arc: centre
  double radius = 0.0;
  double sigma = 1.0;  // arc: +1 counter-clockwise, −1 clockwise
  double length = 0.0;

  // Unit tangent (direction of travel) at a point x on the curve.
  [[nodiscard]] V2 tangent(const V2& x) const { return line ? d : V2(sigma * perp(x - c) / radius); }
};

// Points of the curve offset by r toward the side `side` (+1 left of travel).
// Line: x·n = P·n + r·side (n the left normal). Circle: |x − c| = R − side·σ·r.
struct Fillet {
  V2 center, ta, tb;  // centre, tangent points on a and b
  double trim_a = 0.0, trim_b = 0.0;
};

std::optional<V2> nearest(const V2& p, const std::optional<V2>& u, const std::optional<V2>& v) {
  if (!u) return v;
  if (!v) return u;
  return (*u - p).squaredNorm() <= (*v - p).squaredNorm() ? u : v;
}

// Crossings of line {x : (x − q)·n = 0} (n unit) with circle |x − c| = R, nearest p.
std::optional<V2> line_circle(const V2& q, const V2& dir, const V2& c, double R, const V2& p) {
  const V2 f = q - c;
  const double b = f.dot(dir), cc = f.squaredNorm() - R * R;
  const double disc = b * b - cc;
  if (disc < 0.0) return std::nullopt;
  const double s = std::sqrt(disc);
  return nearest(p, V2(q + (-b - s) * dir), V2(q + (-b + s) * dir));
}

std::optional<V2> circle_circle(const V2& c1, double r1, const V2& c2, double r2, const V2& p) {
  const V2 d = c2 - c1;
  const double dist = d.norm();
  if (dist <= 0.0 || dist > r1 + r2 || dist < std::abs(r1 - r2)) return std::nullopt;
  const double a = (r1 * r1 - r2 * r2 + dist * dist) / (2.0 * dist);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
  const V2 m = c1 + a * d / dist;
  const V2 o = h * perp(d / dist);
  return nearest(p, V2(m + o), V2(m - o));
}

// Signed travel from `from` to `to` along the curve (arc angle·R or line
// projection), positive in the direction of travel.
double travel(const Curve& k, const V2& from, const V2& to) {
  if (k.line) return (to - from).dot(k.d);
  const V2 a = from - k.c, b = to - k.c;
  return k.sigma * std::atan2(cross(a, b), a.dot(b)) * k.radius;
}

std::optional<Fillet> fillet_at(const Curve& A, const Curve& B, const V2& p, double side, double r) {
  std::optional<V2> x;
  if (A.line && B.line) return std::nullopt;  // handled by arc_transition
  if (A.line || B.line) {
    const Curve& L = A.line ? A : B;
    const Curve& C = A.line ? B : A;
    const double R = C.radius - side * C.sigma * r;
    if (R <= 0.0) return std::nullopt;
    x = line_circle(V2(p + side * r * perp(L.d)), L.d, C.c, R, p);
  } else {
    const double ra = A.radius - side * A.sigma * r, rb = B.radius - side * B.sigma * r;
    if (ra <= 0.0 || rb <= 0.0) return std::nullopt;
    x = circle_circle(A.c, ra, B.c, rb, p);
  }
  if (!x) return std::nullopt;
  auto foot = [&](const Curve& k) -> V2 {
    if (k.line) return p + (*x - p).dot(k.d) * k.d;
    return k.c + k.radius * (*x - k.c).normalized();
  };
  Fillet f{*x, foot(A), foot(B), 0.0, 0.0};
  f.trim_a = travel(A, f.ta, p);  // ta lies before p on a
  f.trim_b = travel(B, p, f.tb);  // tb lies after p on b
  return f;
}

bool curve_of(const Segment& s, const PlaneAxes& pa, Curve& out) {
  const Pose d = s.end - s.start;
  if (d.tail<3>().norm() > 0.0) return false;  // rotary motion: not here
  if (s.kind == MotionKind::Linear) {
    if (std::abs(d[pa.normal]) > plan::kInPlaneMm) return false;  // leaves the plane
    out.line = true;
    out.d = V2(d[pa.first], d[pa.second]);
    out.length = out.d.norm();
    if (out.length <= plan::kMinSegmentLength) return false;
    out.d /= out.length;
    return true;
  }
  if (s.kind != MotionKind::Arc || s.plane == Plane::Free || plane_axes(s.plane).normal != pa.normal)
    return false;
  if (std::abs(d[pa.normal]) > plan::kInPlaneMm) return false;  // helix
  out.line = false;
  out.c = V2(s.center[pa.first], s.center[pa.second]);
  out.radius = (V2(s.start[pa.first], s.start[pa.second]) - out.c).norm();
  // a spiral (end radius not the start's) has no circle to fillet against:
  // its corner is a junction (lookahead)
  const double r_end = (V2(s.end[pa.first], s.end[pa.second]) - out.c).norm();
  if (std::abs(r_end - out.radius) > plan::kSpiralBlendMm) return false;
  out.sigma = s.clockwise ? -1.0 : 1.0;
  out.length = SegmentGeometry(s).length();
  return out.radius > plan::kMinSegmentLength;
}

}  // namespace

ArcTransition fillet_transition(const Segment& a, const Segment& b, double tolerance_mm, double max_trim_a,
                                double max_trim_b) {
  ArcTransition t;
  if (tolerance_mm <= 0.0) return t;
  const Segment& arc = a.kind == MotionKind::Arc ? a : b;
  if (arc.kind != MotionKind::Arc || arc.plane == Plane::Free) return t;
  const PlaneAxes pa = plane_axes(arc.plane);
  Curve A, B;
  if (!curve_of(a, pa, A) || !curve_of(b, pa, B)) return t;
  if (std::abs(a.end[pa.normal] - b.start[pa.normal]) > plan::kInPlaneMm) return t;
  const V2 p(b.start[pa.first], b.start[pa.second]);
  const V2 ta = A.tangent(p), tb = B.tangent(p);
  const double turn = std::atan2(cross(ta, tb), ta.dot(tb));
  if (std::abs(turn) < plan::kMinBlendAngle || std::abs(turn) > plan::kMaxBlendAngle) return t;
  const double side = turn > 0.0 ? 1.0 : -1.0;  // the fillet sits inside the turn

  auto feasible = [&](double r) -> std::optional<Fillet> {
    auto f = fillet_at(A, B, p, side, r);
    if (!f) return std::nullopt;
    if (f->trim_a <= 0.0 || f->trim_b <= 0.0 || f->trim_a > max_trim_a || f->trim_b > max_trim_b)
      return std::nullopt;
    if (std::abs((p - f->center).norm() - r) > tolerance_mm) return std::nullopt;
    return f;
  };
  // Start from the line–line estimate on the tangents and search up and down.
  const double half = std::abs(turn) / 2.0;
  const double l_c = tolerance_mm * std::sin(half) / (1.0 - std::cos(half));
  const double r_est = std::min({l_c, max_trim_a, max_trim_b}) / std::tan(half);
  double lo = 0.0, hi = 4.0 * r_est;
  std::optional<Fillet> best;
  for (double r = r_est; r > r_est * plan::kFilletSearchFloor; r *= 0.25) {
    if ((best = feasible(r))) {
      lo = r;
      break;
    }
    hi = r;
  }
  if (!best) return t;
  // to kFilletRadiusRel of the radius
  for (int it = 0; it < plan::kFilletBisectionSteps && hi - lo > plan::kFilletRadiusRel * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (auto f = feasible(mid)) {
      lo = mid;
      best = f;
    } else {
      hi = mid;
    }
  }
  const Fillet& f = *best;
  auto pose_at = [&](const Segment& s, const V2& x) {
    Pose q = s.end;  // same normal coordinate and rotary values
    q[pa.first] = x.x();
    q[pa.second] = x.y();
    return q;
  };
  t.blended = true;
  t.trim = std::max(f.trim_a, f.trim_b);
  t.q0 = pose_at(a, f.ta);
  t.q2 = pose_at(b, f.tb);
  set_blend_arc(a, b, t.q0, t.q2, t.arc);
  t.arc.plane = arc.plane;
  t.arc.center = b.start.head<3>();
  t.arc.center[pa.first] = f.center.x();
  t.arc.center[pa.second] = f.center.y();
  t.arc.clockwise = side < 0.0;
  return t;
}

}  // namespace lcnc
