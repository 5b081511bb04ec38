// Tolerances and fixed factors of the G-code front end, in one place.
// Lengths are mm (after G20/G21 conversion), angles radians.
#pragma once

namespace lcnc::gcode {

inline constexpr double kMmPerInch = 25.4;

// A position counts as inside an axis' travel when within this of [min, max].
inline constexpr double kTravelTolMm = 1e-9;

// Two points of an arc count as the same (IJK full circle, R-form error) when
// closer than this in the plane. Tighter than any step (1 µm): it only absorbs
// floating-point noise of the unit and offset arithmetic.
inline constexpr double kSamePointMm = 1e-9;

// R form: the end point counts as reachable while half the chord exceeds |R|
// by at most this (LinuxCNC 2.9's 0.00005 in, in mm and inch programs
// alike, measured against its interpreter); such an arc is a half circle
// about the chord's midpoint, through both ends.
inline constexpr double kArcReachMm = 0.00005 * 25.4;

// IJK form, LinuxCNC 2.9's rule (interp_arc.cc, its default tolerances):
// the radius to the end may differ from the radius to the start by up to
// kArcRadiusAbsMm (G21) or kArcRadiusAbsIn (G20) — 2·√2 rounding units of
// 0.01 mm or 0.001 in, so an arc whose centre and end were rounded to the
// post's precision is accepted — or by more as long as the relative
// difference stays within kArcRadiusRel; never by more than 100 × the
// absolute tolerance. Such an arc is a spiral from one radius to the other
// (path/segment_geometry.h), as LinuxCNC moves it: it ends on its end point.
inline constexpr double kArcRadiusAbsMm = 2.0 * 0.01 * 1.4142135623730951;
inline constexpr double kArcRadiusAbsIn = 2.0 * 0.001 * 1.4142135623730951;
inline constexpr double kArcRadiusRel = 0.001;
inline constexpr double kArcRadiusHardFactor = 100.0;

// An arc whose radius (start or end) is below this has no direction.
inline constexpr double kArcMinRadiusMm = 1e-6;

// G codes are read as value × 10 (G61.1 -> 611): the scaled value must be
// this close to an integer. M codes and arc turns (P) must be this close to
// an integer. Both as LinuxCNC (read_g, read_integer_value).
inline constexpr double kCodeTenthsTol = 1e-3;
inline constexpr double kIntegerTol = 1e-4;

// Most full turns of one arc (P of G2/G3): a helix down a 100 mm deep hole
// at 0.01 mm a turn is 10,000 turns, finer than any laser or drill pitch; a
// larger P is a typo. (Long helices are also bounded by kMaxArcLengthMm.)
inline constexpr double kMaxArcTurns = 10000.0;

// --- bounds on values: every block must describe something a machine can
// finish. The planner clamps speeds to the axes' limits, so an upper bound on
// feed only refuses garbage; the lower bounds and the time bounds are what
// keep a typo (a missing decimal point, F in the wrong units) from becoming a
// move or dwell that never ends.

// Longest a single move or dwell may take: a day. No cutting, marking or
// waiting step of a job lasts that long; a block computed to take longer is a
// typo, and a controller must finish what it starts.
inline constexpr double kMaxBlockSeconds = 86400.0;

// Slowest feed (G94): one 1 µm step (the finest axis step) per minute, in
// mm/min, or deg/min for a move of rotary axes only. F0 stays allowed as "no
// feed yet" (a feed move with it is refused, as before); a feed between 0 and
// this is no process speed: the axis would stand still for minutes per step.
inline constexpr double kMinFeedPerMin = 0.001;

// Fastest feed accepted (G94, mm/min or deg/min; G93, 1/min): 10^7, that is
// 167 m/s or a move of 6 µs — far above any machine, whose axis limits the
// planner applies anyway. Above it a value is garbage (F1e300), not a feed.
inline constexpr double kMaxFeedPerMin = 1e7;

// Inverse time (G93): F = 1 / minutes the move takes, so kMaxBlockSeconds
// gives the smallest F (1/1440 per minute).
inline constexpr double kMinInverseTimeF = 60.0 / kMaxBlockSeconds;

// Largest |position| an axis may be sent to, in machine coordinates. Linear
// axes: 1 km, a hundred times the longest bed, so only garbage is refused
// where the travel check does not apply (tool-centre-point control checks
// joints later). Rotary axes, continuous ones included (no travel to check):
// 10^7 degrees, 27,777 turns — a spiral cut along a tube of 8 km at 100 mm
// diameter. Both keep positions far inside exact double and int64 step
// arithmetic.
inline constexpr double kMaxLinearPositionMm = 1e6;
inline constexpr double kMaxRotaryPositionDeg = 1e7;

// Longest arc (helix included), in mm of X Y Z path: 1 km, as the linear
// positions. Bounds what P turns × radius can make of one block.
inline constexpr double kMaxArcLengthMm = 1e6;

// Largest G64 blend (P) and naive-CAM (Q) tolerance: 10 mm. Laser and
// router paths are held to tenths of a millimetre; a tolerance beyond a
// centimetre lets corners be cut anywhere and is a unit or decimal typo.
inline constexpr double kMaxPathToleranceMm = 10.0;

// Longest line of a program, in bytes: 64 KiB. CAM output lines are under
// 200 bytes and LinuxCNC stops at 256; the bound keeps a file without line
// ends (/dev/zero, a binary) from growing the read buffer without end.
// It must stay below the line source's read chunk.
inline constexpr unsigned kMaxLineBytes = 64u * 1024u;

}  // namespace lcnc::gcode
