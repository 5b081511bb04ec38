// Arc geometry shared by the reader (travel check) and check_program (path
// length, bounding box), on the Segment representation of an arc.
//
// In plane coordinates (a, b) = (first, second) axis of Plane — (X, Y) for
// G17, (Z, X) for G18, (Y, Z) for G19 — the triple (first, second, normal) is
// right-handed, so counter-clockwise seen from +normal is the positive angle
// from a toward b for all three planes. With θs, θe the angles of start and
// end about the centre:
//   sweep = (θe − θs) mod 2π  (G3)   or   (θs − θe) mod 2π  (G2),
// taken in (0, 2π] so that end == start is one full turn, plus
// 2π · extra_turns. Arc length over X Y Z (helix):
//   L = sqrt((r · sweep)² + Δn²),  r the radius at the start;
// for a spiral (the radius to the end differs) the planner's bound
//   L = sqrt((r_max · sweep)² + Δr² + Δn²)   (path/segment_geometry.h).
#pragma once

#include <array>

#include "geom/pose.h"
#include "path/segment.h"

namespace lcnc::gcode {

// Indices into Pose / Vec3 of (first, second, normal) axis of a plane.
[[nodiscard]] constexpr std::array<int, 3> arc_plane_axes(Plane p) noexcept {
  switch (p) {
    case Plane::ZX: return {2, 0, 1};
    case Plane::YZ: return {1, 2, 0};
    case Plane::XY:
    default: return {0, 1, 2};
  }
}

// Angle the arc turns through, radians, in (0, 2π] + 2π · extra_turns.
[[nodiscard]] double arc_sweep_rad(const Segment& arc);

// Length of the arc over X Y Z (helix included).
[[nodiscard]] double arc_length_mm(const Segment& arc);

// Bounding box over X Y Z of the arc: its end points and the in-plane extreme
// points (centre ± r along either plane axis) that the arc passes.
void arc_bounds(const Segment& arc, Vec3& lo, Vec3& hi);

}  // namespace lcnc::gcode
