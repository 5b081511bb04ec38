// Named tolerances of the planner (one header per module, STYLE §4).
#pragma once

namespace lcnc::plan {

// Segments shorter than this (mm or deg) carry no motion of their own.
inline constexpr double kMinSegmentLength = 1e-9;
// Share of an arc plane axis's acceleration given to the centripetal and to
// the tangential component: each gets a_max/√2, so their vector sum ≤ a_max.
inline constexpr double kArcAccelShare = 0.70710678118654752;
// Velocities below this (mm/s) count as standing still.
inline constexpr double kMinVelocity = 1e-9;

}  // namespace lcnc::plan
