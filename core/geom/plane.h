// Plane geometry the cut, the DXF checks and cutter compensation share.
#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace lcnc::geom {

// z of a × b: > 0 when b turns counter-clockwise from a.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Distance from p to the segment a–b (to a when it has no length).
inline double point_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace lcnc::geom
