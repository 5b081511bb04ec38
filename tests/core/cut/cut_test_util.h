// Shared helpers of the cutting tests: squares and circles as polygons.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace lcnc::test {

// Counter-clockwise square of side `a` with its lower left corner at (x, y).
inline std::vector<Eigen::Vector2d> square(double x, double y, double a) {
  return {{x, y}, {x + a, y}, {x + a, y + a}, {x, y + a}};
}

// Counter-clockwise regular n-gon inscribed in the circle (cx, cy, r).
inline std::vector<Eigen::Vector2d> ngon(double cx, double cy, double r, int n) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    p.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a));
  }
  return p;
}

}  // namespace lcnc::test
