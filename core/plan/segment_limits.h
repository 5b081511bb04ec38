// Path-speed and path-acceleration limits of a segment from the per-axis
// limits of the machine (DESIGN §5.2: "a segment's path limits follow from its
// direction").
//
// Line: axis i moves k_i = |Δ_i|/L per unit of path, so
//   v ≤ min_i vmax_i / k_i,   a ≤ min_i amax_i / k_i.
// Arc (radius r, plane share ρ = r·|sweep|/L): each plane axis sees at most
// ρ·v, tangential ρ·a_t and centripetal (ρ·v)²/r. Both accelerations get
// a_plane/√2 (a_plane = the smaller of the two plane axes' limits), so
//   ρ·a_t ≤ a_plane/√2   and   (ρ·v)²/r ≤ a_plane/√2   (centripetal limit).
// Normal and rotary axes move linearly with the path as on a line.
#pragma once

#include "machine/machine_config.h"
#include "path/segment.h"
#include "path/segment_geometry.h"

namespace lcnc {

struct SegmentLimits {
  double v_max = 0.0;  // path units/s: the highest speed the axes allow
  double a_max = 0.0;  // path units/s²: tangential acceleration the axes allow
};

[[nodiscard]] SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                                           const MachineConfig& machine);

// The speed to plan for: rapid → v_max; feed → min(F, v_max); G93 → L/duration.
[[nodiscard]] double target_speed(const Segment& seg, const SegmentGeometry& geo,
                                  const SegmentLimits& lim);

}  // namespace lcnc
