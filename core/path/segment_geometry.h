// Geometry of a motion segment, parametrised by path length s ∈ [0, length].
//
// Path length is measured in the linear axes (mm) when X, Y or Z move, else in
// the rotary axes (deg) — as RS274NGC measures feed. Every axis moves in
// proportion: a line is p(s) = start + (end − start)·s/L; an arc (helix)
// turns by angle φ(s) = sweep·s/L about its centre in its plane while the
// normal axis and the rotary axes move linearly with φ:
//   L = sqrt((r·sweep)² + h²),  h = normal-axis travel.
#pragma once

#include "geom/pose.h"
#include "path/segment.h"

namespace lcnc {

// Indices (0..2) of the first, second and normal axis of an arc plane.
struct PlaneAxes {
  int first, second, normal;
};
[[nodiscard]] PlaneAxes plane_axes(Plane plane) noexcept;

class SegmentGeometry {
 public:
  explicit SegmentGeometry(const Segment& seg);

  [[nodiscard]] double length() const noexcept { return length_; }
  [[nodiscard]] bool is_arc() const noexcept { return arc_; }
  [[nodiscard]] double radius() const noexcept { return radius_; }
  // Signed total sweep angle of an arc (rad, CCW positive), incl. extra turns.
  [[nodiscard]] double sweep_rad() const noexcept { return sweep_; }
  // Position at path length s (clamped to [0, L]).
  [[nodiscard]] Pose at(double s) const;
  // Per-axis rate of change d(axis)/ds at s (unit tangent in path units).
  [[nodiscard]] Pose tangent(double s) const;
  // Fraction of the path speed seen in the arc plane (r·|sweep| / L); 0 for lines.
  [[nodiscard]] double plane_speed_ratio() const noexcept { return plane_ratio_; }
  // Closest distance from a linear-axes point to this segment's XYZ path (mm).
  [[nodiscard]] double distance_xyz(const Vec3& p) const;

 private:
  Pose start_, end_;
  bool arc_ = false;
  PlaneAxes pa_{0, 1, 2};
  Vec3 center_ = Vec3::Zero();
  double radius_ = 0.0, start_angle_ = 0.0, sweep_ = 0.0, length_ = 0.0, plane_ratio_ = 0.0;
};

}  // namespace lcnc
