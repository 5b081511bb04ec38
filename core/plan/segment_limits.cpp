#include "plan/segment_limits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plan/tolerances.h"

namespace lcnc {

SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                             const MachineConfig& machine) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  SegmentLimits lim{kInf, kInf};
  const double L = geo.length();
  if (L <= plan::kMinSegmentLength) return {0.0, 0.0};
  const Pose d = seg.end - seg.start;
  PlaneAxes pa{-1, -1, -1};
  if (geo.is_arc()) pa = plane_axes(seg.plane);
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine.axes[i];
    if (i == pa.first || i == pa.second) continue;
    const double k = std::abs(d[i]) / L;
    if (k <= 0.0) continue;
    if (!ax.present) return {0.0, 0.0};  // cannot happen after the reader's checks
    lim.v_max = std::min(lim.v_max, ax.max_velocity / k);
    lim.a_max = std::min(lim.a_max, ax.max_acceleration / k);
  }
  if (geo.is_arc()) {
    const AxisConfig& a1 = machine.axes[pa.first];
    const AxisConfig& a2 = machine.axes[pa.second];
    const double rho = geo.plane_speed_ratio();
    if (rho > 0.0) {
      const double v_plane = std::min(a1.max_velocity, a2.max_velocity);
      const double a_plane = std::min(a1.max_acceleration, a2.max_acceleration);
      const double a_share = a_plane * plan::kArcAccelShare;
      lim.v_max = std::min(lim.v_max, v_plane / rho);
      lim.a_max = std::min(lim.a_max, a_share / rho);
      // Centripetal limit (DESIGN §5.1): (ρ·v)²/r ≤ a_share.
      lim.v_max = std::min(lim.v_max, std::sqrt(a_share * geo.radius()) / rho);
    }
  }
  if (!std::isfinite(lim.v_max)) lim = {0.0, 0.0};
  return lim;
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
