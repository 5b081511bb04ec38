// Re-timing of an orientation move; the method is in orientation_retiming.h.
#include "kinematics/orientation_retiming.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcnc {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Share of each axis' acceleration given to the curvature term X''·u̇².
constexpr double kCurvatureShare = 0.5;

double limit_ratio(double limit, double derivative) { return derivative > 0.0 ? limit / derivative : kInf; }

}  // namespace

RetimedLaw retime(const OrientationMove& move, const RotaryLimits& lim, double max_u_rate,
                  double max_u_accel) {
  const int n = kin::kRetimeSamples;
  const double du = 1.0 / n;
  std::vector<RotaryJoints> j(n + 1);
  for (int i = 0; i <= n; ++i) j[i] = move.joints_at(i * du);

  std::vector<double> v_lim(n + 1), acc(n + 1);
  for (int i = 0; i <= n; ++i) {
    const RotaryJoints& lo = j[std::max(i - 1, 0)];
    const RotaryJoints& hi = j[std::min(i + 1, n)];
    const double span = (std::min(i + 1, n) - std::max(i - 1, 0)) * du;
    const double d1a = std::abs(hi.a_deg - lo.a_deg) / span;
    const double d1c = std::abs(hi.c_deg - lo.c_deg) / span;
    double d2a = 0.0, d2c = 0.0;
    if (i > 0 && i < n) {
      d2a = std::abs(hi.a_deg - 2.0 * j[i].a_deg + lo.a_deg) / (du * du);
      d2c = std::abs(hi.c_deg - 2.0 * j[i].c_deg + lo.c_deg) / (du * du);
    }
    v_lim[i] = std::min({max_u_rate, limit_ratio(lim.a_max_velocity_deg_s, d1a),
                         limit_ratio(lim.c_max_velocity_deg_s, d1c),
                         std::sqrt(limit_ratio(kCurvatureShare * lim.a_max_accel_deg_s2, d2a)),
                         std::sqrt(limit_ratio(kCurvatureShare * lim.c_max_accel_deg_s2, d2c))});
    acc[i] = std::min({max_u_accel, limit_ratio((1.0 - kCurvatureShare) * lim.a_max_accel_deg_s2, d1a),
                       limit_ratio((1.0 - kCurvatureShare) * lim.c_max_accel_deg_s2, d1c)});
  }
  // Forward from rest, backward to rest (squared rates, docs/design.md §5.2).
  std::vector<double> v_sqr(n + 1);
  v_sqr[0] = 0.0;
  for (int i = 0; i < n; ++i)
    v_sqr[i + 1] = std::min(v_lim[i + 1] * v_lim[i + 1], v_sqr[i] + 2.0 * acc[i] * du);
  v_sqr[n] = 0.0;
  for (int i = n; i > 0; --i) v_sqr[i - 1] = std::min(v_sqr[i - 1], v_sqr[i] + 2.0 * acc[i] * du);

  RetimedLaw law;
  law.t_s_.resize(n + 1);
  law.rate_.resize(n + 1);
  law.t_s_[0] = 0.0;
  for (int i = 0; i <= n; ++i) law.rate_[i] = std::sqrt(v_sqr[i]);
  for (int i = 0; i < n; ++i) {
    const double sum = law.rate_[i] + law.rate_[i + 1];
    law.t_s_[i + 1] = law.t_s_[i] + (sum > 0.0 ? 2.0 * du / sum : kInf);
  }
  return law;
}

double RetimedLaw::u_at(double t) const noexcept {
  if (t_s_.size() < 2 || t <= 0.0) return 0.0;
  if (t >= t_s_.back()) return 1.0;
  const auto it = std::upper_bound(t_s_.begin(), t_s_.end(), t);
  const auto i = static_cast<std::size_t>(it - t_s_.begin()) - 1;
  const double du = 1.0 / static_cast<double>(t_s_.size() - 1);
  const double v0 = rate_[i], v1 = rate_[i + 1];
  const double a = (v1 * v1 - v0 * v0) / (2.0 * du);  // constant between grid points
  const double tau = t - t_s_[i];
  return std::min(1.0, static_cast<double>(i) * du + v0 * tau + 0.5 * a * tau * tau);
}

double RetimedLaw::peak_u_rate() const noexcept {
  double peak = 0.0;
  for (double r : rate_) peak = std::max(peak, r);
  return peak;
}

OrientationReport evaluate(const OrientationMove& move, const RetimedLaw& law, double dt) {
  return evaluate(
      move, law.duration_s(), [&law](double t) { return law.u_at(t); }, dt);
}

}  // namespace lcnc
