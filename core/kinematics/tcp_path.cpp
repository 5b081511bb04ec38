// TCP subdivision of a straight tip move; see tcp_path.h.
#include "kinematics/tcp_path.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "kinematics/kinematics_tolerances.h"
#include "path/path_tolerances.h"
#include "path/segment_geometry.h"

namespace lcnc {

namespace {

// Step of u for dq/du: far above the rounding of q (1e-16 of hundreds of
// mm), far below a piece (2^-24 of a move at the deepest).
constexpr double kJointRateStepU = 1e-7;
// Samples of a move's joint path and of the rotary travel of one whose tip
// stands still (their chords: lengths within ~10⁻⁴ of the curve's).
constexpr int kLengthSamples = 64;
// dq/du may change by at most this share across a piece: the planner holds
// each piece to the joints' highest rate and bend on it, so where those
// change fast (near the pole) long pieces would run below the speed the
// joints allow along most of them.
constexpr double kMaxRateChange = 0.05;

}  // namespace

Pose TcpMove::joints_at(double u) const { return kin->joints_for_tip(tip_at(u), move.joints_at(u)); }

Pose TcpMove::rate_at(double u) const {
  const double h = kJointRateStepU;
  if (u - h < 0.0) return (-3.0 * joints_at(u) + 4.0 * joints_at(u + h) - joints_at(u + 2.0 * h)) / (2.0 * h);
  if (u + h > 1.0) return (3.0 * joints_at(u) - 4.0 * joints_at(u - h) + joints_at(u - 2.0 * h)) / (2.0 * h);
  return (joints_at(u + h) - joints_at(u - h)) / (2.0 * h);
}

TcpMove TcpMove::make(const FiveAxisKinematics& kin, const Vec3& a, const Vec3& b,
                      const OrientationMove& move) {
  TcpMove m{&kin, a, b, move, 0.0, tcp_move_length(a, b, move)};
  Pose prev = m.joints_at(0.0);
  for (int k = 1; k <= kLengthSamples; ++k) {
    const Pose q = m.joints_at(static_cast<double>(k) / kLengthSamples);
    m.length += (q - prev).norm();
    prev = q;
  }
  if (!(m.length > path::kMinSegmentLength)) m.length = 0.0;
  return m;
}

double tcp_move_length(const Vec3& a, const Vec3& b, const OrientationMove& move) {
  const double tip = (b - a).norm();
  if (tip > path::kMinSegmentLength) return tip;
  double rot = 0.0;
  RotaryJoints prev = move.joints_at(0.0);
  for (int k = 1; k <= kLengthSamples; ++k) {
    const RotaryJoints r = move.joints_at(static_cast<double>(k) / kLengthSamples);
    rot += std::hypot(r.a_deg - prev.a_deg, r.c_deg - prev.c_deg);
    prev = r;
  }
  return rot > path::kMinSegmentLength ? rot : 0.0;
}

Result<std::vector<Segment>> tcp_curve_segments(const TcpMove& m, const Segment& prototype, double tip_tol,
                                                double orient_tol, double u_from, double u_to) {
  if (!(tip_tol > 0.0 && orient_tol > 0.0))
    return make_error(ErrorCode::GcodeBadValue, "TCP tolerances must be > 0 (tip mm, orientation deg)");
  struct Piece {
    double u0, u1;
    int depth;
  };
  std::vector<Segment> out;
  if (!(u_to > u_from) || m.length <= 0.0) return out;
  // Depth-first, right half pushed first, so pieces come out in order.
  std::vector<Piece> stack{{u_from, u_to, 0}};
  Pose q0 = m.joints_at(u_from), d0 = m.rate_at(u_from);
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    const double du = p.u1 - p.u0;
    Segment s = prototype;
    s.kind = prototype.kind == MotionKind::Rapid ? MotionKind::Rapid : MotionKind::Linear;
    s.curve = true;
    s.smooth_in = !out.empty();
    s.start = q0;
    s.end = m.joints_at(p.u1);
    const Pose d1 = m.rate_at(p.u1);
    s.curve_d_start = d0 * du;
    s.curve_d_end = d1 * du;
    s.curve_length = m.length * du;
    const SegmentGeometry geo(s);
    bool ok = (d1 - d0).norm() <= kMaxRateChange * std::max(d0.norm(), d1.norm());
    for (double f : std::array{0.25, 0.5, 0.75}) {
      if (!ok) break;
      const ToolPose t = m.kin->forward(geo.at(f * s.curve_length));
      const double u = p.u0 + f * du;
      if ((t.tip_mm - m.tip_at(u)).norm() > tip_tol ||
          angle_between_deg(t.axis, m.move.axis_at(u)) > orient_tol) {
        ok = false;
        break;
      }
    }
    if (!ok) {
      if (p.depth >= kin::kMaxTcpDepth)
        return make_error(ErrorCode::GcodeBadValue,
                          "TCP move cannot be split within tolerance near u = " + std::to_string(p.u0) +
                              " (C jumps: a vector move through A = 0? use pole-smoothed)");
      const double um = 0.5 * (p.u0 + p.u1);
      stack.push_back({um, p.u1, p.depth + 1});
      stack.push_back({p.u0, um, p.depth + 1});
      continue;
    }
    s.feed_mm_s = m.path_feed(prototype.feed_mm_s);
    // G93: the move's time shared out as its parameter
    if (prototype.duration_s > 0.0) s.duration_s = prototype.duration_s * du;
    q0 = s.end;
    d0 = d1;
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace lcnc
