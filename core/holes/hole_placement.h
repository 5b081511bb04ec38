// Places a hole program (hole frame, hole_processes.h) into machine joints:
// at the hole's constant A and C the map from the hole frame to the joints'
// X Y Z is rigid,
//   joints_xyz = T·local,   T = kin.tip_to_joints(A, C) · program.frame
// so lines stay lines and arcs stay arcs of the same radius:
// * T keeps the hole axis on machine Z (table-table, or head-head at A = 0):
//   G17 arcs and helices stay G17 arcs and helices;
// * otherwise flat arcs become Plane::Free arcs about T·ẑ, and helices,
//   which a Free-plane Segment cannot carry (path/segment_geometry.h), become
//   chords whose sag is at most chord_tolerance_mm.
// Events keep their meaning: before_segment is remapped to the placed
// segment index.
#pragma once

#include "common/result.h"
#include "holes/hole_processes.h"
#include "kinematics/five_axis.h"

namespace lcnc {

[[nodiscard]] Result<HoleProgram> place_hole(const HoleProgram& program,
                                             const FiveAxisKinematics& kin,
                                             double chord_tolerance_mm);

}  // namespace lcnc
