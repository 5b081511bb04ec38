// Tool-orientation interpolation between two orientations of one move
// (docs/design.md §5.6, Shao (2022) §4 and its Fig. 16), parametrised by u ∈ [0, 1].
//
// The ideal orientation is the great circle (slerp) from k0 to k1:
//   k*(u) = cos(uΘ)·k0 + sin(uΘ)·t0,   Θ = ∠(k0, k1),  t0 = n × k0,  n = k0×k1/|k0×k1|
// Three interpolators (OrientationMethod):
//
// * JointLinear: A and C linear in u between the start and end joints, as a
//   G1 with A and C words moves. Tool axis k(A(u), C(u)); its error against
//   k*(u) is largest of the three (tens of degrees when C turns far at a
//   large A, Shao (2022): 44°).
// * Vector: k(u) = k*(u) exactly; the joints by the inverse of five_axis.h on
//   the start's branch (sign of A) with C continuous. Along a great circle
//   that misses the pole, C turns monotonically at
//     dC/dα = n_z / sin²θ     (θ = |A|, α = uΘ the arc angle)
//   which near the pole peaks at 1/sin δ, δ the distance of the arc from the
//   pole: C swings ~180° within a few δ of arc. On a path through A = 0 that
//   is a C-speed spike far beyond the axis (Shao 2022 Fig. 16).
// * PoleSmoothed (the improved vector interpolation): when the arc passes
//   the pole at δ ≤ the orientation tolerance ε (default 0.01°), the great
//   circle is turned by δ·w(α) about its own direction of travel t_m at the
//   closest point m, so that it runs exactly through the pole:
//     k(u) = Rot(t_m, δ·w(α))·k*(u),   w = 1 for |α − α_m| ≤ c, smoothstep
//     (quintic, C²) down to 0 over a further c, c = min(10°, margin/2)
//   A rotation by δ·w moves any vector by at most δ·w ≤ ε, so the error stays
//   within ε. Through the pole the path is a meridian: A passes linearly
//   through 0 and changes sign (the other inverse solution) and C holds;
//   the taper shifts the path laterally by ≤ δ over degrees of arc, so C
//   moves by ~δ/c ≪ 1°. Both the C spike and the A "V" at the pole (A
//   acceleration ~ω²/δ on the A ≥ 0 branch) are gone.
//   The snap is kept only when its path stays within the A range (it flips
//   the sign of A) and max_u_rate() is no lower than the exact path's (a
//   pole near an end of the move leaves a short taper, whose C motion can
//   cost more than the pole pass saves).
//   When δ > ε (or the snap is not kept) the orientation cannot leave the
//   great circle by enough to reach the pole; the path stays exact and C is
//   kept within its limits by re-timing instead: retime()
//   (orientation_retiming.h) slows only the pole pass; max_u_rate() is the
//   cruder constant-rate bound (the feed limit of the whole move).
//
// Ends on the pole (A = 0): C is free there, so the move starts (ends) with
// the C its path leaves (enters) the pole with; start_joints() may differ in
// C from the joints the machine stands at. The planner turns C at the pole
// (the orientation does not change) before the move.
//
// Units: degrees for joints and errors, u dimensionless, time in s.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/result.h"
#include "kinematics/five_axis.h"
#include "kinematics/five_axis_geometry.h"
#include "kinematics/kinematics_tolerances.h"

namespace lcnc {

[[nodiscard]] const char* method_name(OrientationMethod method) noexcept;

class OrientationMove {
 public:
  // From the joints at the start to programmed end joints (JointLinear moves
  // exactly there; the others to the end joints' orientation, on the branch
  // and C turn their path arrives with: end_joints()).
  [[nodiscard]] static Result<OrientationMove> between_joints(
      OrientationMethod method, const RotaryJoints& start, const RotaryJoints& end,
      const RotaryLimits& limits, double tolerance_deg = kin::kOrientationToleranceDeg);
  // From the joints at the start to a programmed tool axis (unit or not).
  // JointLinear ends at choose_rotary(end_axis, start).
  [[nodiscard]] static Result<OrientationMove> to_axis(OrientationMethod method, const RotaryJoints& start,
                                                       const Vec3& end_axis, const RotaryLimits& limits,
                                                       double tolerance_deg = kin::kOrientationToleranceDeg);

  [[nodiscard]] OrientationMethod method() const noexcept { return method_; }
  // Joints at u ∈ [0, 1] (clamped); C continuous over the move.
  [[nodiscard]] RotaryJoints joints_at(double u) const;
  // The interpolator's tool axis at u: tool_axis(joints_at(u)).
  [[nodiscard]] Vec3 axis_at(double u) const;
  // The ideal (great-circle) axis at u.
  [[nodiscard]] Vec3 ideal_axis_at(double u) const;
  [[nodiscard]] RotaryJoints start_joints() const { return joints_at(0.0); }
  [[nodiscard]] RotaryJoints end_joints() const { return joints_at(1.0); }
  // Arc angle Θ of the ideal great circle (deg).
  [[nodiscard]] double arc_deg() const noexcept;
  // Closest approach of the ideal arc to the pole (deg): the smallest |A|
  // along k*(u).
  [[nodiscard]] double pole_distance_deg() const noexcept;
  // PoleSmoothed only: true when the path was snapped through the pole.
  [[nodiscard]] bool pole_snapped() const noexcept { return snapped_; }
  // d(A, C)/du at u (deg per unit of u), by central difference: for the
  // planner's per-axis limits pointwise, |dC/dt| = |dC/du|·du/dt.
  [[nodiscard]] RotaryJoints rate_at(double u) const;
  // Re-timing: the highest constant du/dt (1/s) at which |dA/dt|, |dC/dt|
  // and |d²A/dt²|, |d²C/dt²| stay within the limits, from the joint curves
  // sampled at kin::kCurveSamples points (so resolved to Θ/4096 of arc).
  // Infinity when neither axis moves.
  [[nodiscard]] double max_u_rate(const RotaryLimits& limits) const;

 private:
  OrientationMove() = default;
  [[nodiscard]] Result<OrientationMove> finish(const RotaryLimits& limits);
  // The first sampled u whose A is outside the range; −1 when none.
  [[nodiscard]] double first_a_outside(const RotaryLimits& limits) const;
  [[nodiscard]] Vec3 smoothed_axis_at(double u) const;
  [[nodiscard]] double branch_at(double u) const noexcept;
  [[nodiscard]] double vector_c_at(double u) const;
  [[nodiscard]] double pole_weight(double alpha_rad) const noexcept;

  OrientationMethod method_ = OrientationMethod::Vector;
  RotaryJoints start_{}, end_{};                          // JointLinear: the joints it moves between
  double tolerance_deg_ = kin::kOrientationToleranceDeg;  // PoleSmoothed: ε
  Vec3 k0_ = Vec3::UnitZ(), k1_ = Vec3::UnitZ();
  Vec3 t0_ = Vec3::UnitX();     // direction of travel at k0 (unit)
  Vec3 n_ = Vec3::Zero();       // unit normal of the great circle (0 if Θ = 0)
  double theta_rad_ = 0.0;      // Θ
  double branch0_ = 1.0;        // sign of A at the start
  double sigma_ = 1.0;          // sign of dC/du on a great circle (n_z)
  double c0_deg_ = 0.0;         // C at u = 0 (departure C when the start is on the pole)
  double c0_raw_deg_ = 0.0;     // the raw azimuth C0 is congruent to
  double pole_dist_rad_ = 0.0;  // δ
  bool pole_interior_ = false;  // the closest approach lies inside the arc
  double alpha_m_rad_ = 0.0;    // arc angle of the closest approach
  // Snap (PoleSmoothed).
  bool snapped_ = false;
  Vec3 snap_axis_ = Vec3::UnitX();  // t_m: rotation axis of the snap
  double core_rad_ = 0.0;           // half-width of the core and of each taper
  double c_core_deg_ = 0.0;         // C along the meridian through the pole
  std::vector<double> c_table_;     // C at kin::kCurveSamples + 1 points (unwrap reference)
};

// A time law for evaluation: u(t) with a trapezoidal du/dt, from rest to
// rest in duration_s, accelerating over ramp_fraction·duration_s and braking
// over the same (0 < ramp_fraction ≤ 0.5).
struct TimeLaw {
  double duration_s = 1.0;
  double ramp_fraction = 0.25;

  [[nodiscard]] double u_at(double t_s) const noexcept;
};

struct OrientationSample {
  double t_s = 0.0, u = 0.0;
  double a_deg = 0.0, c_deg = 0.0;
  double a_vel_deg_s = 0.0, c_vel_deg_s = 0.0;
  double a_acc_deg_s2 = 0.0, c_acc_deg_s2 = 0.0;
  double error_deg = 0.0;  // ∠(interpolated axis, great-circle axis) at the same u
};

struct OrientationReport {
  std::vector<OrientationSample> samples;
  double max_error_deg = 0.0;
  double peak_a_vel_deg_s = 0.0, peak_c_vel_deg_s = 0.0;
  double peak_a_acc_deg_s2 = 0.0, peak_c_acc_deg_s2 = 0.0;

  // Peaks within the limits' velocities and accelerations.
  [[nodiscard]] bool within(const RotaryLimits& limits) const noexcept;
};

// Samples a move every sample_dt_s along the time law: joints, their speeds
// and accelerations (central differences; at rest before and after the
// move) and the orientation error against the great circle.
[[nodiscard]] OrientationReport evaluate(const OrientationMove& move, const TimeLaw& law, double sample_dt_s);
// The same for any time law u(t) from rest at t = 0 to rest at duration_s
// (orientation_retiming.h).
[[nodiscard]] OrientationReport evaluate(const OrientationMove& move, double duration_s,
                                         const std::function<double(double)>& u_of_t, double sample_dt_s);

}  // namespace lcnc
