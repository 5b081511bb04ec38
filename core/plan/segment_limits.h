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
// limits returned are v_max/K and a_max/K², so any override up to K keeps
// every axis within its limits.
#pragma once

#include <array>

#include "machine/machine_config.h"
#include "path/segment.h"
#include "path/segment_geometry.h"

namespace lcnc {

struct SegmentLimits {
  double v_max = 0.0;  // path units/s: the highest speed the axes allow
  double a_max = 0.0;  // path units/s²: tangential acceleration at v_max

  // Tangential acceleration (speeding up) and deceleration (slowing down,
  // > 0) allowed while the speed stays ≤ v (planned units): on an arc, slower
  // means less centripetal load; on a line both are a_max whatever v.
  [[nodiscard]] double accel_at(double v) const noexcept { return tangential(v, +1.0); }
  [[nodiscard]] double decel_at(double v) const noexcept { return tangential(v, -1.0); }
  [[nodiscard]] double tangential(double v, double sign) const noexcept;

  // What accel_at() needs (physical units).
  double a_linear = 0.0;  // bound from the linearly moving axes
  bool arc = false;
  double rho = 0.0, radius = 0.0;
  std::array<double, 3> a_axis{}, g{}, t_lo{}, t_hi{}, n_lo{}, n_hi{};  // per linear axis, arcs only
  double override_k = 1.0;
};

// Limits of the segment (accel_at/decel_at give its acceleration at a speed).
[[nodiscard]] SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                                           const MachineConfig& machine);

// The speed to plan for: rapid → v_max; feed → min(F, v_max); G93 → L/duration.
[[nodiscard]] double target_speed(const Segment& seg, const SegmentGeometry& geo,
                                  const SegmentLimits& lim);

}  // namespace lcnc
