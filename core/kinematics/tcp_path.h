// Tool-centre-point (TCP) control of a straight tip move (docs/design.md §5.6): the
// tool tip runs on the straight line a → b while A and C follow an
// orientation interpolator, both driven by the same u ∈ [0, 1]:
//   tip(u) = a + u·(b − a),   (A, C)(u) = move.joints_at(u)
//   joints(u) = FiveAxisKinematics::joints_for_tip(tip(u), (A, C)(u))
// The planner moves the joints linearly within a segment, so the move is
// split (by bisection) into joint-space lines short enough that, with the
// joints linear in between, the tip stays within tip_tolerance_mm of the
// line a–b and the axis within orientation_tolerance_deg of the
// interpolator's. Checked at ¼, ½ and ¾ of each piece: the deviation of a
// linearly interpolated smooth curve is near-parabolic, largest mid-piece.
#pragma once

#include <vector>

#include "common/result.h"
#include "kinematics/five_axis.h"
#include "kinematics/orientation_interpolation.h"
#include "path/segment.h"

namespace lcnc {

// Joints at u of the TCP move.
[[nodiscard]] Pose tcp_joints_at(const FiveAxisKinematics& kin, const Vec3& tip_start_mm,
                                 const Vec3& tip_end_mm, const OrientationMove& move, double u);

// The joint-space line segments of a TCP move. Each copies `prototype`
// (feed, laser, path mode, line) with start and end in joints; its feed is
// scaled by joint length / tip length so that the planner, running the
// joints' path at that feed, moves the tip at prototype.feed_mm_s. Error
// GcodeBadValue when a tolerance is not > 0 or when the move cannot be split
// within them (a C jump: a vector move through the pole).
[[nodiscard]] Result<std::vector<Segment>> tcp_line_segments(const FiveAxisKinematics& kin,
                                                             const Vec3& tip_start_mm, const Vec3& tip_end_mm,
                                                             const OrientationMove& move,
                                                             const Segment& prototype,
                                                             double tip_tolerance_mm,
                                                             double orientation_tolerance_deg);

}  // namespace lcnc
