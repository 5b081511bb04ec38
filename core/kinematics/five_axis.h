// 5-axis kinematics of the X Y Z A C laser machine (docs/design.md §5.6, Shao (2022) §4):
// forward (joints → tool tip + tool axis in the workpiece frame) and inverse
// (tip + axis → joints) for a head-head and a table-table variant, and the
// choice of the inverse solution for the shortest, limit-respecting motion.
//
// Tool axis. Both variants share one orientation map, so a program of tool
// vectors means the same on either machine. The unit tool axis k points from
// the tool tip toward the head (the beam travels along −k); in the workpiece
// frame
//   k(A, C) = Rz(C)·Rx(A)·ẑ = (sin A·sin C, −sin A·cos C, cos A)
// A tilts about X, C turns about Z. At A = 0, k = ẑ for every C: the
// singularity (C undefined). The two inverse solutions of an axis k ≠ ẑ are
//   A = +acos(k_z),  C = atan2( k_x, −k_y)
//   A = −acos(k_z),  C = atan2(−k_x,  k_y)   (the first C + 180°)
//
// Head-head: the workpiece frame is the machine frame. X Y Z place the head's
// reference point P on the C axis; the A pivot sits at Rz(C)·c_to_a from P
// and the tool tip pivot_length L from the A pivot along −k:
//   tip = P + Rz(C)·(c_to_a + Rx(A)·(−L·ẑ))
// Table-table: the tool is fixed along machine +Z with its tip at P = (X, Y,
// Z). The A trunnion axis (parallel to X) passes through a_pivot (machine
// frame); the C table's centre sits at c_offset from it in the trunnion's
// frame; the workpiece frame has its origin there and turns with the table.
// Positive A and C turn the table the negative way about X and Z, so that the
// tool seen from the workpiece follows k(A, C) above:
//   machine point = a_pivot + Rx(−A)·(c_offset + Rz(−C)·w)
//   tip_w = Rz(C)·(Rx(A)·(P − a_pivot) − c_offset),  k_w = Rz(C)·Rx(A)·ẑ
// (On a machine whose table turns the other way, negate the joint in the
// axis' drive direction, not here.)
//
// Joints are a Pose (X Y Z A B C; B stays 0). C is continuous: the inverse
// returns it unwrapped, as the nearest turn to the previous C, so the motion
// never goes the long way round; the axis' wrap shows it modulo 360.
// Units: mm, degrees (docs/design.md §4).
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Geometry>

#include "common/result.h"
#include "geom/pose.h"
#include "kinematics/five_axis_geometry.h"
#include "machine/machine_config.h"

namespace lcnc {

// Range and dynamics of A and C (deg, deg/s, deg/s²). C is continuous.
struct RotaryLimits {
  double a_min_deg = -95.0;
  double a_max_deg = 95.0;
  double a_max_velocity_deg_s = 180.0;
  double a_max_accel_deg_s2 = 1800.0;
  double c_max_velocity_deg_s = 360.0;
  double c_max_accel_deg_s2 = 3600.0;
};

// A and C of a machine config (its [axes.A] and [axes.C]); the defaults above
// for an axis the config lacks.
[[nodiscard]] RotaryLimits rotary_limits_from(const MachineConfig& config);

// Tool tip and unit tool axis (tip → head) in the workpiece frame.
struct ToolPose {
  Vec3 tip_mm = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
};

struct RotaryJoints {
  double a_deg = 0.0;
  double c_deg = 0.0;  // unwrapped (continuous)
};

// k(A, C) above.
[[nodiscard]] Vec3 tool_axis(double a_deg, double c_deg) noexcept;
[[nodiscard]] inline Vec3 tool_axis(const RotaryJoints& j) noexcept { return tool_axis(j.a_deg, j.c_deg); }
// The two solutions of a unit axis: [0] with A ≥ 0, [1] with A ≤ 0, C in
// [0, 360). On the pole (sin A < kin::kPoleSin) both have A = 0 and C = 0.
[[nodiscard]] std::array<RotaryJoints, 2> rotary_solutions(const Vec3& axis) noexcept;
// c + 360·n nearest to ref (deg).
[[nodiscard]] double nearest_turn(double c_deg, double ref_deg) noexcept;
// c modulo 360 in [0, 360).
[[nodiscard]] double wrap_360(double c_deg) noexcept;
// Angle between two vectors (deg), accurate also for tiny angles.
[[nodiscard]] double angle_between_deg(const Vec3& a, const Vec3& b) noexcept;
// True when the axis is on the pole (A = 0, C undefined).
[[nodiscard]] bool on_pole(const Vec3& axis) noexcept;

// The rotary joints for `axis` nearest to `previous`: of the two solutions,
// each with C on its nearest turn, the one within the A range that takes the
// least time at the axes' max velocities (ties: the smaller |ΔA| + |ΔC|). On
// the pole C stays at previous.c_deg. Error GcodeBeyondTravel when neither
// solution's A is within range.
[[nodiscard]] Result<RotaryJoints> choose_rotary(const Vec3& axis, const RotaryJoints& previous,
                                                 const RotaryLimits& limits);

class FiveAxisKinematics {
 public:
  explicit FiveAxisKinematics(FiveAxisGeometry geometry = {}, RotaryLimits limits = {});

  [[nodiscard]] const FiveAxisGeometry& geometry() const noexcept { return geometry_; }
  [[nodiscard]] const RotaryLimits& limits() const noexcept { return limits_; }

  // Joints → tip and axis in the workpiece frame.
  [[nodiscard]] ToolPose forward(const Pose& joints) const;
  // The joints that put the tip at tip_mm with the rotary axes at `rotary`
  // (the axis is then tool_axis(rotary)): the linear part of the inverse, and
  // the step of tool-centre-point control that keeps the tip on the path
  // while A and C move.
  [[nodiscard]] Pose joints_for_tip(const Vec3& tip_mm, const RotaryJoints& rotary) const;
  // Both inverse solutions (rotary_solutions order; C in [0, 360)).
  [[nodiscard]] std::array<Pose, 2> inverse_solutions(const ToolPose& target) const;
  // The inverse solution nearest to `previous` (choose_rotary).
  [[nodiscard]] Result<Pose> inverse(const ToolPose& target, const Pose& previous) const;
  // For a constant A and C: the rigid map from workpiece (tip) coordinates to
  // the joints' X Y Z, joints_xyz = T·tip. Lines and arcs keep their shape
  // under it (hole patterns, constant-orientation moves).
  [[nodiscard]] Eigen::Isometry3d tip_to_joints(const RotaryJoints& rotary) const;

 private:
  FiveAxisGeometry geometry_;
  RotaryLimits limits_;
};

// The machine's kinematics: its [kinematics] geometry, its A and C limits.
[[nodiscard]] FiveAxisKinematics kinematics_from(const MachineConfig& config);

// How far the tool tip may be from the rotary axes: a turn of A or C by δ
// (rad) moves it by at most this × δ. Head-head: the A pivot's offset from
// the C axis plus the pivot length. Table-table: a workpiece point up to
// kTableLeverMm from the table's axes (the tip is anywhere on the part).
inline constexpr double kTableLeverMm = 1000.0;
[[nodiscard]] double tip_lever_mm(const FiveAxisGeometry& g) noexcept;

// A pose's X Y Z under a rigid map (tip_to_joints), its rotary axes as they are.
[[nodiscard]] inline Pose transformed(const Eigen::Isometry3d& t, const Pose& p) {
  Pose q = p;
  q.head<3>() = t * Vec3(p.head<3>());
  return q;
}

[[nodiscard]] inline RotaryJoints rotary_of(const Pose& joints) noexcept {
  return {joints[index(Axis::A)], joints[index(Axis::C)]};
}

}  // namespace lcnc
