// How the program screen looks at a toolpath in 3D, Qt-free: an
// orthographic view turned by `yaw` about the machine's Z, then tipped by
// `pitch` about the screen's horizontal (0: from above, the top view; 90:
// from the front). project() gives screen coordinates in mm, x right and y
// up; the widget scales and centres them.
//
//   p1 = Rz(yaw)·p,   screen = (p1.x, p1.y·cos(pitch) + p1.z·sin(pitch))
//   depth (towards the viewer) = p1.z·cos(pitch) − p1.y·sin(pitch)
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geom/pose.h"

namespace lcnc::hmi {

struct ViewAngles {
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;  // 0 … 90
};
inline constexpr ViewAngles kTopView{0.0, 0.0};
inline constexpr ViewAngles kIsoView{-35.0, 55.0};  // from the front left, above

struct ScreenPoint {
  double x = 0.0, y = 0.0;
};

[[nodiscard]] inline ScreenPoint project(const Vec3& p, const ViewAngles& v) noexcept {
  const double yaw = v.yaw_deg * std::numbers::pi / 180.0;
  const double pitch = std::clamp(v.pitch_deg, 0.0, 90.0) * std::numbers::pi / 180.0;
  const double x1 = p.x() * std::cos(yaw) - p.y() * std::sin(yaw);
  const double y1 = p.x() * std::sin(yaw) + p.y() * std::cos(yaw);
  return {x1, y1 * std::cos(pitch) + p.z() * std::sin(pitch)};
}

// A grid spacing of 1, 2 or 5 × 10^k near span / lines.
[[nodiscard]] inline double nice_step(double span, int lines = 10) noexcept {
  const double raw = std::max(span, 1e-9) / lines;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0})
    if (raw <= m * decade) return m * decade;
  return 10.0 * decade;
}

}  // namespace lcnc::hmi
