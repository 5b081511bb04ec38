// Orientation interpolators and their evaluation; the method and formulas
// are in orientation_interpolation.h.
#include "kinematics/orientation_interpolation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "common/number_text.h"

namespace lcnc {

namespace {

// Noise allowance of the monotone C unwrap (deg): a raw azimuth this far on
// the wrong side of C0 is rounding, not a turn of 360°.
constexpr double kUnwrapSlackDeg = 1e-6;
// Rounding allowance of the A-range check (deg).
constexpr double kARangeSlackDeg = 1e-9;
// Half-step of rate_at()'s central difference (of u).
constexpr double kRateStepU = 1e-7;
// Step back from a sample exactly on the pole to read the C it arrives with.
constexpr double kPoleNudgeU = 1e-6;

// |A| of an axis (deg), accurate near the pole.
double tilt_deg(const Vec3& k) { return std::atan2(std::hypot(k.x(), k.y()), k.z()) / kRadPerDeg; }

// C of an axis on the branch b (sign of A), in (−180, 180].
double raw_c_deg(const Vec3& k, double b) { return std::atan2(b * k.x(), -b * k.y()) / kRadPerDeg; }

// Quintic smoothstep: 0 → 1 with zero first and second derivatives at both ends.
double smoothstep5(double s) { return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s); }

}  // namespace

const char* method_name(OrientationMethod method) noexcept {
  switch (method) {
    case OrientationMethod::JointLinear: return "joint-linear";
    case OrientationMethod::Vector: return "vector";
    case OrientationMethod::PoleSmoothed: return "pole-smoothed";
  }
  return "unknown";
}

Result<OrientationMove> OrientationMove::between_joints(OrientationMethod method, const RotaryJoints& start,
                                                        const RotaryJoints& end, const RotaryLimits& limits,
                                                        double tolerance_deg) {
  OrientationMove m;
  m.method_ = method;
  m.start_ = start;
  m.end_ = end;
  m.k1_ = tool_axis(end);
  m.tolerance_deg_ = tolerance_deg;
  return m.finish(limits);
}

Result<OrientationMove> OrientationMove::to_axis(OrientationMethod method, const RotaryJoints& start,
                                                 const Vec3& end_axis, const RotaryLimits& limits,
                                                 double tolerance_deg) {
  if (!(end_axis.allFinite() && end_axis.norm() > 0.0))
    return make_error(ErrorCode::GcodeBadValue, "tool axis must be a finite, non-zero vector");
  Result<RotaryJoints> end = choose_rotary(end_axis, start, limits);
  if (!end) return end.error();
  OrientationMove m;
  m.method_ = method;
  m.start_ = start;
  m.end_ = *end;
  m.k1_ = end_axis.normalized();
  m.tolerance_deg_ = tolerance_deg;
  return m.finish(limits);
}

Result<OrientationMove> OrientationMove::finish(const RotaryLimits& limits) {
  const double tolerance_rad = tolerance_deg_ * kRadPerDeg;
  if (!(tolerance_rad >= 0.0 && std::isfinite(tolerance_rad)))
    return make_error(ErrorCode::GcodeBadValue,
                      "orientation tolerance = " + six_digits(tolerance_deg_) + "°; allowed ≥ 0");
  k0_ = tool_axis(start_);
  const Vec3 z = Vec3::UnitZ();
  theta_rad_ = std::atan2(k0_.cross(k1_).norm(), k0_.dot(k1_));
  if (theta_rad_ > std::numbers::pi - kin::kAntipodalRad)
    return make_error(ErrorCode::GcodeBadValue,
                      "tool axes 180° apart: no unique great circle between them; "
                      "program an intermediate orientation");
  if (theta_rad_ > kin::kSameAxisRad) {
    n_ = k0_.cross(k1_).normalized();
    t0_ = n_.cross(k0_);
  } else {
    theta_rad_ = 0.0;
    n_ = Vec3::Zero();
  }
  sigma_ = n_.z() < 0.0 ? -1.0 : 1.0;

  // Closest approach of the arc to the pole.
  const Vec3 zp = z - n_.z() * n_;
  pole_interior_ = false;
  if (theta_rad_ > 0.0 && zp.norm() > 1e-15) {
    const Vec3 m = zp.normalized();
    const double alpha = std::atan2(m.dot(t0_), m.dot(k0_));
    if (alpha >= 0.0 && alpha <= theta_rad_) {
      pole_interior_ = true;
      alpha_m_rad_ = alpha;
      pole_dist_rad_ = std::atan2(std::abs(n_.z()), zp.norm());
      snap_axis_ = m.cross(z).norm() > 0.0 ? Vec3(m.cross(z).normalized()) : Vec3(n_.cross(m));
    }
  }
  if (!pole_interior_) {
    const double d0 = tilt_deg(k0_) * kRadPerDeg, d1 = tilt_deg(k1_) * kRadPerDeg;
    pole_dist_rad_ = std::min(d0, d1);
    alpha_m_rad_ = d0 <= d1 ? 0.0 : theta_rad_;
  }

  // Branch and C at the start. On the pole C is free: take the branch whose
  // departure C is nearest to the C the machine stands at.
  if (method_ != OrientationMethod::JointLinear) {
    if (!on_pole(k0_)) {
      branch0_ = start_.a_deg < 0.0 ? -1.0 : 1.0;
      c0_raw_deg_ = raw_c_deg(k0_, branch0_);
    } else {
      Vec3 k = k1_;
      for (double u = kPoleNudgeU; u < 1.0 && theta_rad_ > 0.0; u *= 2.0) {
        k = ideal_axis_at(u);
        if (!on_pole(k)) break;
      }
      const double plus = raw_c_deg(k, 1.0), minus = raw_c_deg(k, -1.0);
      const bool use_plus = std::abs(nearest_turn(plus, start_.c_deg) - start_.c_deg) <=
                            std::abs(nearest_turn(minus, start_.c_deg) - start_.c_deg);
      branch0_ = use_plus ? 1.0 : -1.0;
      c0_raw_deg_ = use_plus ? plus : minus;
    }
    c0_deg_ = nearest_turn(c0_raw_deg_, start_.c_deg);
  }

  // Snap through the pole (PoleSmoothed, δ ≤ ε, pole well inside the arc).
  snapped_ = false;
  if (method_ == OrientationMethod::PoleSmoothed && pole_interior_ && pole_dist_rad_ <= tolerance_rad) {
    const double margin = std::min(alpha_m_rad_, theta_rad_ - alpha_m_rad_);
    if (margin >= kin::kMinPoleMarginRad) {
      snapped_ = true;
      core_rad_ = std::min(kin::kPoleCoreRad, margin / 2.0);
      // C along the meridian: read it just after the pole, on the flipped branch.
      const Vec3 k = smoothed_axis_at((alpha_m_rad_ + core_rad_ / 2.0) / theta_rad_);
      c_core_deg_ = raw_c_deg(k, -branch0_);
      // Unwrap reference: C sampled along the move, each on the turn nearest
      // the previous sample.
      c_table_.assign(kin::kCurveSamples + 1, c0_deg_);
      double prev = c0_deg_;
      for (int i = 0; i <= kin::kCurveSamples; ++i) {
        const double u = static_cast<double>(i) / kin::kCurveSamples;
        const double alpha = u * theta_rad_;
        double c = c_core_deg_;
        if (std::abs(alpha - alpha_m_rad_) > core_rad_) c = raw_c_deg(smoothed_axis_at(u), branch_at(u));
        prev = c_table_[i] = (i == 0) ? c0_deg_ : nearest_turn(c, prev);
      }
      // Keep the snap only where it helps: within the A range (it flips the
      // sign of A) and no slower under the limits than the exact path. A pole
      // near an end leaves a short taper whose C motion can cost more than
      // the pole pass saves.
      const double rate_snapped = first_a_outside(limits) < 0.0 ? max_u_rate(limits) : -1.0;
      snapped_ = false;
      if (rate_snapped >= max_u_rate(limits)) {
        snapped_ = true;
      } else {
        c_table_.clear();
      }
    }
  }

  if (const double u = first_a_outside(limits); u >= 0.0) {
    const double a = joints_at(u).a_deg;
    return make_error(ErrorCode::GcodeBeyondTravel,
                      std::string(method_name(method_)) + " orientation path reaches A = " + six_digits(a) +
                          "° at u = " + six_digits(u) + "; allowed A " + six_digits(limits.a_min_deg) +
                          " … " + six_digits(limits.a_max_deg) + "°");
  }
  return *this;
}

double OrientationMove::first_a_outside(const RotaryLimits& limits) const {
  for (int i = 0; i <= kin::kCurveSamples; ++i) {
    const double u = static_cast<double>(i) / kin::kCurveSamples;
    const double a = joints_at(u).a_deg;
    if (a < limits.a_min_deg - kARangeSlackDeg || a > limits.a_max_deg + kARangeSlackDeg) return u;
  }
  return -1.0;
}

double OrientationMove::arc_deg() const noexcept { return theta_rad_ / kRadPerDeg; }
double OrientationMove::pole_distance_deg() const noexcept { return pole_dist_rad_ / kRadPerDeg; }

Vec3 OrientationMove::ideal_axis_at(double u) const {
  if (theta_rad_ == 0.0) return k0_;
  const double alpha = std::clamp(u, 0.0, 1.0) * theta_rad_;
  return std::cos(alpha) * k0_ + std::sin(alpha) * t0_;
}

double OrientationMove::pole_weight(double alpha_rad) const noexcept {
  const double d = std::abs(alpha_rad - alpha_m_rad_);
  if (d <= core_rad_) return 1.0;
  if (d >= 2.0 * core_rad_) return 0.0;
  return 1.0 - smoothstep5((d - core_rad_) / core_rad_);
}

Vec3 OrientationMove::smoothed_axis_at(double u) const {
  Vec3 k = ideal_axis_at(u);
  if (!snapped_) return k;
  const double angle = pole_dist_rad_ * pole_weight(std::clamp(u, 0.0, 1.0) * theta_rad_);
  return Eigen::AngleAxisd(angle, snap_axis_) * k;
}

double OrientationMove::branch_at(double u) const noexcept {
  return (snapped_ && u * theta_rad_ > alpha_m_rad_) ? -branch0_ : branch0_;
}

double OrientationMove::vector_c_at(double u) const {
  const Vec3 k = ideal_axis_at(u);
  if (on_pole(k)) {
    // Exactly on the pole: the C the path arrives with (or leaves with at u = 0).
    return u <= 0.0 ? c0_deg_ : vector_c_at(std::max(0.0, u - kPoleNudgeU));
  }
  // Along a great circle missing the pole C is monotone with sign σ = sign(n_z)
  // and turns less than 360° over the arc: C = C0 + σ·((σ·(raw − raw0)) mod 360).
  const double d = sigma_ * (raw_c_deg(k, branch0_) - c0_raw_deg_);
  return c0_deg_ + sigma_ * (wrap_360(d + kUnwrapSlackDeg) - kUnwrapSlackDeg);
}

RotaryJoints OrientationMove::joints_at(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  if (method_ == OrientationMethod::JointLinear)
    return {start_.a_deg + u * (end_.a_deg - start_.a_deg), start_.c_deg + u * (end_.c_deg - start_.c_deg)};
  if (!snapped_) return {branch0_ * tilt_deg(ideal_axis_at(u)), vector_c_at(u)};
  const Vec3 k = smoothed_axis_at(u);
  const double b = branch_at(u);
  const double x = u * kin::kCurveSamples;
  const int i = std::min(static_cast<int>(x), kin::kCurveSamples - 1);
  const double ref = c_table_[i] + (x - i) * (c_table_[i + 1] - c_table_[i]);
  const bool core = std::abs(u * theta_rad_ - alpha_m_rad_) <= core_rad_;
  const double c = core ? c_core_deg_ : raw_c_deg(k, b);
  return {b * tilt_deg(k), nearest_turn(c, ref)};
}

Vec3 OrientationMove::axis_at(double u) const { return tool_axis(joints_at(u)); }

RotaryJoints OrientationMove::rate_at(double u) const {
  const double u0 = std::clamp(u - kRateStepU, 0.0, 1.0), u1 = std::clamp(u + kRateStepU, 0.0, 1.0);
  const RotaryJoints j0 = joints_at(u0), j1 = joints_at(u1);
  return {(j1.a_deg - j0.a_deg) / (u1 - u0), (j1.c_deg - j0.c_deg) / (u1 - u0)};
}

double OrientationMove::max_u_rate(const RotaryLimits& limits) const {
  const int n = kin::kCurveSamples;
  const double du = 1.0 / n;
  double d1a = 0.0, d1c = 0.0, d2a = 0.0, d2c = 0.0;
  RotaryJoints prev2 = joints_at(0.0), prev = prev2;
  for (int i = 1; i <= n; ++i) {
    const RotaryJoints j = joints_at(i * du);
    d1a = std::max(d1a, std::abs(j.a_deg - prev.a_deg) / du);
    d1c = std::max(d1c, std::abs(j.c_deg - prev.c_deg) / du);
    if (i >= 2) {
      d2a = std::max(d2a, std::abs(j.a_deg - 2.0 * prev.a_deg + prev2.a_deg) / (du * du));
      d2c = std::max(d2c, std::abs(j.c_deg - 2.0 * prev.c_deg + prev2.c_deg) / (du * du));
    }
    prev2 = prev;
    prev = j;
  }
  double rate = std::numeric_limits<double>::infinity();
  if (d1a > 0.0) rate = std::min(rate, limits.a_max_velocity_deg_s / d1a);
  if (d1c > 0.0) rate = std::min(rate, limits.c_max_velocity_deg_s / d1c);
  if (d2a > 0.0) rate = std::min(rate, std::sqrt(limits.a_max_accel_deg_s2 / d2a));
  if (d2c > 0.0) rate = std::min(rate, std::sqrt(limits.c_max_accel_deg_s2 / d2c));
  return rate;
}

double TimeLaw::u_at(double t) const noexcept {
  const double r = std::clamp(ramp_fraction, 1e-9, 0.5);
  const double T = duration_s;
  if (t <= 0.0) return 0.0;
  if (t >= T) return 1.0;
  const double v_max = 1.0 / (T * (1.0 - r));  // du/dt at cruise
  const double ta = r * T;
  const double acc = v_max / ta;
  if (t < ta) return 0.5 * acc * t * t;
  if (t <= T - ta) return 0.5 * acc * ta * ta + v_max * (t - ta);
  return 1.0 - 0.5 * acc * (T - t) * (T - t);
}

bool OrientationReport::within(const RotaryLimits& l) const noexcept {
  return peak_a_vel_deg_s <= l.a_max_velocity_deg_s && peak_c_vel_deg_s <= l.c_max_velocity_deg_s &&
         peak_a_acc_deg_s2 <= l.a_max_accel_deg_s2 && peak_c_acc_deg_s2 <= l.c_max_accel_deg_s2;
}

OrientationReport evaluate(const OrientationMove& move, const TimeLaw& law, double dt) {
  return evaluate(
      move, law.duration_s, [&law](double t) { return law.u_at(t); }, dt);
}

OrientationReport evaluate(const OrientationMove& move, double duration_s,
                           const std::function<double(double)>& u_of_t, double dt) {
  OrientationReport rep;
  const auto n = static_cast<std::size_t>(std::ceil(duration_s / dt));
  rep.samples.resize(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    OrientationSample& s = rep.samples[i];
    s.t_s = static_cast<double>(i) * dt;
    s.u = s.t_s >= duration_s ? 1.0 : u_of_t(s.t_s);
    const RotaryJoints j = move.joints_at(s.u);
    s.a_deg = j.a_deg;
    s.c_deg = j.c_deg;
    s.error_deg = angle_between_deg(tool_axis(j), move.ideal_axis_at(s.u));
  }
  // At rest before and after: the neighbours of the ends are the ends.
  for (std::size_t i = 0; i <= n; ++i) {
    OrientationSample& s = rep.samples[i];
    const OrientationSample& lo = rep.samples[i == 0 ? 0 : i - 1];
    const OrientationSample& hi = rep.samples[i == n ? n : i + 1];
    s.a_vel_deg_s = (hi.a_deg - lo.a_deg) / (2.0 * dt);
    s.c_vel_deg_s = (hi.c_deg - lo.c_deg) / (2.0 * dt);
    s.a_acc_deg_s2 = (hi.a_deg - 2.0 * s.a_deg + lo.a_deg) / (dt * dt);
    s.c_acc_deg_s2 = (hi.c_deg - 2.0 * s.c_deg + lo.c_deg) / (dt * dt);
    rep.max_error_deg = std::max(rep.max_error_deg, s.error_deg);
    rep.peak_a_vel_deg_s = std::max(rep.peak_a_vel_deg_s, std::abs(s.a_vel_deg_s));
    rep.peak_c_vel_deg_s = std::max(rep.peak_c_vel_deg_s, std::abs(s.c_vel_deg_s));
    rep.peak_a_acc_deg_s2 = std::max(rep.peak_a_acc_deg_s2, std::abs(s.a_acc_deg_s2));
    rep.peak_c_acc_deg_s2 = std::max(rep.peak_c_acc_deg_s2, std::abs(s.c_acc_deg_s2));
  }
  return rep;
}

}  // namespace lcnc
