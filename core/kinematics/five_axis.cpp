// 5-axis forward and inverse kinematics; the formulas are in five_axis.h.
#include "kinematics/five_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

#include "common/number_text.h"
#include "kinematics/kinematics_tolerances.h"

namespace lcnc {

namespace {

Eigen::Matrix3d rot_x(double deg) {
  return Eigen::AngleAxisd(deg * kRadPerDeg, Vec3::UnitX()).toRotationMatrix();
}
Eigen::Matrix3d rot_z(double deg) {
  return Eigen::AngleAxisd(deg * kRadPerDeg, Vec3::UnitZ()).toRotationMatrix();
}

}  // namespace

RotaryLimits rotary_limits_from(const MachineConfig& config) {
  RotaryLimits l;
  if (const AxisConfig& a = config.axis(Axis::A); a.present) {
    l.a_min_deg = a.min;
    l.a_max_deg = a.max;
    l.a_max_velocity_deg_s = a.max_velocity;
    l.a_max_accel_deg_s2 = a.max_acceleration;
  }
  if (const AxisConfig& c = config.axis(Axis::C); c.present) {
    l.c_max_velocity_deg_s = c.max_velocity;
    l.c_max_accel_deg_s2 = c.max_acceleration;
  }
  return l;
}

FiveAxisKinematics kinematics_from(const MachineConfig& config) {
  return FiveAxisKinematics(config.kinematics, rotary_limits_from(config));
}

Vec3 tool_axis(double a_deg, double c_deg) noexcept {
  const double sa = std::sin(a_deg * kRadPerDeg), ca = std::cos(a_deg * kRadPerDeg);
  const double sc = std::sin(c_deg * kRadPerDeg), cc = std::cos(c_deg * kRadPerDeg);
  return {sa * sc, -sa * cc, ca};
}

bool on_pole(const Vec3& axis) noexcept {
  return std::hypot(axis.x(), axis.y()) < kin::kPoleSin * axis.norm() && axis.z() > 0.0;
}

std::array<RotaryJoints, 2> rotary_solutions(const Vec3& k) noexcept {
  const Vec3 n = k.normalized();
  // atan2 of the horizontal and vertical parts: accurate near the pole,
  // where acos(k_z) loses half the digits.
  const double a = std::atan2(std::hypot(n.x(), n.y()), n.z()) / kRadPerDeg;
  if (on_pole(n)) return {RotaryJoints{0.0, 0.0}, RotaryJoints{0.0, 0.0}};
  const double c = wrap_360(std::atan2(n.x(), -n.y()) / kRadPerDeg);
  return {RotaryJoints{a, c}, RotaryJoints{-a, wrap_360(c + 180.0)}};
}

double nearest_turn(double c_deg, double ref_deg) noexcept {
  return c_deg - 360.0 * std::round((c_deg - ref_deg) / 360.0);
}

double tip_lever_mm(const FiveAxisGeometry& g) noexcept {
  return g.variant == MachineVariant::HeadHead ? g.head_c_to_a_mm.norm() + g.head_pivot_length_mm
                                               : kTableLeverMm;
}

double wrap_360(double c_deg) noexcept {
  double w = std::fmod(c_deg, 360.0);
  if (w < 0.0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;  // fmod of −tiny + 360 can round to 360
}

double angle_between_deg(const Vec3& a, const Vec3& b) noexcept {
  return std::atan2(a.cross(b).norm(), a.dot(b)) / kRadPerDeg;
}

Result<RotaryJoints> choose_rotary(const Vec3& axis, const RotaryJoints& previous,
                                   const RotaryLimits& limits) {
  auto sols = rotary_solutions(axis);
  if (on_pole(axis)) {
    // C is free: keep it; A = 0 (both solutions coincide).
    sols[0].c_deg = sols[1].c_deg = previous.c_deg;
  }
  const RotaryJoints* best = nullptr;
  double best_time = 0.0, best_sum = 0.0;
  RotaryJoints cand[2];
  for (int i = 0; i < 2; ++i) {
    cand[i] = {sols[i].a_deg, nearest_turn(sols[i].c_deg, previous.c_deg)};
    if (cand[i].a_deg < limits.a_min_deg || cand[i].a_deg > limits.a_max_deg) continue;
    const double da = std::abs(cand[i].a_deg - previous.a_deg);
    const double dc = std::abs(cand[i].c_deg - previous.c_deg);
    const double time = std::max(da / limits.a_max_velocity_deg_s, dc / limits.c_max_velocity_deg_s);
    const double sum = da + dc;
    if (best == nullptr || time < best_time || (time == best_time && sum < best_sum)) {
      best = &cand[i];
      best_time = time;
      best_sum = sum;
    }
  }
  if (best == nullptr)
    return make_error(ErrorCode::GcodeBeyondTravel, "tool axis needs A = ±" + six_digits(sols[0].a_deg) +
                                                        "°; allowed A " + six_digits(limits.a_min_deg) +
                                                        " … " + six_digits(limits.a_max_deg) + "°");
  return *best;
}

FiveAxisKinematics::FiveAxisKinematics(FiveAxisGeometry geometry, RotaryLimits limits)
    : geometry_(std::move(geometry)), limits_(limits) {}

Eigen::Isometry3d FiveAxisKinematics::tip_to_joints(const RotaryJoints& r) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  if (geometry_.variant == MachineVariant::HeadHead) {
    // P = tip − Rz(C)·(c_to_a + Rx(A)·(−L·ẑ)): a pure translation.
    const Vec3 tip_from_p =
        rot_z(r.c_deg) *
        (geometry_.head_c_to_a_mm + rot_x(r.a_deg) * Vec3(0.0, 0.0, -geometry_.head_pivot_length_mm));
    t.translation() = -tip_from_p;
  } else {
    // P = a_pivot + Rx(−A)·(c_offset + Rz(−C)·tip_w)
    t.linear() = rot_x(-r.a_deg) * rot_z(-r.c_deg);
    t.translation() = geometry_.table_a_pivot_mm + rot_x(-r.a_deg) * geometry_.table_c_offset_mm;
  }
  return t;
}

Pose FiveAxisKinematics::joints_for_tip(const Vec3& tip_mm, const RotaryJoints& r) const {
  Pose j = Pose::Zero();
  j.head<3>() = tip_to_joints(r) * tip_mm;
  j[index(Axis::A)] = r.a_deg;
  j[index(Axis::C)] = r.c_deg;
  return j;
}

ToolPose FiveAxisKinematics::forward(const Pose& joints) const {
  const RotaryJoints r = rotary_of(joints);
  ToolPose p;
  p.tip_mm = tip_to_joints(r).inverse() * Vec3(joints.head<3>());
  p.axis = tool_axis(r);
  return p;
}

std::array<Pose, 2> FiveAxisKinematics::inverse_solutions(const ToolPose& target) const {
  const auto sols = rotary_solutions(target.axis);
  return {joints_for_tip(target.tip_mm, sols[0]), joints_for_tip(target.tip_mm, sols[1])};
}

Result<Pose> FiveAxisKinematics::inverse(const ToolPose& target, const Pose& previous) const {
  Result<RotaryJoints> r = choose_rotary(target.axis, rotary_of(previous), limits_);
  if (!r) return r.error();
  return joints_for_tip(target.tip_mm, *r);
}

}  // namespace lcnc
