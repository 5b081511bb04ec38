#include "gcode/arc_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "path/segment_geometry.h"

namespace lcnc::gcode {
namespace {

// x mod 2π in [0, 2π).
[[nodiscard]] double wrap_2pi(double x) {
  double r = std::fmod(x, kTwoPi);
  if (r < 0.0) r += kTwoPi;
  return r;
}

}  // namespace

double arc_sweep_rad(const Segment& arc) {
  const auto [ia, ib, in] = arc_plane_axes(arc.plane);
  (void)in;
  const double ts = std::atan2(arc.start[ib] - arc.center[ib], arc.start[ia] - arc.center[ia]);
  const double te = std::atan2(arc.end[ib] - arc.center[ib], arc.end[ia] - arc.center[ia]);
  double sweep = wrap_2pi(arc.clockwise ? ts - te : te - ts);
  if (sweep <= 0.0) sweep = kTwoPi;  // end == start: one full turn
  return sweep + kTwoPi * arc.extra_turns;
}

double arc_length_mm(const Segment& arc) {
  const auto [ia, ib, in] = arc_plane_axes(arc.plane);
  const double rs = std::hypot(arc.start[ia] - arc.center[ia], arc.start[ib] - arc.center[ib]);
  const double re = std::hypot(arc.end[ia] - arc.center[ia], arc.end[ib] - arc.center[ib]);
  const double dn = arc.end[in] - arc.start[in];
  const double dr = re - rs;
  if (!SegmentGeometry::radii_differ(rs, re)) return std::hypot(rs * arc_sweep_rad(arc), dn);
  // a spiral: the planner's length bound (path/segment_geometry.h)
  const double plane = std::max(rs, re) * arc_sweep_rad(arc);
  return std::sqrt(plane * plane + dr * dr + dn * dn);
}

void arc_bounds(const Segment& arc, Vec3& lo, Vec3& hi) {
  const Vec3 s = linear_part(arc.start);
  const Vec3 e = linear_part(arc.end);
  lo = s.cwiseMin(e);
  hi = s.cwiseMax(e);
  const auto [ia, ib, in] = arc_plane_axes(arc.plane);
  (void)in;
  const double rs = std::hypot(arc.start[ia] - arc.center[ia], arc.start[ib] - arc.center[ib]);
  const double re = std::hypot(arc.end[ia] - arc.center[ia], arc.end[ib] - arc.center[ib]);
  const double ts = std::atan2(arc.start[ib] - arc.center[ib], arc.start[ia] - arc.center[ia]);
  const double sweep = arc_sweep_rad(arc);
  // A spiral's radius runs linearly with the angle, r(φ) = rs + q·φ; near a
  // plane axis' angle its coordinate r(φ)·cos(φ − φk) peaks a little past
  // φk, by at most q²/(2·r) above r(φk).
  const double q = (re - rs) / sweep;
  const double peak = q == 0.0 ? 0.0 : q * q / (2.0 * std::min(rs, re));
  // Extreme points at angles 0, π/2, π, 3π/2: +a, +b, −a, −b — where the
  // arc passes them, each turn (the first and last pass bound the radius).
  for (int k = 0; k < 4; ++k) {
    const double phi = k * (std::numbers::pi / 2.0);
    const double first = wrap_2pi(arc.clockwise ? ts - phi : phi - ts);
    if (first > sweep) continue;
    const double last = first + kTwoPi * std::floor((sweep - first) / kTwoPi);
    const double r = std::max(rs + q * first, rs + q * last) + peak;
    const int axis = (k % 2 == 0) ? ia : ib;
    const double v = arc.center[axis] + ((k < 2) ? r : -r);
    lo[axis] = std::min(lo[axis], v);
    hi[axis] = std::max(hi[axis], v);
  }
}

}  // namespace lcnc::gcode
