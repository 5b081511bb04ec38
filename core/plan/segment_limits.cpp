#include "plan/segment_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "plan/tolerances.h"

namespace lcnc {
namespace {

constexpr double kPi = 3.14159265358979323846;

enum class Within : std::uint8_t { No, Yes, Unsure };

// Whether the angle of (a, b) lies in [0, sweep], decided without atan2 where
// the answer is certain: short sweeps (the blend arcs) by the signs of a and
// b and the cross product a·sin(sweep) − b·cos(sweep) = |(a, b)|·sin(sweep −
// angle), when it is further from 0 than kSure·(|a| + |b|), far beyond the
// rounding of atan2, sin and cos. Unsure otherwise: the caller asks atan2.
Within quick_within(double a, double b, double sweep, double cos_sweep, double sin_sweep) {
  constexpr double kSure = 1e-9;
  const double size = std::abs(a) + std::abs(b);
  if (!(sweep < 1.5) || size == 0.0 || (b != 0.0 && std::abs(b) < 1e-300)) return Within::Unsure;
  if (b < 0.0 || a <= 0.0) return Within::No;  // angle in (π/2, 2π): beyond the sweep
  const double cross = a * sin_sweep - b * cos_sweep;
  if (cross > kSure * size) return Within::Yes;
  if (cross < -kSure * size) return Within::No;
  return Within::Unsure;
}

// Range [lo, hi] of a·cos φ + b·sin φ for φ in [0, sweep].
void sinusoid_range(double a, double b, const SegmentGeometry& geo, double& lo, double& hi) {
  const double sweep = geo.sweep_rad();
  auto f = [&](double cos_phi, double sin_phi) { return a * cos_phi + b * sin_phi; };
  lo = std::min(f(1.0, 0.0), f(geo.cos_sweep(), geo.sin_sweep()));
  hi = std::max(f(1.0, 0.0), f(geo.cos_sweep(), geo.sin_sweep()));
  // maximum at atan2(b, a) + 2kπ, minimum half a turn later
  Within max_in = quick_within(a, b, sweep, geo.cos_sweep(), geo.sin_sweep());
  Within min_in = quick_within(-a, -b, sweep, geo.cos_sweep(), geo.sin_sweep());
  if (max_in == Within::Unsure || min_in == Within::Unsure) {
    double phi = std::atan2(b, a);
    if (phi < 0.0) phi += 2 * kPi;
    const double phi_min = phi >= kPi ? phi - kPi : phi + kPi;
    max_in = phi <= sweep ? Within::Yes : Within::No;
    min_in = phi_min <= sweep ? Within::Yes : Within::No;
  }
  if (max_in == Within::No && min_in == Within::No) return;
  const double amp = std::hypot(a, b);
  if (max_in == Within::Yes) hi = amp;
  if (min_in == Within::Yes) lo = -amp;
}

}  // namespace

SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                             const MachineConfig& machine) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  SegmentLimits lim;
  lim.v_max = kInf;
  lim.a_linear = kInf;
  const double L = geo.length();
  if (L <= plan::kMinSegmentLength) return {};
  // Linearly moving part of every axis (whole line; helix normal and rotary axes of an arc).
  Pose lin = (seg.end - seg.start) / L;
  if (geo.is_arc()) lin.head<3>() = geo.start_tangent().head<3>() -
                                    geo.plane_speed_ratio() * geo.w();
  for (int i = 0; i < kAxisCount; ++i) {
    const double k = std::abs(lin[i]);
    if (k <= 1e-15) continue;
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) return {};  // the reader rejects such moves first
    lim.v_max = std::min(lim.v_max, ax.max_velocity / k);
    lim.a_linear = std::min(lim.a_linear, ax.max_acceleration / k);
  }
  if (geo.is_arc() && geo.plane_speed_ratio() > 0.0) {
    const double rho = geo.plane_speed_ratio();
    lim.arc = true;
    lim.rho = rho;
    lim.radius = geo.radius();
    double a_n_max = kInf;
    for (int i = 0; i < 3; ++i) {
      const double ui = geo.u()[i], wi = geo.w()[i];
      const double g = std::hypot(ui, wi);
      if (g <= 1e-15) continue;
      const AxisConfig& ax = machine.axes[i];
      double t_lo, t_hi, n_lo, n_hi;
      sinusoid_range(wi, -ui, geo, t_lo, t_hi);   // t = −sin φ·u + cos φ·w
      sinusoid_range(-ui, -wi, geo, n_lo, n_hi);  // n = −cos φ·u − sin φ·w
      SegmentLimits::ArcAxis& x = lim.arc_axes[lim.arc_axis_count++];
      x.a_axis = ax.max_acceleration;
      const double by_norm = ax.max_acceleration / g;
      x.by_norm_sqr = by_norm * by_norm;
      x.a1_cap = std::sqrt(x.by_norm_sqr) / rho;  // the norm bound at a_n = 0
      x.n_lo = n_lo;
      x.n_hi = n_hi;
      // box bound, x = s·t over [x_lo, x_hi]: s = +1 speeding up, −1 slowing down
      for (int side = 0; side < 2; ++side) {
        const double x_lo = side == 0 ? t_lo : -t_hi, x_hi = side == 0 ? t_hi : -t_lo;
        x.den_hi[side] = x_hi > 1e-15 ? rho * x_hi : 0.0;
        x.den_lo[side] = x_lo < -1e-15 ? rho * -x_lo : 0.0;
      }
      const double t_abs = std::max(std::abs(t_lo), std::abs(t_hi));
      const double n_abs = std::max(std::abs(n_lo), std::abs(n_hi));
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
  return lim;
}

// Per axis the larger a_t either bound allows (both bounds are true):
//   by the norm  a1 = sqrt((amax_i/g_i)² − a_n²)/ρ
//   the box      largest a with −amax_i ≤ ρ·a·x + c ≤ amax_i for x in
//                [x_lo, x_hi], c in [min(0, a_n·n_lo), max(0, a_n·n_hi)]
// a_n anywhere in [0, a_n(v)]: the bound then holds at every speed ≤ v,
// and falls as v rises (the look-ahead relies on that).
Accel SegmentLimits::arc_at(double v) const noexcept {
  const double k2 = override_k * override_k;
  const double vp = rho * v * override_k;  // physical in-plane speed
  const double a_n = vp * vp / radius;
  auto box_bound = [](const ArcAxis& x, int side, double c_lo, double c_hi) {
    if (c_hi > x.a_axis || c_lo < -x.a_axis) return 0.0;
    double a = std::numeric_limits<double>::infinity();
    if (x.den_hi[side] != 0.0) a = std::min(a, (x.a_axis - c_hi) / x.den_hi[side]);
    if (x.den_lo[side] != 0.0) a = std::min(a, (x.a_axis + c_lo) / x.den_lo[side]);
    return std::max(0.0, a);
  };
  double accel = a_linear, decel = a_linear;
  for (int j = 0; j < arc_axis_count; ++j) {
    const ArcAxis& x = arc_axes[j];
    const double c_lo = std::min(0.0, a_n * x.n_lo), c_hi = std::max(0.0, a_n * x.n_hi);
    const double up = box_bound(x, 0, c_lo, c_hi), down = box_bound(x, 1, c_lo, c_hi);
    // a1 ≤ a1_cap (its value at a_n = 0): max(a1, b) is b when b ≥ a1_cap,
    // so the square root is taken only when a box bound falls below that
    double a1 = x.a1_cap;
    if (up < x.a1_cap || down < x.a1_cap || std::isnan(a_n))
      a1 = std::sqrt(std::max(0.0, x.by_norm_sqr - a_n * a_n)) / rho;
    accel = std::min(accel, std::max(a1, up));
    decel = std::min(decel, std::max(a1, down));
  }
  return {accel / k2, decel / k2};
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
