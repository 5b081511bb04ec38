#include "plan/segment_limits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plan/tolerances.h"

namespace lcnc {
namespace {

// Range [lo, hi] of a·cos φ + b·sin φ for φ in [0, sweep].
void sinusoid_range(double a, double b, double sweep, double& lo, double& hi) {
  constexpr double kPi = 3.14159265358979323846;
  auto f = [&](double phi) { return a * std::cos(phi) + b * std::sin(phi); };
  lo = std::min(f(0.0), f(sweep));
  hi = std::max(f(0.0), f(sweep));
  const double amp = std::hypot(a, b);
  // maximum at atan2(b, a) + 2kπ, minimum half a turn later
  double phi = std::atan2(b, a);
  if (phi < 0.0) phi += 2 * kPi;
  for (double p = phi; p <= sweep; p += 2 * kPi) hi = amp;
  for (double p = phi >= kPi ? phi - kPi : phi + kPi; p <= sweep; p += 2 * kPi) lo = -amp;
}

// Largest a ≥ 0 with lo ≤ ρ·a·s·t + c ≤ hi for every t in [t_lo, t_hi],
// c ∈ [c_lo, c_hi]: the box bound (s = +1 speeding up, −1 slowing down).
double box_bound(double amax, double rho, double sign, double t_lo, double t_hi, double c_lo,
                 double c_hi) {
  // with x = s·t ranging over [x_lo, x_hi]
  const double x_lo = sign > 0 ? t_lo : -t_hi, x_hi = sign > 0 ? t_hi : -t_lo;
  double a = std::numeric_limits<double>::infinity();
  if (c_hi > amax || c_lo < -amax) return 0.0;
  if (x_hi > 1e-15) a = std::min(a, (amax - c_hi) / (rho * x_hi));
  if (x_lo < -1e-15) a = std::min(a, (amax + c_lo) / (rho * -x_lo));
  return std::max(0.0, a);
}

}  // namespace

SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                             const MachineConfig& machine) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  SegmentLimits lim{kInf, kInf};
  const double L = geo.length();
  if (L <= plan::kMinSegmentLength) return {0.0, 0.0};
  // Linearly moving part of every axis (whole line; helix normal and rotary axes of an arc).
  Pose lin = (seg.end - seg.start) / L;
  if (geo.is_arc()) lin.head<3>() = geo.tangent(0.0).head<3>() -
                                    geo.plane_speed_ratio() * geo.w();
  for (int i = 0; i < kAxisCount; ++i) {
    const double k = std::abs(lin[i]);
    if (k <= 1e-15) continue;
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) return {0.0, 0.0};  // the reader rejects such moves first
    lim.v_max = std::min(lim.v_max, ax.max_velocity / k);
    lim.a_max = std::min(lim.a_max, ax.max_acceleration / k);
  }
  lim.a_linear = lim.a_max;
  if (geo.is_arc() && geo.plane_speed_ratio() > 0.0) {
    const double rho = geo.plane_speed_ratio();
    const double sweep = geo.sweep_rad();
    lim.arc = true;
    lim.rho = rho;
    lim.radius = geo.radius();
    double a_n_max = kInf;
    for (int i = 0; i < 3; ++i) {
      const double ui = geo.u()[i], wi = geo.w()[i];
      lim.g[i] = std::hypot(ui, wi);
      if (lim.g[i] <= 1e-15) continue;
      const AxisConfig& ax = machine.axes[i];
      lim.a_axis[i] = ax.max_acceleration;
      sinusoid_range(wi, -ui, sweep, lim.t_lo[i], lim.t_hi[i]);  // t = −sin φ·u + cos φ·w
      sinusoid_range(-ui, -wi, sweep, lim.n_lo[i], lim.n_hi[i]); // n = −cos φ·u − sin φ·w
      const double t_abs = std::max(std::abs(lim.t_lo[i]), std::abs(lim.t_hi[i]));
      const double n_abs = std::max(std::abs(lim.n_lo[i]), std::abs(lim.n_hi[i]));
      lim.v_max = std::min(lim.v_max, ax.max_velocity / (rho * t_abs + std::abs(lin[i])));
      if (n_abs > 1e-15) a_n_max = std::min(a_n_max, ax.max_acceleration / n_abs);
    }
    // centripetal limit: (ρ·v)²/r · N_i ≤ share · amax_i
    if (std::isfinite(a_n_max))
      lim.v_max = std::min(lim.v_max,
                           std::sqrt(plan::kArcNormalShare * a_n_max * geo.radius()) / rho);
  }
  if (!std::isfinite(lim.v_max)) return {};
  // Planned at the highest feed override (DESIGN §5.5): at K the speed is K·v
  // and the acceleration K²·a.
  const double k = machine.max_feed_override;
  lim.override_k = k;
  lim.v_max /= k;
  lim.a_max = lim.accel_at(lim.v_max);
  return lim;
}

double SegmentLimits::tangential(double v, double sign) const noexcept {
  const double k2 = override_k * override_k;
  if (!arc) return a_linear / k2;
  const double vp = rho * v * override_k;  // physical in-plane speed
  const double a_n = vp * vp / radius;
  double a_t = a_linear;
  for (int i = 0; i < 3; ++i) {
    if (g[i] <= 1e-15) continue;
    // the larger a_t either bound allows (both bounds are true)
    const double by_norm = a_axis[i] / g[i];
    const double a1 = std::sqrt(std::max(0.0, by_norm * by_norm - a_n * a_n)) / rho;
    // a_n anywhere in [0, a_n(v)]: the bound then holds at every speed ≤ v,
    // and falls as v rises (the look-ahead relies on that)
    const double a2 = box_bound(a_axis[i], rho, sign, t_lo[i], t_hi[i],
                                std::min(0.0, a_n * n_lo[i]), std::max(0.0, a_n * n_hi[i]));
    a_t = std::min(a_t, std::max(a1, a2));
  }
  return a_t / k2;
}

double target_speed(const Segment& seg, const SegmentGeometry& geo, const SegmentLimits& lim) {
  switch (seg.kind) {
    case MotionKind::Rapid: return lim.v_max;
    case MotionKind::Dwell: return 0.0;
    case MotionKind::Linear:
    case MotionKind::Arc:
      if (seg.duration_s > 0.0) return std::min(lim.v_max, geo.length() / seg.duration_s);
      return std::min(lim.v_max, seg.feed_mm_s);
  }
  return 0.0;
}

}  // namespace lcnc
