#include "path/segment_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "path/path_tolerances.h"

namespace lcnc {

PlaneAxes plane_axes(Plane plane) noexcept {
  switch (plane) {
    case Plane::ZX: return {2, 0, 1};
    case Plane::YZ: return {1, 2, 0};
    case Plane::XY:
    case Plane::Free: return {0, 1, 2};
  }
  return {0, 1, 2};
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) noexcept {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double f = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + ab * f - p).norm();
}

namespace {

// Linear axes if they move, else rotary (as RS274NGC measures feed). Linear
// travel the planner takes as none (path::kMinSegmentLength) is none here
// too: otherwise a rotary swing with a nanometre of X Y Z would have the
// nanometre as its length, be planned as no motion and skipped while its
// rotary axes still count as moved — the next move would jump.
double line_length(const Pose& d) {
  const double lin = d.head<3>().norm();
  return lin > path::kMinSegmentLength ? lin : d.tail<3>().norm();
}

// atan2(y, x); for x > 0 and |y| ≤ x/64 (every corner blend's sweep) by the
// series of atan(y/x): the terms left out are below 1e-19 of the result.
double atan2_small(double y, double x) noexcept {
  if (x > 0.0 && std::abs(y) <= 0.015625 * x) {
    const double t = y / x, t2 = t * t;
    return t * (1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 * (1.0 / 9.0)))));
  }
  return std::atan2(y, x);
}

}  // namespace

double path_length(const Segment& seg) {
  if (seg.kind != MotionKind::Arc) return seg.curve ? seg.curve_length : line_length(seg.end - seg.start);
  return SegmentGeometry(seg).length();
}

void SegmentGeometry::set(const Segment& seg) {
  start_ = seg.start;
  end_ = seg.end;
  const Pose d = end_ - start_;
  if (seg.kind != MotionKind::Arc) {
    // every member as a default-constructed line's
    arc_ = false;
    center_ = Vec3::Zero();
    u_ = Vec3::UnitX();
    w_ = Vec3::UnitY();
    axis_n_ = Vec3::Zero();
    helix_h_ = radius_ = sweep_ = plane_ratio_ = dr_ = spiral_excess_ = 0.0;
    sin_sweep_ = 0.0;
    cos_sweep_ = 1.0;
    curve_ = seg.curve;
    if (curve_) {
      d0_ = seg.curve_d_start;
      d1_ = seg.curve_d_end;
      length_ = seg.curve_length;
    } else {
      length_ = line_length(d);
    }
    inv_length_ = length_ > 0.0 ? 1.0 / length_ : 0.0;
    return;
  }
  curve_ = false;
  arc_ = true;
  center_ = seg.center;
  const Vec3 a = start_.head<3>(), b = end_.head<3>();
  double r_end = 0.0;  // the end's distance from the centre, in the plane
  const double two_pi = 2.0 * std::numbers::pi;
  if (seg.plane == Plane::Free) {
    const Vec3 n = seg.normal.normalized();
    // Flat (corner blends, circles on a tilted head): start and end lie in
    // the plane through the centre. Else a helix about n (a helix on a tilted
    // head): the plane is the start's, the centre moved into it, and the end
    // rises by `rise` along n.
    const double rise = (b - a).dot(n);
    axis_n_ = Vec3::Zero();
    helix_h_ = 0.0;
    if (std::abs(rise) > path::kMinSegmentLength) {
      axis_n_ = n;
      helix_h_ = rise;
      center_ += (a - center_).dot(n) * n;
    }
    const Vec3 ra = a - center_;
    radius_ = ra.norm();
    u_ = ra / radius_;
    w_ = n.cross(u_);
    const Vec3 rb = b - center_;
    const double y = rb.dot(w_), x = rb.dot(u_);
    r_end = std::sqrt(x * x + y * y);
    sweep_ = atan2_small(y, x);
    // End on the start (to rounding: a full circle mapped by a rotation comes
    // back a few 1e-17 rad either side): one full turn, as on the named planes.
    if (sweep_ <= path::kFullTurnAngle) sweep_ += two_pi;
    sweep_ += two_pi * seg.extra_turns;
    set_sin_cos_sweep(y, x);
  } else {
    const PlaneAxes pa = plane_axes(seg.plane);
    Vec3 n = Vec3::Zero();
    n[pa.normal] = seg.clockwise ? -1.0 : 1.0;  // turn counter-clockwise about n
    axis_n_ = Vec3::Zero();
    axis_n_[pa.normal] = 1.0;
    helix_h_ = d[pa.normal];
    Vec3 ra = a - center_;
    ra[pa.normal] = 0.0;
    Vec3 rb = b - center_;
    rb[pa.normal] = 0.0;
    radius_ = ra.norm();
    u_ = ra / radius_;
    w_ = n.cross(u_);
    const double y = rb.dot(w_), x = rb.dot(u_);
    r_end = rb.norm();
    double sweep = atan2_small(y, x);                    // (−π, π]
    if (sweep <= path::kFullTurnAngle) sweep += two_pi;  // end == start: one full turn
    sweep_ = sweep + two_pi * seg.extra_turns;
    set_sin_cos_sweep(y, x);
  }
  set_spiral(r_end);
}

void SegmentGeometry::set_spiral(double r_end) {
  dr_ = radii_differ(radius_, r_end) ? r_end - radius_ : 0.0;
  const double plane_len = radius_max() * sweep_;
  if (dr_ == 0.0) {
    spiral_excess_ = 0.0;
    // hypot(x, 0) is |x| exactly (C Annex F): skip the call for plane arcs
    length_ = helix_h_ == 0.0 ? std::abs(plane_len) : std::hypot(plane_len, helix_h_);
  } else {
    spiral_excess_ = (std::abs(dr_) + std::abs(dr_) / sweep_) / radius_max();
    length_ = std::sqrt(plane_len * plane_len + dr_ * dr_ + helix_h_ * helix_h_);
  }
  plane_ratio_ = length_ > 0.0 ? plane_len / length_ : 0.0;
  inv_length_ = length_ > 0.0 ? 1.0 / length_ : 0.0;
}

void SegmentGeometry::set_circular_arc(const Pose& start, const Pose& end, const Vec3& center, const Vec3& u,
                                       const Vec3& w, double radius, double sin_sweep, double cos_sweep) {
  start_ = start;
  end_ = end;
  arc_ = true;
  curve_ = false;
  center_ = center;
  u_ = u;
  w_ = w;
  axis_n_ = Vec3::Zero();
  helix_h_ = 0.0;
  radius_ = radius;
  dr_ = spiral_excess_ = 0.0;
  sweep_ = atan2_small(sin_sweep, cos_sweep);
  if (sweep_ <= 0.0) sweep_ += 2.0 * std::numbers::pi;
  sin_sweep_ = sin_sweep;
  cos_sweep_ = cos_sweep;
  length_ = radius * sweep_;
  plane_ratio_ = length_ > 0.0 ? 1.0 : 0.0;
  inv_length_ = length_ > 0.0 ? 1.0 / length_ : 0.0;
}

void SegmentGeometry::set_sin_cos_sweep(double y, double x) noexcept {
  // those of atan2(y, x), which differs from the sweep by whole turns
  const double h = std::sqrt(x * x + y * y);  // about the radius
  if (h > 0.0) {
    sin_sweep_ = y / h;
    cos_sweep_ = x / h;
  } else {
    sin_sweep_ = std::sin(sweep_);
    cos_sweep_ = std::cos(sweep_);
  }
}

double SegmentGeometry::angle_at(double s) const noexcept {
  return length_ > 0.0 ? sweep_ * std::clamp(s / length_, 0.0, 1.0) : 0.0;
}

// P'(φ)·dφ/ds with P'(φ) = r(φ)·e_θ + (Δr/sweep)·e_r + (h/sweep)·n̂, dφ/ds = sweep/L
Pose SegmentGeometry::tangent_at_angle(double f, double sin_phi, double cos_phi) const {
  if (length_ <= 0.0) return Pose::Zero();
  Pose t = (end_ - start_) * inv_length_;
  if (arc_) {
    const double dphi_ds = sweep_ * inv_length_;
    t.head<3>() =
        (radius_ + f * dr_) * dphi_ds * (-sin_phi * u_ + cos_phi * w_) + (helix_h_ * inv_length_) * axis_n_;
    if (dr_ != 0.0) t.head<3>() += (dr_ * inv_length_) * (cos_phi * u_ + sin_phi * w_);
  }
  return t;
}

Pose SegmentGeometry::tangent(double s) const {
  if (curve_) return curve_d1(std::clamp(s * inv_length_, 0.0, 1.0)) * inv_length_;
  if (!arc_) return tangent_at_angle(0.0, 0.0, 1.0);
  const double phi = angle_at(s);
  return tangent_at_angle(sweep_ > 0.0 ? phi / sweep_ : 0.0, std::sin(phi), std::cos(phi));
}

// angle_at(0) is 0 and angle_at(length_) is sweep_ exactly (s / L is 0 and 1).
Pose SegmentGeometry::start_tangent() const {
  return curve_ ? Pose(d0_ * inv_length_) : tangent_at_angle(0.0, 0.0, 1.0);
}

Pose SegmentGeometry::end_tangent() const {
  return curve_ ? Pose(d1_ * inv_length_) : tangent_at_angle(1.0, sin_sweep_, cos_sweep_);
}

// H'(σ) = 6σ(1−σ)·(p1 − p0) + (1 − 4σ + 3σ²)·d0 + (3σ² − 2σ)·d1
Pose SegmentGeometry::curve_d1(double f) const {
  return (6.0 * f * (1.0 - f)) * (end_ - start_) + (1.0 - 4.0 * f + 3.0 * f * f) * d0_ +
         (3.0 * f * f - 2.0 * f) * d1_;
}

// H''(σ) = (6 − 12σ)·(p1 − p0) + (6σ − 4)·d0 + (6σ − 2)·d1
Pose SegmentGeometry::curve_d2(double f) const {
  return (6.0 - 12.0 * f) * (end_ - start_) + (6.0 * f - 4.0) * d0_ + (6.0 * f - 2.0) * d1_;
}

// P''(φ)·(dφ/ds)² with P''(φ) = −r(φ)·e_r + 2·(Δr/sweep)·e_θ
Pose SegmentGeometry::curvature(double s) const {
  if (curve_) return curve_d2(std::clamp(s * inv_length_, 0.0, 1.0)) * (inv_length_ * inv_length_);
  Pose k = Pose::Zero();
  if (!arc_ || length_ <= 0.0) return k;
  const double phi = angle_at(s);
  const double dphi_ds = sweep_ / length_;
  const double c = std::cos(phi), sn = std::sin(phi);
  const double r = dr_ == 0.0 ? radius_ : radius_ + (phi / sweep_) * dr_;
  k.head<3>() = -r * dphi_ds * dphi_ds * (c * u_ + sn * w_);
  if (dr_ != 0.0) k.head<3>() += (2.0 * dr_ / sweep_) * dphi_ds * dphi_ds * (-sn * u_ + c * w_);
  return k;
}

double SegmentGeometry::distance_xyz(const Vec3& p, double below) const {
  const Vec3 a = start_.head<3>();
  const Vec3 b = end_.head<3>();
  if (curve_) {
    // The curve lies in the box of its Bézier points p0, p0 + d0/3,
    // p1 − d1/3, p1: no nearer than the box.
    const Vec3 b1 = a + d0_.head<3>() / 3.0, b2 = b - d1_.head<3>() / 3.0;
    const Vec3 lo_box = a.cwiseMin(b).cwiseMin(b1).cwiseMin(b2),
               hi_box = a.cwiseMax(b).cwiseMax(b1).cwiseMax(b2);
    const double to_box = (p - p.cwiseMax(lo_box).cwiseMin(hi_box)).norm();
    if (to_box >= below) return to_box;
    // kCurveChords + 1 points, then a golden-section search of the distance
    // over the parameter either side of each that is nearer than both its
    // neighbours (a curve may pass near a point twice)
    Pose q;
    const auto dist = [&](double f) {
      at(f * length_, q);
      return (q.head<3>() - p).norm();
    };
    std::array<double, kCurveChords + 1> d{};
    for (int k = 0; k <= kCurveChords; ++k) d[k] = dist(static_cast<double>(k) / kCurveChords);
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= kCurveChords; ++k) {
      best = std::min(best, d[k]);
      if ((k > 0 && d[k - 1] < d[k]) || (k < kCurveChords && d[k + 1] < d[k])) continue;
      constexpr double kGolden = 0.6180339887498949;
      double lo = std::max(0, k - 1) / static_cast<double>(kCurveChords);
      double hi = std::min(kCurveChords, k + 1) / static_cast<double>(kCurveChords);
      double x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
      double f1 = dist(x1), f2 = dist(x2);
      for (int it = 0; it < kCurveSearchSteps; ++it) {
        if (f1 < f2) {
          hi = x2;
          x2 = x1;
          f2 = f1;
          x1 = hi - kGolden * (hi - lo);
          f1 = dist(x1);
        } else {
          lo = x1;
          x1 = x2;
          f1 = f2;
          x2 = lo + kGolden * (hi - lo);
          f2 = dist(x2);
        }
      }
      best = std::min({best, f1, f2});
    }
    return best;
  }
  if (!arc_) return distance_to_segment(p, a, b);
  // Candidate parameters: the point's polar angle in every turn of the sweep,
  // plus both ends. On a circle the polar angle is the closest point; on a
  // helix it is only near it (the rise moves the closest point along the
  // turn, by up to the point's height off the helix over its pitch: on a
  // steep helix of a small radius, far), so there the nearest candidate and
  // a turn either side of it are refined by Newton's method on the squared
  // distance (a helix of many turns costs three walks, not one per turn); a
  // spiral is refined the same way:
  //   P(φ) = c + r(φ)·e_r + φ·k·n,  r(φ) = r0 + q·φ,  q = Δr / sweep,  k = rise / sweep
  //   e_r = cos φ·u + sin φ·w,  e_θ = −sin φ·u + cos φ·w
  //   P' = r·e_θ + q·e_r + k·n,  P'' = −r·e_r + 2q·e_θ
  //   f'(φ) = (P − p)·P',  f''(φ) = |P'|² + (P − p)·P''
  const Vec3 q = p - center_;
  const double two_pi = 2.0 * std::numbers::pi;
  double best = std::min((a - p).norm(), (b - p).norm());
  double rel = std::atan2(q.dot(w_), q.dot(u_));
  if (rel < 0.0) rel += two_pi;
  const bool helix = helix_h_ != 0.0;
  double best_ang = -1.0;
  for (double ang = rel; ang <= sweep_; ang += two_pi) {
    const double d = (at(ang / sweep_ * length_).head<3>() - p).norm();
    if (d < best) {
      best = d;
      best_ang = ang;
    }
  }
  if (!helix && dr_ == 0.0) return best;
  // the polar angle's best turn (or the end nearest), and a turn either side
  // of it, each walked in by Newton: a few steps each, whatever the turns
  const double k = helix_h_ / sweep_, dr_dphi = dr_ / sweep_;
  const double from = best_ang >= 0.0 ? best_ang : ((a - p).norm() <= (b - p).norm() ? 0.0 : sweep_);
  for (const double start : {from - two_pi, from, from + two_pi}) {
    double phi = std::clamp(start, 0.0, sweep_);
    for (int it = 0; it < kHelixNewtonSteps; ++it) {
      const double c = std::cos(phi), sn = std::sin(phi), r = radius_ + dr_dphi * phi;
      const Vec3 e_r = c * u_ + sn * w_, e_t = -sn * u_ + c * w_;
      const Vec3 d = center_ + r * e_r + (phi * k) * axis_n_ - p;
      const Vec3 d1 = r * e_t + dr_dphi * e_r + k * axis_n_;
      const double f1 = d.dot(d1);
      const double f2 = d1.squaredNorm() + d.dot(2.0 * dr_dphi * e_t - r * e_r);
      if (!(f2 > 0.0)) break;
      const double next = std::clamp(phi - f1 / f2, 0.0, sweep_);
      if (next == phi) break;
      phi = next;
    }
    best = std::min(best, (at(phi / sweep_ * length_).head<3>() - p).norm());
  }
  return best;
}

std::vector<Pose> arc_chord_ends(const Segment& arc, double sag_mm) {
  const SegmentGeometry g(arc);
  const double r = std::max(g.radius_max(), 1e-9);
  const double dphi = 2.0 * std::acos(std::max(-1.0, 1.0 - sag_mm / r));
  const auto n = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(g.sweep_rad() / dphi)));
  std::vector<Pose> out;
  out.reserve(n);
  for (std::size_t k = 1; k < n; ++k)
    out.push_back(g.at(g.length() * static_cast<double>(k) / static_cast<double>(n)));
  out.push_back(arc.end);
  return out;
}

}  // namespace lcnc
