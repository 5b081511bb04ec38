// Path-speed and path-acceleration limits of a segment from the per-axis
// limits of the machine (DESIGN §5.2: "a segment's path limits follow from its
// direction").
//
// Line: axis i moves k_i = |Δ_i|/L per unit of path, so
//   v ≤ min_i vmax_i / k_i,   a ≤ min_i amax_i / k_i.
// Arc of radius r in the plane (u, w), plane share ρ = r·sweep/L: axis i sees
// the in-plane motion with weight g_i = sqrt(u_i² + w_i²) ≤ 1; its in-plane
// acceleration is at most g_i·sqrt((ρ·a_t)² + a_n²), a_n = (ρ·v)²/r. With
// A = min_i amax_i / g_i the centripetal limit (DESIGN §5.1) takes a share of A
//   (ρ·v)²/r ≤ kArcNormalShare·A
// and what is left at the segment's top speed is its tangential acceleration
//   ρ·a_t ≤ sqrt(A² − a_n(v_max)²).
// Normal (helix) and rotary axes move linearly with the path, as on a line.
// All of it is planned at the highest feed override K (DESIGN §5.5): the
// limits returned are v_max/K and a_max/K², so any override up to K keeps
// every axis within its limits.
#pragma once

#include "machine/machine_config.h"
#include "path/segment.h"
#include "path/segment_geometry.h"

namespace lcnc {

struct SegmentLimits {
  double v_max = 0.0;  // path units/s: the highest speed the axes allow
  double a_max = 0.0;  // path units/s²: tangential acceleration the axes allow
};

// Limits of the segment when its speed never exceeds v_cap (the planned
// speed): a lower cap leaves more of an arc's acceleration for the tangent.
[[nodiscard]] SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                                           const MachineConfig& machine,
                                           double v_cap = 1e300);

// The speed to plan for: rapid → v_max; feed → min(F, v_max); G93 → L/duration.
[[nodiscard]] double target_speed(const Segment& seg, const SegmentGeometry& geo,
                                  const SegmentLimits& lim);

}  // namespace lcnc
