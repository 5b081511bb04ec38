// Tool-centre-point (TCP) control of a straight tip move (docs/design.md §5.6): the
// tool tip runs on the straight line a → b while A and C follow an
// orientation interpolator, both driven by the same u ∈ [0, 1]:
//   tip(u) = a + u·(b − a),   (A, C)(u) = move.joints_at(u)
//   q(u) = FiveAxisKinematics::joints_for_tip(tip(u), (A, C)(u))
// q(u) is a smooth curve in joint space. The planner runs it as one path:
// pieces of it (u0 → u1), each the cubic Hermite curve through q(u0) and
// q(u1) with q's own derivatives there (SegmentGeometry's curve), its path
// length Λ·(u1 − u0), Λ the length of q in X Y Z A C (mm and degrees
// alike). The pieces join with the same dq/ds = q'(u)/Λ: no corner, no
// velocity jump, wherever they meet. Their feed is F·Λ/Λ_F, Λ_F the move's
// length as RS274NGC measures feed — the tip's |b − a|, or where the tip
// stands still the rotary axes' travel (deg) — so the tip runs at F mm/s,
// or A and C at F deg/s on a move that only turns them, all along.
// A piece is halved until, at ¼, ½ and ¾ of it, the tip is within
// tip_tolerance_mm of tip(u) and the tool axis within
// orientation_tolerance_deg of the interpolator's (a Hermite piece's error
// is fourth order in its length: a few pieces a move, where joint lines
// needed hundreds), and dq/du changes by at most 5 % across it (the
// planner holds a piece to its joints' highest rate and bend: where they
// change fast, as near the pole, short pieces keep close to what the
// joints allow at each point).
#pragma once

#include <vector>

#include "common/result.h"
#include "kinematics/five_axis.h"
#include "kinematics/orientation_interpolation.h"
#include "path/segment.h"

namespace lcnc {

// A programmed straight tip move under TCP: the tip a → b, the orientation
// `move`, its joint path's length Λ and its feed length Λ_F (make()).
struct TcpMove {
  const FiveAxisKinematics* kin = nullptr;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  OrientationMove move;
  double length = 0.0;       // Λ: 0 when nothing moves
  double feed_length = 0.0;  // Λ_F (tcp_move_length)

  [[nodiscard]] static TcpMove make(const FiveAxisKinematics& kin, const Vec3& a, const Vec3& b,
                                    const OrientationMove& move);
  // The feed of its pieces for a programmed feed F: F·Λ/Λ_F.
  [[nodiscard]] double path_feed(double f) const { return feed_length > 0.0 ? f * length / feed_length : f; }

  // Joints at u, and dq/du (differences over kRateStepU, one-sided at the ends).
  [[nodiscard]] Pose joints_at(double u) const;
  [[nodiscard]] Pose rate_at(double u) const;
  [[nodiscard]] Vec3 tip_at(double u) const { return a + u * (b - a); }
};

// Λ: |b − a| when the tip moves, else the rotary axes' travel along the
// interpolator (deg); 0 when neither moves.
[[nodiscard]] double tcp_move_length(const Vec3& a, const Vec3& b, const OrientationMove& move);

// The curve pieces of u ∈ [u_from, u_to] of the move. Each copies
// `prototype` (feed, laser, path mode, line; a rapid stays a rapid, any
// other kind becomes a line) with start and end in joints, curve set and
// every piece but the first smooth_in. Error GcodeBadValue when a tolerance
// is not > 0 or when the move cannot be split within them (a C jump: a
// vector move through the pole).
[[nodiscard]] Result<std::vector<Segment>> tcp_curve_segments(const TcpMove& m, const Segment& prototype,
                                                              double tip_tolerance_mm,
                                                              double orientation_tolerance_deg,
                                                              double u_from = 0.0, double u_to = 1.0);

}  // namespace lcnc
