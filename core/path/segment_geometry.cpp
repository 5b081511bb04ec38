#include "path/segment_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lcnc {

PlaneAxes plane_axes(Plane plane) noexcept {
  switch (plane) {
    case Plane::XY: return {0, 1, 2};
    case Plane::ZX: return {2, 0, 1};
    case Plane::YZ: return {1, 2, 0};
  }
  return {0, 1, 2};
}

SegmentGeometry::SegmentGeometry(const Segment& seg) : start_(seg.start), end_(seg.end) {
  const Pose d = end_ - start_;
  const double lin = d.head<3>().norm();
  if (seg.kind != MotionKind::Arc) {
    length_ = lin > 0.0 ? lin : d.tail<3>().norm();
    return;
  }
  arc_ = true;
  pa_ = plane_axes(seg.plane);
  center_ = seg.center;
  const double u0 = start_[pa_.first] - center_[pa_.first];
  const double v0 = start_[pa_.second] - center_[pa_.second];
  const double u1 = end_[pa_.first] - center_[pa_.first];
  const double v1 = end_[pa_.second] - center_[pa_.second];
  radius_ = std::hypot(u0, v0);
  start_angle_ = std::atan2(v0, u0);
  const double two_pi = 2.0 * std::numbers::pi;
  double sweep = std::atan2(v1, u1) - start_angle_;  // (−2π, 2π)
  if (seg.clockwise) {
    while (sweep >= 0.0) sweep -= two_pi;  // start == end: one full turn
  } else {
    while (sweep <= 0.0) sweep += two_pi;
  }
  // An end point within rounding of the start closes a full circle.
  if (std::abs(std::abs(sweep) - two_pi) < 1e-12) sweep = seg.clockwise ? -two_pi : two_pi;
  sweep += (seg.clockwise ? -two_pi : two_pi) * seg.extra_turns;
  sweep_ = sweep;
  const double plane_len = radius_ * std::abs(sweep_);
  const double h = d[pa_.normal];
  length_ = std::hypot(plane_len, h);
  plane_ratio_ = length_ > 0.0 ? plane_len / length_ : 0.0;
}

Pose SegmentGeometry::at(double s) const {
  if (length_ <= 0.0) return end_;
  const double f = std::clamp(s / length_, 0.0, 1.0);
  if (f >= 1.0) return end_;
  Pose p = start_ + (end_ - start_) * f;
  if (arc_) {
    const double ang = start_angle_ + sweep_ * f;
    p[pa_.first] = center_[pa_.first] + radius_ * std::cos(ang);
    p[pa_.second] = center_[pa_.second] + radius_ * std::sin(ang);
  }
  return p;
}

Pose SegmentGeometry::tangent(double s) const {
  if (length_ <= 0.0) return Pose::Zero();
  Pose t = (end_ - start_) / length_;
  if (arc_) {
    const double f = std::clamp(s / length_, 0.0, 1.0);
    const double ang = start_angle_ + sweep_ * f;
    const double dang_ds = sweep_ / length_;
    t[pa_.first] = -radius_ * std::sin(ang) * dang_ds;
    t[pa_.second] = radius_ * std::cos(ang) * dang_ds;
  }
  return t;
}

double SegmentGeometry::distance_xyz(const Vec3& p) const {
  const Vec3 a = start_.head<3>();
  const Vec3 b = end_.head<3>();
  if (!arc_) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double f = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + ab * f - p).norm();
  }
  // Helix: candidate parameters are the point's polar angle in every turn of
  // the sweep, plus both ends; the nearest of them is the closest point for
  // any helix whose pitch is small against its radius (all real arcs).
  const double u = p[pa_.first] - center_[pa_.first];
  const double v = p[pa_.second] - center_[pa_.second];
  const double two_pi = 2.0 * std::numbers::pi;
  double best = std::min((a - p).norm(), (b - p).norm());
  if (sweep_ == 0.0) return best;
  double rel = std::atan2(v, u) - start_angle_;  // angle from start, any turn
  if (sweep_ > 0.0) {
    rel = std::fmod(rel, two_pi);
    if (rel < 0.0) rel += two_pi;
    for (double ang = rel; ang <= sweep_; ang += two_pi)
      best = std::min(best, (at(ang / sweep_ * length_).head<3>() - p).norm());
  } else {
    rel = std::fmod(rel, two_pi);
    if (rel > 0.0) rel -= two_pi;
    for (double ang = rel; ang >= sweep_; ang -= two_pi)
      best = std::min(best, (at(ang / sweep_ * length_).head<3>() - p).norm());
  }
  return best;
}

}  // namespace lcnc
