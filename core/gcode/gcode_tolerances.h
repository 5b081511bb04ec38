// Tolerances and fixed factors of the G-code front end, in one place
// (STYLE §4). Lengths are mm (after G20/G21 conversion), angles radians.
#pragma once

namespace lcnc::gcode {

inline constexpr double kMmPerInch = 25.4;

// A position counts as inside an axis' travel when within this of [min, max].
inline constexpr double kTravelTolMm = 1e-9;

// Two points of an arc count as the same (IJK full circle, R-form error) when
// closer than this in the plane. Tighter than any step (1 µm): it only absorbs
// floating-point noise of the unit and offset arithmetic.
inline constexpr double kSamePointMm = 1e-9;

// R form: the end point counts as reachable when 2|R| >= chord - this·max(1, chord)
// (LinuxCNC allows a tiny error for semicircles the same way).
inline constexpr double kArcReachRel = 1e-6;

// IJK form, LinuxCNC's rule (interp_arc.cc): the radius to the end may differ
// from the radius to the start by up to kArcRadiusAbsMm, or by more as long as
// the relative difference stays within kArcRadiusRel; never by more than
// kArcRadiusHardAbsMm (100 × the absolute tolerance).
inline constexpr double kArcRadiusAbsMm = 0.002;
inline constexpr double kArcRadiusRel = 0.001;
inline constexpr double kArcRadiusHardAbsMm = 100.0 * kArcRadiusAbsMm;

// An arc whose radius (start or end) is below this has no direction.
inline constexpr double kArcMinRadiusMm = 1e-6;

// G codes are read as value × 10 (G61.1 -> 611): the scaled value must be
// this close to an integer. M codes and arc turns (P) must be this close to
// an integer. Both as LinuxCNC (read_g, read_integer_value).
inline constexpr double kCodeTenthsTol = 1e-3;
inline constexpr double kIntegerTol = 1e-4;

// Most full turns one arc word may add (P of G2/G3): a helix of 100,000
// turns is beyond any hole; a larger P is a typo.
inline constexpr double kMaxArcTurns = 100000.0;

}  // namespace lcnc::gcode
