#include "plan/segment_limits.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "plan/tolerances.h"

namespace lcnc {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Range [lo, hi] of a·cos φ + b·sin φ for φ in [0, sweep] (amp = sqrt(a² +
// b²)): the values at the two ends, widened to amp where the maximum (at
// the angle α of (a, b)) lies inside, to −amp where the minimum (α + π)
// does. For sweep < π (every blend) that is decided without atan2 and
// without branching on the data (lines and arcs alternate, the signs are
// anyone's): α ∈ [0, sweep] ⇔ b ≥ 0 and a·sin(sweep) − b·cos(sweep) ≥ 0.
// Within kSweepExtremumRel·(|a| + |b|) of either boundary it counts as inside — the
// extremum is then that close to an end, so the range widens by a relative
// 1e-18 at most, to the safe side.
void sinusoid_range(double a, double b, double amp, const SegmentGeometry& geo, double& lo, double& hi) {
  const double cs = geo.cos_sweep(), sn = geo.sin_sweep();
  const double end = a * cs + b * sn;
  lo = std::min(a, end);
  hi = std::max(a, end);
  if (geo.sweep_rad() < kPi) {
    const double tol = plan::kSweepExtremumRel * (std::abs(a) + std::abs(b));
    const double cross = a * sn - b * cs;
    hi = (b >= -tol && cross >= -tol) ? amp : hi;
    lo = (b <= tol && cross <= tol) ? -amp : lo;
    return;
  }
  double phi = std::atan2(b, a);
  if (phi < 0.0) phi += 2 * kPi;
  const double phi_min = phi >= kPi ? phi - kPi : phi + kPi;
  if (phi <= geo.sweep_rad()) hi = amp;
  if (phi_min <= geo.sweep_rad()) lo = -amp;
}

}  // namespace

namespace {

// Per linear axis an arc moves in: what its two bounds need.
struct ArcAxis {
  double a_axis = 0.0;                                    // amax_i
  double g = 0.0;                                         // sqrt(u_i² + w_i²)
  double t_lo = 0.0, t_hi = 0.0, n_lo = 0.0, n_hi = 0.0;  // ranges over the sweep
  std::array<double, 2> t_end{}, n_end{};                 // t_i, n_i at the two ends of the sweep
};

// The box bounds of one axis as lines in a_n, x = ±t over the sweep (+
// speeding up, − slowing down):
//   a ≤ (amax − a_n·n_hi) / (ρ·x_hi)    (x_hi > 0)
//   a ≤ (amax + a_n·n_lo) / (ρ·(−x_lo))  (x_lo < 0)
// with a_n = c·x: a line falls in x where the centripetal part hinders
// (SegmentLimits takes it at the top of a phase's speeds), rises where it
// helps (taken at the bottom). A side the tangent never
// points to gives no line (p = ∞). Speeding up, x = t: x_hi = t_hi, x_lo =
// t_lo; slowing down the two swap sides (x_hi = −t_lo, x_lo = −t_hi), so one
// division per side of t serves both.
void box_lines(const ArcAxis& x, double rho, double c, ArcAxisBound& b) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  b.p_up = b.p_down = {kInf, kInf};
  b.q_up = b.q_down = {0.0, 0.0};
  const double q_hi = x.n_hi * c, q_lo = -x.n_lo * c;
  if (x.t_hi > plan::kNegligibleAxisShare) {  // speeding up: its first line; slowing down: its second
    const double per = 1.0 / (rho * x.t_hi);
    b.p_up[0] = b.p_down[1] = x.a_axis * per;
    b.q_up[0] = q_hi * per;
    b.q_down[1] = q_lo * per;
  }
  if (x.t_lo < -plan::kNegligibleAxisShare) {  // speeding up: its second line; slowing down: its first
    const double per = 1.0 / (rho * -x.t_lo);
    b.p_up[1] = b.p_down[0] = x.a_axis * per;
    b.q_up[1] = q_lo * per;
    b.q_down[0] = q_hi * per;
  }
}

// The box at the two ends of a short sweep (≤ kEndBoxSweep). Per bound σ
// (+1: the axis's acceleration ≤ amax, −1: ≥ −amax) the axis sees
// f(φ) = σ·(ρ·a_t·t_i(φ) + a_n·n_i(φ)), a sinusoid in φ of amplitude at most
// g·(ρ·|a_t| + a_n); over [0, w] it exceeds the larger of its two end values
// by at most amplitude·(1 − cos(w/2)) ≤ amplitude·μ/g, μ = g·w²/8. So an a
// (a_t = s·a, s = +1 speeding up, −1 slowing down) keeps the axis within
// amax over the whole sweep when at both ends e
//
//     ρ·a·(σ·s·t_e + μ) + a_n·(σ·n_e + μ) ≤ amax.
//
// Where σ·s·t_e + μ > 0 that is a line in x = v², a ≤ p − q·x (q < 0 where
// the centripetal part helps, as in box_lines); where it is ≤ 0 the bound holds at any a as
// long as a_n·(σ·n_e + μ) ≤ amax. Tighter than the sweep's separate ranges
// of t and n (box_lines) by about a_n·w/t on arcs near their centripetal
// limit — the CAM-chord blends of a curve. Used when each end, for each
// side, gives one line (|t_e| > μ: two lines a side, as box_lines), and the
// a-free bounds hold at v_max; else box_lines. Returns whether it was used.
constexpr double kEndBoxSweep = 0.1;  // rad: μ ≤ 0.00125·g

bool end_box_lines(const ArcAxis& x, double rho, double c, double x_max, double sweep, ArcAxisBound& b) {
  if (sweep > kEndBoxSweep) return false;
  const double mu = x.g * sweep * sweep / 8.0;
  const double a_n_max = c * x_max;
  for (int e = 0; e < 2; ++e) {
    if (std::abs(x.t_end[e]) <= mu) return false;
    // the bound whose a-coefficient is ≤ 0 must hold with a free
    if (a_n_max * (std::abs(x.n_end[e]) + mu) > x.a_axis) return false;
  }
  for (int e = 0; e < 2; ++e) {
    for (const double side : {1.0, -1.0}) {
      // σ with σ·s·t_e > 0
      const double sigma = side * x.t_end[e] > 0.0 ? 1.0 : -1.0;
      const double per = 1.0 / (rho * (std::abs(x.t_end[e]) + mu));
      const double q = (sigma * x.n_end[e] + mu) * c * per;
      if (side > 0) {
        b.p_up[e] = x.a_axis * per;
        b.q_up[e] = q;
      } else {
        b.p_down[e] = x.a_axis * per;
        b.q_down[e] = q;
      }
    }
  }
  return true;
}

// Factors on the axes' velocity and acceleration limits for a spiral (1, 1
// for lines and circles). The limits below are those of the circle of
// radius r_max at the spiral's dφ/ds; the spiral strays from it (ε its
// spiral_excess, ρ the plane speed ratio, t and n the circle's unit tangent
// and normal, a_n = (ρ·v)²/r_max its centripetal acceleration):
//   velocity, per unit of path speed, by at most ρ·ε along any axis;
//   curvature by at most 2·ε·ρ²/r_max, so v² times it by at most 2·ε·a_n.
// Some axis sees at least 1/√3 of the unit t (and of n), so at a speed and
// acceleration the circle's limits allow, v ≤ √3·v_top/ρ, a_n ≤ √3·share·a_top
// and |a_t| ≤ √3·(a_top + a_n)/ρ (v_top, a_top the largest axis limits): the
// velocity strays by at most √3·ε·v_top, the acceleration by at most
// ε·(2·a_n + ρ·|a_t|) ≤ ε·(√3 + (2√3 + 3)·share)·a_top < 9·ε·a_top. Limits
// lowered to lim/(1 + 2·ε·top/bottom) and lim/(1 + 9·ε·top/bottom) (over the
// linear axes) keep the spiral itself within them.
struct SpiralDerate {
  double v = 1.0, a = 1.0;
};

SpiralDerate spiral_derate(const SegmentGeometry& geo, const MachineConfig& machine) {
  SpiralDerate d;
  const double eps = geo.spiral_excess();
  if (eps <= 0.0) return d;
  double v_lo = std::numeric_limits<double>::infinity(), v_hi = 0.0, a_lo = v_lo, a_hi = 0.0;
  for (int i = 0; i < 3; ++i) {
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) continue;
    v_lo = std::min(v_lo, ax.max_velocity);
    v_hi = std::max(v_hi, ax.max_velocity);
    a_lo = std::min(a_lo, ax.max_acceleration);
    a_hi = std::max(a_hi, ax.max_acceleration);
  }
  if (v_hi <= 0.0 || a_hi <= 0.0) return d;
  d.v = 1.0 / (1.0 + 2.0 * eps * v_hi / v_lo);
  d.a = 1.0 / (1.0 + 9.0 * eps * a_hi / a_lo);
  return d;
}

}  // namespace

namespace {

// The range of f = a·σ² + b·σ + c over σ ∈ [0, 1]: its ends and its vertex.
void quadratic_range(double a, double b, double c, double& lo, double& hi) {
  lo = std::min(c, a + b + c);
  hi = std::max(c, a + b + c);
  if (a != 0.0) {
    const double s = -b / (2.0 * a);
    if (s > 0.0 && s < 1.0) {
      const double v = (a * s + b) * s + c;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
}

// A curve piece (SegmentGeometry::is_curve): axis i moves at k_i(σ) =
// p_i'(σ)/L per unit of path and bends by κ_i(σ) = p_i''(σ)/L², so at path
// speed v and tangential acceleration a_t it sees k_i·a_t + κ_i·v². Let
// K_i = max|k_i| (p_i' is quadratic in σ: its ends and its vertex). Where
// k_i keeps one sign σ_i over the piece, the bend helps one way and
// hinders the other: with h⁺ = max(σ_i·κ_i) and h⁻ = max(−σ_i·κ_i) over
// the piece (κ_i is linear in σ: its ends), the axis keeps amax_i when
//   speeding up    a_t ≤ (amax_i − h⁺·x) / K_i        (x = v²)
//   slowing down   a_t ≤ (amax_i − h⁻·x) / K_i
// (k_i·a_t ≤ K_i·a_t, and the bend's part is at most h·x); where k_i
// changes sign both take h = max|κ_i|. These are box lines a ≤ p − q·x of
// the arcs' (q < 0 where the bend helps). Two axes share each of
// SegmentLimits' slots (a slot has two lines per side; the norm bound is
// off: b = cap = 0). The top speed keeps every axis within its velocity,
// and the bend within kArcNormalShare of its acceleration, so the other
// side of each bound (k_i·a_t + κ_i·x ≥ −amax_i) holds as well.
void curve_limits(const SegmentGeometry& geo, const MachineConfig& machine, SegmentLimits& lim) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double L = geo.length();
  const Pose d0 = geo.curve_d1(0.0), d1 = geo.curve_d1(1.0);
  const Pose c0 = geo.curve_d2(0.0), c1 = geo.curve_d2(1.0);
  const Pose chord = geo.at(L) - geo.at(0.0);
  double v_max = kInf;
  int line = 0;
  for (int i = 0; i < kAxisCount; ++i) {
    // p_i'(σ) = a·σ² + b·σ + c
    const double a = -6.0 * chord[i] + 3.0 * d0[i] + 3.0 * d1[i];
    const double b = 6.0 * chord[i] - 4.0 * d0[i] - 2.0 * d1[i];
    double lo, hi;
    quadratic_range(a, b, d0[i], lo, hi);
    const double k = std::max(-lo, hi) / L;
    const double kappa = std::max(std::abs(c0[i]), std::abs(c1[i])) / (L * L);
    const double sign = lo > 0.0 ? 1.0 : hi < 0.0 ? -1.0 : 0.0;
    const double h_up = sign == 0.0 ? kappa : std::max(sign * c0[i], sign * c1[i]) / (L * L);
    const double h_down = sign == 0.0 ? kappa : std::max(-sign * c0[i], -sign * c1[i]) / (L * L);
    if (k <= plan::kNegligibleAxisShare && kappa <= plan::kNegligibleAxisShare) continue;
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) {
      lim.v_max = 0.0;  // the reader rejects such moves first
      return;
    }
    if (k > plan::kNegligibleAxisShare) v_max = std::min(v_max, ax.max_velocity / k);
    if (kappa > plan::kNegligibleAxisShare)
      v_max = std::min(v_max, std::sqrt(plan::kArcNormalShare * ax.max_acceleration / kappa));
    if (k <= plan::kNegligibleAxisShare) continue;  // bending only: the top speed holds it
    if (line % 2 == 0) {
      ArcAxisBound& slot = lim.axes[lim.axis_count++];
      slot.p_up = slot.p_down = {kInf, kInf};
      slot.q_up = slot.q_down = {0.0, 0.0};
      slot.b = slot.cap = 0.0;
    }
    ArcAxisBound& slot = lim.axes[lim.axis_count - 1];
    const int j = line % 2;
    slot.p_up[j] = slot.p_down[j] = ax.max_acceleration / k;
    slot.q_up[j] = h_up / k;
    slot.q_down[j] = h_down / k;
    ++line;
  }
  if (!std::isfinite(v_max)) return;
  lim.v_max = v_max;
  lim.a_linear = kInf;
}

}  // namespace

void segment_limits(const SegmentGeometry& geo, const MachineConfig& machine, SegmentLimits& lim) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  lim.v_max = 0.0;  // until known: no motion (as for the segments rejected below)
  lim.a_linear = 0.0;
  lim.c = 0.0;
  lim.axis_count = 0;
  const double L = geo.length();
  if (L <= plan::kMinSegmentLength) return;
  if (geo.is_curve()) {
    curve_limits(geo, machine, lim);
    return;
  }
  double v_max = kInf, a_linear = kInf;
  // Linearly moving part of every axis (whole line; helix normal and rotary axes of an arc).
  Pose lin = geo.start_tangent();
  if (geo.is_spiral()) {
    lin.head<3>() = geo.helix_rate();
  } else if (geo.is_arc()) {
    lin.head<3>() -= geo.plane_speed_ratio() * geo.w();
  }
  const SpiralDerate derate = spiral_derate(geo, machine);
  // min over axes of max_velocity / k and max_acceleration / k: the axes
  // that bind found by comparing the ratios cross-multiplied, one division each
  const AxisConfig* v_axis = nullptr;
  const AxisConfig* a_axis = nullptr;
  double v_k = 0.0, a_k = 0.0;
  for (int i = 0; i < kAxisCount; ++i) {
    const double k = std::abs(lin[i]);
    if (k <= plan::kNegligibleAxisShare) continue;
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) return;  // the reader rejects such moves first
    if (v_axis == nullptr || k * v_axis->max_velocity > v_k * ax.max_velocity) {
      v_axis = &ax;
      v_k = k;
    }
    if (a_axis == nullptr || k * a_axis->max_acceleration > a_k * ax.max_acceleration) {
      a_axis = &ax;
      a_k = k;
    }
  }
  if (v_axis != nullptr) {
    v_max = derate.v * v_axis->max_velocity / v_k;
    a_linear = derate.a * a_axis->max_acceleration / a_k;
  }
  std::array<ArcAxis, 3> arc_axes;
  int arc_axis_count = 0;
  const double rho = geo.plane_speed_ratio();
  const bool arc = geo.is_arc() && rho > 0.0;
  if (arc) {
    double a_n_max = kInf;
    for (int i = 0; i < 3; ++i) {
      const double ui = geo.u()[i], wi = geo.w()[i];
      const double g = std::sqrt(ui * ui + wi * wi);  // ≤ 1
      if (g <= plan::kNegligibleAxisShare) continue;
      const AxisConfig& ax = machine.axes[i];
      ArcAxis& x = arc_axes[arc_axis_count++];
      x.a_axis = derate.a * ax.max_acceleration;
      x.g = g;
      sinusoid_range(wi, -ui, g, geo, x.t_lo, x.t_hi);   // t = −sin φ·u + cos φ·w
      sinusoid_range(-ui, -wi, g, geo, x.n_lo, x.n_hi);  // n = −cos φ·u − sin φ·w
      const double cs = geo.cos_sweep(), sn = geo.sin_sweep();
      x.t_end = {wi, -sn * ui + cs * wi};
      x.n_end = {-ui, -cs * ui - sn * wi};
      const double t_abs = std::max(std::abs(x.t_lo), std::abs(x.t_hi));
      const double n_abs = std::max(std::abs(x.n_lo), std::abs(x.n_hi));
      v_max = std::min(v_max, derate.v * ax.max_velocity / (rho * t_abs + std::abs(lin[i])));
      if (n_abs > plan::kNegligibleAxisShare) a_n_max = std::min(a_n_max, x.a_axis / n_abs);
    }
    // centripetal limit: (ρ·v)²/r · N_i ≤ share · amax_i
    if (std::isfinite(a_n_max))
      v_max = std::min(v_max, std::sqrt(plan::kArcNormalShare * a_n_max * geo.radius_max()) / rho);
  }
  if (!std::isfinite(v_max)) return;
  // Planned at the machine's full limits: an override above 100 % is planned
  // for (the feed scaled, the limits kept), one below it slows what is planned.
  lim.v_max = v_max;
  lim.a_linear = a_linear;  // ∞ when only the arc's plane moves
  if (!arc) return;
  // a_n = (ρ·v)²/r: the centripetal acceleration at speed v
  const double c = rho * rho / geo.radius_max();
  lim.c = c / rho;  // the norm bound sqrt((amax/g)² − a_n²)/ρ as sqrt(b − (c'·x)²)
  for (int j = 0; j < arc_axis_count; ++j) {
    const ArcAxis& x = arc_axes[j];
    ArcAxisBound& ax = lim.axes[lim.axis_count++];
    if (!end_box_lines(x, rho, c, v_max * v_max, geo.sweep_rad(), ax)) box_lines(x, rho, c, ax);
    const double by_norm = x.a_axis / (x.g * rho);
    ax.b = by_norm * by_norm;
    ax.cap = by_norm;
  }
}

double target_speed(const Segment& seg, const SegmentGeometry& geo, const SegmentLimits& lim,
                    double feed_scale) {
  switch (seg.kind) {
    case MotionKind::Rapid: return lim.v_max;
    case MotionKind::Dwell: return 0.0;
    case MotionKind::Linear:
    case MotionKind::Arc:
      if (seg.duration_s > 0.0) return std::min(lim.v_max, feed_scale * geo.length() / seg.duration_s);
      return std::min(lim.v_max, feed_scale * seg.feed_mm_s);
  }
  return 0.0;
}

}  // namespace lcnc
