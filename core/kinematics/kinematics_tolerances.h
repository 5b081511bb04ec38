// Named tolerances of the 5-axis kinematics and orientation interpolation
// (one header per module). Angles in degrees unless the name says rad.
#pragma once

namespace lcnc::kin {

// sin(A) below this (≈ 6·10⁻⁶ °) counts as A = 0: the tool axis is on the
// pole and C is undefined, so C keeps the value it had (or the value the
// neighbouring orientation needs).
inline constexpr double kPoleSin = 1e-7;
// Default orientation tolerance of the pole-smoothed interpolator: the largest
// angle between its tool axis and the ideal great-circle axis.
inline constexpr double kOrientationToleranceDeg = 0.01;
// Pole-smoothed interpolator: half-width of the core (exactly through the
// pole) and of each taper (rad, along the great circle). Wide enough that the
// lateral shift of at most the tolerance spreads over degrees of path, so
// the C motion it causes is ~tolerance / core ≈ 10⁻³ of the path speed.
inline constexpr double kPoleCoreRad = 0.1745329251994330;  // 10°
// A pole closer than this (rad, along the arc) to an end of the move is not
// snapped through: the taper would be too short. Re-timing
// (orientation_retiming.h) then keeps C within its limits instead.
inline constexpr double kMinPoleMarginRad = 0.0087266462599716;  // 0.5°
// Two orientations closer than this (rad) are the same: the move does not
// reorient. Two closer than π − this to antipodal have no unique great circle.
inline constexpr double kSameAxisRad = 1e-12;
inline constexpr double kAntipodalRad = 1e-6;
// Samples of a move's joint curves used to unwrap C, to check the A range
// and to bound dC/du (max_u_rate).
inline constexpr int kCurveSamples = 4096;
// TCP subdivision: most bisection levels (2^24 pieces) before giving up.
inline constexpr int kMaxTcpDepth = 24;

// The machine's A and C this close to a program's are the program's own
// (rounding only): its move starts from them, deg.
inline constexpr double kSameJointDeg = 1e-9;

}  // namespace lcnc::kin
