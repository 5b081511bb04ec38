// Named tolerances of the planner (one header per module, STYLE §4).
#pragma once

namespace lcnc::plan {

// Segments shorter than this (mm or deg) carry no motion of their own.
inline constexpr double kMinSegmentLength = 1e-9;

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
// An arc whose end lies this close (rad) after its start ends where it
// starts: a full turn (a rounding allowance — a circle mapped by a rotation
// comes back a few 1e-17 rad off; blends turn by at least kMinBlendAngle).
inline constexpr double kFullTurnAngle = 1e-12;
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

}  // namespace lcnc::plan
