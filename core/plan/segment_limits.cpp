#include "plan/segment_limits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plan/tolerances.h"

namespace lcnc {

SegmentLimits segment_limits(const Segment& seg, const SegmentGeometry& geo,
                             const MachineConfig& machine, double v_cap) {
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
  if (geo.is_arc() && geo.plane_speed_ratio() > 0.0) {
    const double rho = geo.plane_speed_ratio();
    double a_plane = kInf;
    for (int i = 0; i < 3; ++i) {
      const double g = std::hypot(geo.u()[i], geo.w()[i]);
      if (g <= 1e-15) continue;
      const AxisConfig& ax = machine.axes[i];
      lim.v_max = std::min(lim.v_max, ax.max_velocity / (rho * g + std::abs(lin[i])));
      a_plane = std::min(a_plane, ax.max_acceleration / g);
    }
    // centripetal limit: (ρ·v)²/r ≤ share·A
    const double v_curve = std::sqrt(plan::kArcNormalShare * a_plane * geo.radius()) / rho;
    lim.v_max = std::min(lim.v_max, v_curve);
    const double v_top = std::min(lim.v_max, v_cap * machine.max_feed_override);
    const double a_n = rho * v_top * rho * v_top / geo.radius();
    const double a_t = std::sqrt(std::max(0.0, a_plane * a_plane - a_n * a_n)) / rho;
    lim.a_max = std::min(lim.a_max, a_t);
  }
  if (!std::isfinite(lim.v_max)) return {0.0, 0.0};
  // Planned at the highest feed override (DESIGN §5.5): at K the speed is K·v
  // and the acceleration K²·a.
  const double k = machine.max_feed_override;
  return {lim.v_max / k, lim.a_max / (k * k)};
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
