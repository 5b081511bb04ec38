// The geometry of a 5-axis machine (X Y Z A C): its variant and the offsets
// that five_axis.h's forward and inverse kinematics use. A plain header, so
// that the machine config can hold it (the [kinematics] table).
#pragma once

#include <cstdint>

#include "geom/pose.h"

namespace lcnc {

enum class MachineVariant : std::uint8_t {
  HeadHead,    // A and C turn the head; the workpiece stands still
  TableTable,  // A and C turn the workpiece on a trunnion table; the tool is fixed
};

// Offsets and pivot lengths (mm), the machine config's [kinematics]
// (machine/machine_config.h). The defaults describe a mid-size machine of the
// default travel (docs/design.md §4).
struct FiveAxisGeometry {
  MachineVariant variant = MachineVariant::HeadHead;
  // Head-head: from the head reference point P (on the C axis) to the A
  // pivot, in the C-turned frame. Default: A pivot 80 mm below P, on the axis.
  Vec3 head_c_to_a_mm = Vec3(0.0, 0.0, -80.0);
  // Head-head: from the A pivot to the tool tip (focus) along −k, > 0.
  double head_pivot_length_mm = 120.0;
  // Table-table: a point of the A trunnion axis, machine frame.
  Vec3 table_a_pivot_mm = Vec3(500.0, 225.0, 100.0);
  // Table-table: from that point to the C table's centre (the workpiece
  // origin), in the trunnion frame (equal to the machine frame at A = 0).
  Vec3 table_c_offset_mm = Vec3(0.0, 0.0, 50.0);
};

enum class OrientationMethod : std::uint8_t {
  JointLinear,   // A, C linear in u
  Vector,        // great circle, joints on the start's branch
  PoleSmoothed,  // great circle, snapped through the pole within tolerance
};

// Tool-centre-point control of G-code programs (kinematics/tcp_program.h),
// the machine config's [kinematics] tcp keys: with it on, a program's X Y Z
// are the tool tip in the workpiece frame and A C the rotary joints; every
// move is turned into joint moves whose tip follows the programmed line
// while the tool axis follows `orientation`.
struct TcpConfig {
  bool enabled = false;
  OrientationMethod orientation = OrientationMethod::PoleSmoothed;
  double orientation_tolerance_deg = 0.01;  // PoleSmoothed's ε, and the joint pieces' axis error
  double tip_tolerance_mm = 0.001;          // the tip's distance from the programmed path
};

}  // namespace lcnc
