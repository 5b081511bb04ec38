// Places a hole program (hole frame, hole_processes.h) into machine joints:
// at the hole's constant A and C the map from the hole frame to the joints'
// X Y Z is rigid,
//   joints_xyz = T·local,   T = kin.tip_to_joints(A, C) · program.frame
// so lines stay lines and arcs stay arcs of the same radius, sweep and turns:
// * T keeps the hole axis on machine Z (table-table, or head-head at A = 0):
//   G17 arcs and helices stay G17 arcs and helices;
// * otherwise they become Plane::Free arcs and helices about T·ẑ — one
//   segment each, as in the hole frame, so a helix runs at its feed without
//   the stops that chords would need at their corners.
// Events keep their meaning: before_segment is remapped to the placed
// segment index.
#pragma once

#include "common/result.h"
#include "holes/hole_processes.h"
#include "kinematics/five_axis.h"

namespace lcnc {

[[nodiscard]] Result<HoleProgram> place_hole(const HoleProgram& program, const FiveAxisKinematics& kin);

}  // namespace lcnc
