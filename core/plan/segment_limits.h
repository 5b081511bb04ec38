// Path-speed and path-acceleration limits of a segment from the per-axis
// limits of the machine (DESIGN §5.2: "a segment's path limits follow from its
// direction").
//
// Line: axis i moves k_i = |Δ_i|/L per unit of path, so
//   v ≤ min_i vmax_i / k_i,   a ≤ min_i amax_i / k_i.
// Arc of radius r in the plane (u, w), plane share ρ = r·sweep/L, unit
// tangent t(φ) and unit normal n(φ) (toward the centre) in the plane. Axis i
// sees the in-plane acceleration ρ·a_t·t_i + a_n·n_i, a_n = (ρ·v)²/r. Two
// bounds on it are both true, and an a_t is allowed when either keeps the
// axis within amax_i:
//   |·| ≤ g_i·sqrt((ρ·a_t)² + a_n²),  g_i = sqrt(u_i² + w_i²)   (long arcs)
//   t_i ∈ [t_lo, t_hi], n_i ∈ [n_lo, n_hi] over the sweep, a_n anywhere in
//   [0, a_n(v)]: the extremes of ρ·a_t·t_i + a_n·n_i over that box, signs
//   kept                                                         (short arcs)
// Both fall as v rises, so a bound taken at the top speed of a segment holds
// over all of it.
// The second is what makes a short blend arc, whose direction hardly turns,
// as fast as the axes allow — and it differs for speeding up and slowing
// down, where the centripetal part helps one and hinders the other. The
// centripetal limit (DESIGN §5.1) takes a share of the budget:
// a_n·max(|n_lo|, |n_hi|) ≤ kArcNormalShare·amax_i.
// Normal (helix) and rotary axes move linearly with the path, as on a line.
// All of it is planned at the highest feed override K (DESIGN §5.5): the
// limits returned are v_max/K and accelerations/K², so any override up to K
// keeps every axis within its limits.
// Cost: the look-ahead asks for accelerations many times per segment, so
// everything that does not depend on the speed is computed once, and the
// ranges over the sweep avoid atan2 where the answer is certain.
#pragma once

#include <array>

#include "machine/machine_config.h"
#include "path/segment.h"
#include "path/segment_geometry.h"

namespace lcnc {

// Tangential acceleration and deceleration (> 0) at one speed (path units/s²).
struct Accel {
  double accel = 0.0;
  double decel = 0.0;
};

struct SegmentLimits {
  double v_max = 0.0;  // path units/s: the highest speed the axes allow

  // Tangential acceleration (speeding up) and deceleration (slowing down,
  // > 0) allowed while the speed stays ≤ v (planned units): on an arc, slower
  // means less centripetal load; on a line both are the same whatever v.
  [[nodiscard]] double accel_at(double v) const noexcept { return at(v).accel; }
  [[nodiscard]] double decel_at(double v) const noexcept { return at(v).decel; }
  [[nodiscard]] double tangential(double v, double sign) const noexcept {
    return sign > 0 ? accel_at(v) : decel_at(v);
  }
  // Both at once (they share the centripetal part); inline for lines.
  [[nodiscard]] Accel at(double v) const noexcept {
    if (!arc) {
      const double a = a_linear / (override_k * override_k);
      return {a, a};
    }
    return arc_at(v);
  }

  // What at() needs (physical units), fixed per segment.
  double a_linear = 0.0;  // bound from the linearly moving axes
  bool arc = false;
  double rho = 0.0, radius = 0.0;
  double override_k = 1.0;
  // Per linear axis an arc moves in (g_i > 0), the constants of the two
  // bounds, computed once per segment (at() is asked many times): the range
  // [n_lo, n_hi] of the unit normal over the sweep, and the box bound's
  // denominators ρ·x_hi and ρ·(−x_lo) for speeding up [0] and slowing down
  // [1] (x = ±t_i over the sweep; 0: that side gives no bound).
  struct ArcAxis {
    double a_axis = 0.0;       // amax_i
    double by_norm_sqr = 0.0;  // (amax_i/g_i)²
    double a1_cap = 0.0;       // sqrt(by_norm_sqr)/ρ: the norm bound at a_n = 0, its largest
    double n_lo = 0.0, n_hi = 0.0;
    std::array<double, 2> den_hi{}, den_lo{};
  };
  std::array<ArcAxis, 3> arc_axes{};
  int arc_axis_count = 0;

 private:
  [[nodiscard]] Accel arc_at(double v) const noexcept;
};

// Limits of the segment (accel_at/decel_at give its acceleration at a speed).
[[nodiscard]] SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                                           const MachineConfig& machine);

// The speed to plan for: rapid → v_max; feed → min(F, v_max); G93 → L/duration.
[[nodiscard]] double target_speed(const Segment& seg, const SegmentGeometry& geo,
                                  const SegmentLimits& lim);

}  // namespace lcnc
