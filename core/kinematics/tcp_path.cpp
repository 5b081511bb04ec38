// TCP subdivision of a straight tip move; see tcp_path.h.
#include "kinematics/tcp_path.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "kinematics/kinematics_tolerances.h"
#include "path/segment_geometry.h"

namespace lcnc {

Pose tcp_joints_at(const FiveAxisKinematics& kin, const Vec3& a, const Vec3& b, const OrientationMove& move,
                   double u) {
  return kin.joints_for_tip(a + u * (b - a), move.joints_at(u));
}

namespace {

// Path length the planner measures on a joint segment: linear axes if they
// move, else rotary (path/segment_geometry.h).
double joint_length(const Pose& d) {
  const double lin = d.head<3>().norm();
  return lin > 0.0 ? lin : d.tail<3>().norm();
}

}  // namespace

Result<std::vector<Segment>> tcp_line_segments(const FiveAxisKinematics& kin, const Vec3& a, const Vec3& b,
                                               const OrientationMove& move, const Segment& prototype,
                                               double tip_tol, double orient_tol) {
  if (!(tip_tol > 0.0 && orient_tol > 0.0))
    return make_error(ErrorCode::GcodeBadValue, "TCP tolerances must be > 0 (tip mm, orientation deg)");
  struct Piece {
    double u0, u1;
    int depth;
  };
  std::vector<Segment> out;
  // Depth-first, right half pushed first, so pieces come out in order.
  std::vector<Piece> stack{{0.0, 1.0, 0}};
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    const Pose j0 = tcp_joints_at(kin, a, b, move, p.u0);
    const Pose j1 = tcp_joints_at(kin, a, b, move, p.u1);
    bool ok = true;
    for (double f : std::array{0.25, 0.5, 0.75}) {
      const ToolPose t = kin.forward(j0 + f * (j1 - j0));
      const double u = p.u0 + f * (p.u1 - p.u0);
      if (distance_to_segment(t.tip_mm, a, b) > tip_tol ||
          angle_between_deg(t.axis, move.axis_at(u)) > orient_tol) {
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
    Segment s = prototype;
    // a rapid stays a rapid (every joint at its own limit, no feed); a feed
    // move or an arc's piece is a joint line at the feed that keeps the tip's
    s.kind = prototype.kind == MotionKind::Rapid ? MotionKind::Rapid : MotionKind::Linear;
    s.start = j0;
    s.end = j1;
    const double tip_len = (p.u1 - p.u0) * (b - a).norm();
    if (tip_len > 0.0) s.feed_mm_s = prototype.feed_mm_s * joint_length(j1 - j0) / tip_len;
    // G93: the move's time shared out as its length (each piece took all of it)
    if (prototype.duration_s > 0.0) s.duration_s = prototype.duration_s * (p.u1 - p.u0);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace lcnc
