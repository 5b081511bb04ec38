// Named tolerances of the planner (one header per module).
#pragma once

#include "path/path_tolerances.h"

namespace lcnc::plan {

// Segments shorter than this (mm or deg) carry no motion of their own; an
// arc's end this close after its start is a full turn (path/path_tolerances.h).
using path::kFullTurnAngle;
using path::kMinSegmentLength;

// A corner fillet (fillet_transition) takes an arc as the circle of its start
// radius; an arc whose end radius differs by more than this (a spiral) is
// not filleted. A nanometre: far under a step, within the quantization
// margin of every blend's tolerance.
inline constexpr double kSpiralBlendMm = 1e-6;
// Share of an arc's in-plane acceleration budget the centripetal part may
// take at the arc's top speed; the rest, sqrt(1 − 0.995²) ≈ 10 %, stays for
// speeding up and slowing down on the arc. Curvature-limited arcs run at
// sqrt(0.995) ≈ 99.75 % of the speed that would use the whole budget.
inline constexpr double kArcNormalShare = 0.995;
// Corners turning less than this (rad) are tangent: no blend needed.
inline constexpr double kMinBlendAngle = 1e-7;
// Corners turning more than this (rad) reverse: no blend, the path stops.
inline constexpr double kMaxBlendAngle = 3.14159265358979323846 - 1e-6;
// Per-axis jump of the unit tangent (per unit of path) at a join: up to
// kTangentJump the join is tangent; beyond kMaxJunctionJump it is a corner
// that the path must stop at; between, the speed is held so that the jump in
// axis velocity is at most kJunctionJumpShare of one period's acceleration.
inline constexpr double kTangentJump = 1e-9;
inline constexpr double kMaxJunctionJump = 1e-3;
inline constexpr double kJunctionJumpShare = 0.1;
// Share of the machine's path tolerance that the jerk filter's own deviation
// may take (plan/jerk_filter.h): beyond it the planned acceleration is lowered.
// The rest stays for the corner blends of programs at the machine's P.
inline constexpr double kJerkFilterShare = 0.5;
// Velocities below this (mm/s) count as standing still.
inline constexpr double kMinVelocity = 1e-9;

// --- segment limits (segment_limits.cpp) ------------------------------------
// An axis' share of a unit direction (its travel per unit of path, or its
// component of an arc's tangent or normal) at or below this is no motion of
// that axis: it sets no limit (a division by it would overflow the limit).
inline constexpr double kNegligibleAxisShare = 1e-15;
// Slack, relative to the sinusoid's coefficients |a| + |b|, on the sign tests
// that decide whether an arc's sweep passes an axis' extremum: rounding in
// the arc's start direction must not hide the peak at its very end.
inline constexpr double kSweepExtremumRel = 1e-9;

// --- corner fillets (fillet_transition.cpp) ---------------------------------
// A line or arc whose ends differ by at most this (mm) along the plane's
// normal lies in the plane (rounding of G18/G19 positions, not a helix).
inline constexpr double kInPlaneMm = 1e-12;
// The fillet radius search steps down from the line–line estimate by 4×
// until it fits; below this fraction of the estimate it gives up (no blend).
inline constexpr double kFilletSearchFloor = 1e-6;
// The bisection then stops at this relative width of the radius bracket
// (the speed it allows, sqrt(a·r), within 5e-10 of the best), or after
// kFilletBisectionSteps halvings.
inline constexpr double kFilletRadiusRel = 1e-9;
inline constexpr int kFilletBisectionSteps = 60;

// --- corner shares and look-ahead (path_blender.cpp, lookahead.cpp) ---------
// A corner takes at most this share of a line and of an arc on each side
// (an arc trimmed to nothing would read as a full circle).
inline constexpr double kCornerLineShare = 0.5;
inline constexpr double kCornerArcShare = 0.45;
// Under tool-centre-point control, the share of a corner's tolerance that
// goes to X Y Z when rotary axes move across it (the rest to the rotary
// axes' tip motion).
inline constexpr double kTcpXyzShare = 0.5;
// A speed profile fits a segment's length L when it needs at most
// L·(1 + this): the rounding of v² sums must not reject the exact fit.
inline constexpr double kProfileFitRel = 1e-12;

}  // namespace lcnc::plan
