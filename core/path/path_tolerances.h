// Tolerances of a path's geometry (path/segment_geometry.h), shared by the
// G-code front end and the planner (plan/tolerances.h names them too).
#pragma once

namespace lcnc::path {

// Segments shorter than this (mm or deg) carry no motion of their own.
inline constexpr double kMinSegmentLength = 1e-9;

// An arc whose end lies this close (rad) after its start ends where it
// starts: a full turn (a rounding allowance — a circle mapped by a rotation
// comes back a few 1e-17 rad off; blends turn by at least
// plan::kMinBlendAngle).
inline constexpr double kFullTurnAngle = 1e-12;

}  // namespace lcnc::path
