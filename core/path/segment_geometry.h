// Geometry of a motion segment, parametrised by path length s ∈ [0, length].
//
// Path length is measured in the linear axes (mm) when X, Y or Z move, else in
// the rotary axes (deg) — as RS274NGC measures feed. Every axis moves in
// proportion: a line is p(s) = start + (end − start)·s/L. An arc (helix) of
// radius r turns by φ(s) = sweep·s/L about its centre c in the plane spanned by
// the unit vectors u (centre → start) and w = n × u (n the unit normal about
// which the arc turns counter-clockwise):
//   xyz(s) = c + r·(cos φ·u + sin φ·w) + (s/L)·h·n̂,   L = sqrt((r·sweep)² + h²)
// with h the travel along the plane's normal axis n̂ (helix): a named plane's
// normal axis, or a Free plane's normal (the start's plane; the centre is
// taken into it); the rotary axes move linearly with s. An arc whose end
// comes back onto its start (to kFullTurnAngle) is a full turn.
//
// Curve (Segment::curve, a piece of a smooth joint path): the cubic Hermite
// curve of σ = s/L ∈ [0, 1] with dp/dσ = d0 at the start and d1 at the end,
//   p(σ) = (2σ³ − 3σ² + 1)·p0 + (σ³ − 2σ² + σ)·d0 + (3σ² − 2σ³)·p1 + (σ³ − σ²)·d1
// in every axis, L = Segment::curve_length: the curve's own parameter
// scaled (the move's parameter under tool-centre-point control), so dp/ds
// = d/L at the ends whatever the arc length, and two pieces whose d/L match
// join with no jump in any axis' velocity at any path speed. |dp/ds| need
// not be 1 inside: the planner's limits take the axes' rates as they are.
//
// Spiral: when the end lies at another distance from the centre than the
// start (G-code accepts IJK arcs whose two radii differ within a tolerance),
// the radius changes linearly with the angle, r(φ) = r0 + Δr·φ/sweep, so the
// path ends exactly on its end point instead of jumping there. With
// q = Δr/sweep, P'(φ) = r·e_θ + q·e_r + (h/sweep)·n̂ has |P'| ≤
// sqrt(r_max² + q² + (h/sweep)²), and the length is taken as that bound
// times the sweep:
//   L = sqrt((r_max·sweep)² + Δr² + h²)
// so |dp/ds| ≤ 1 everywhere: the path speed never exceeds the planned one
// (where the radius is smaller it runs slower, by at most Δr/r_max). The
// planner holds a spiral to limits lowered by its spiral_excess() (see
// segment_limits). Below kSpiralMinMm of difference an arc is a circle.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geom/pose.h"
#include "path/segment.h"

namespace lcnc {

namespace detail {

// sin φ and cos φ; small angles (every sample of a corner blend) by their
// series: for |φ| ≤ 1/64 the terms left out are below 1e-20 of the result,
// far under a double's rounding, and there is no library call. (Factors,
// not divisions: the coarse interpolator asks every period.)
inline void sin_cos(double phi, double& s, double& c) noexcept {
  if (std::abs(phi) <= 0.015625) {
    constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0;
    constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0;
    const double p2 = phi * phi;
    s = phi * (1.0 - p2 * k6 * (1.0 - p2 * k20 * (1.0 - p2 * k42)));
    c = 1.0 - p2 * 0.5 * (1.0 - p2 * k12 * (1.0 - p2 * k30 * (1.0 - p2 * k56)));
    return;
  }
  s = std::sin(phi);
  c = std::cos(phi);
}

}  // namespace detail

// Indices (0..2) of the first, second and normal axis of a named arc plane.
struct PlaneAxes {
  int first, second, normal;
};
[[nodiscard]] PlaneAxes plane_axes(Plane plane) noexcept;

// Distance from p to the straight segment a–b (a point when a == b).
[[nodiscard]] double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) noexcept;

// Path length of a segment: SegmentGeometry(seg).length(), straight from the
// end points for lines.
[[nodiscard]] double path_length(const Segment& seg);

class SegmentGeometry {
 public:
  explicit SegmentGeometry(const Segment& seg) { set(seg); }
  // The same, in place: *this = SegmentGeometry(seg) without a temporary (a
  // few hundred bytes built on the stack and copied again, per segment).
  void set(const Segment& seg);
  // A circular arc (no helix) whose parts are already known — a corner
  // blend's, from its construction: as SegmentGeometry(seg) of the arc from
  // start to end about `center`, turning by the angle whose sine and cosine
  // are given (0 < sweep < 2π) from unit u toward unit w (w ⊥ u); rotary
  // axes linear from start to end.
  // (Set in place: a blend's geometry goes straight where it is kept.)
  void set_circular_arc(const Pose& start, const Pose& end, const Vec3& center, const Vec3& u, const Vec3& w,
                        double radius, double sin_sweep, double cos_sweep);

  [[nodiscard]] double length() const noexcept { return length_; }
  [[nodiscard]] bool is_arc() const noexcept { return arc_; }
  // A piece of a smooth curve (Segment::curve): dp/ds and d²p/ds² vary.
  [[nodiscard]] bool is_curve() const noexcept { return curve_; }
  // A curve's dp/dσ and d²p/dσ² at σ = s/L ∈ [0, 1].
  [[nodiscard]] Pose curve_d1(double f) const;
  [[nodiscard]] Pose curve_d2(double f) const;
  // distance_xyz() on a curve: this many + 1 points, then this many
  // golden-section steps about each local nearest (the bracket shrinks to 10⁻⁹ of the piece).
  static constexpr int kCurveChords = 16;
  static constexpr int kCurveSearchSteps = 40;
  // Radius at the start; on a spiral also the largest radius and the change.
  [[nodiscard]] double radius() const noexcept { return radius_; }
  [[nodiscard]] double radius_max() const noexcept { return radius_ + std::max(0.0, dr_); }
  [[nodiscard]] bool is_spiral() const noexcept { return dr_ != 0.0; }
  // (|Δr| + |Δr|/sweep) / r_max: how far a spiral's velocity (per unit of
  // path speed, over the plane speed ratio) and its acceleration terms may
  // stray from the circle of radius_max() that the limits are computed for;
  // 0 for circles and lines.
  [[nodiscard]] double spiral_excess() const noexcept { return spiral_excess_; }
  // The helix part of the tangent, (h/L)·n̂ (zero for plane arcs and lines).
  [[nodiscard]] Vec3 helix_rate() const noexcept { return (helix_h_ * inv_length_) * axis_n_; }
  // Differences of the radii up to kSpiralMinMm + kSpiralMinRel·r are
  // rounding (the centre of a corner blend of a nearly straight corner is
  // computed from a radius of kilometres): the arc is a circle.
  static constexpr double kSpiralMinMm = 1e-9;
  static constexpr double kSpiralMinRel = 1e-12;
  [[nodiscard]] static bool radii_differ(double r_start, double r_end) noexcept {
    return std::abs(r_end - r_start) > kSpiralMinMm + kSpiralMinRel * std::max(r_start, r_end);
  }
  // Total sweep angle of an arc (rad, > 0, about the turning normal), incl. turns.
  [[nodiscard]] double sweep_rad() const noexcept { return sweep_; }
  // The sine and cosine of sweep_rad(), computed once.
  [[nodiscard]] double sin_sweep() const noexcept { return sin_sweep_; }
  [[nodiscard]] double cos_sweep() const noexcept { return cos_sweep_; }
  // In-plane unit vectors of an arc (u: centre → start, w: start tangent).
  [[nodiscard]] const Vec3& u() const noexcept { return u_; }
  [[nodiscard]] const Vec3& w() const noexcept { return w_; }
  // Position at path length s (clamped to [0, L]).
  [[nodiscard]] Pose at(double s) const {
    Pose p;
    at(s, p);
    return p;
  }
  // The same, written into p (inline, in place: the coarse interpolator asks
  // every period, and a pose built on the stack by parts and then copied
  // whole makes the copy wait for the parts' stores).
  void at(double s, Pose& p) const;
  // dp/ds: per-axis rate of change (the unit tangent in path units).
  [[nodiscard]] Pose tangent(double s) const;
  // dp/ds at the start and at the end: equal to tangent(0) and tangent(length()),
  // without evaluating sin and cos (those of the sweep are kept).
  [[nodiscard]] Pose start_tangent() const;
  [[nodiscard]] Pose end_tangent() const;
  // d²p/ds²: the curvature vector (zero on lines).
  [[nodiscard]] Pose curvature(double s) const;
  // Fraction of the path speed seen in the arc plane (r·sweep / L); 0 for lines.
  [[nodiscard]] double plane_speed_ratio() const noexcept { return plane_ratio_; }
  // Closest distance from a linear-axes point to this segment's XYZ path
  // (mm). On a curve, when a bound shows it is at least `below`, that bound
  // instead (a value ≥ below: a caller taking the least of several loses
  // nothing, and skips the search on the curves that are far).
  [[nodiscard]] double distance_xyz(const Vec3& p,
                                    double below = std::numeric_limits<double>::infinity()) const;
  // Newton steps that refine a helix's closest point (distance_xyz):
  // quadratic convergence from the polar angle, a few are exact to rounding.
  static constexpr int kHelixNewtonSteps = 8;

 private:
  [[nodiscard]] double angle_at(double s) const noexcept;
  // sin and cos of the sweep, from the end point's coordinates (y, x) about the centre
  void set_sin_cos_sweep(double y, double x) noexcept;
  // dp/ds at arc angle φ = f·sweep, given f, sin φ and cos φ.
  [[nodiscard]] Pose tangent_at_angle(double f, double sin_phi, double cos_phi) const;
  // the radius and, for a spiral, the length and ratios from the sweep
  void set_spiral(double r_end);

  Pose start_, end_;
  bool arc_ = false;
  bool curve_ = false;
  Pose d0_ = Pose::Zero(), d1_ = Pose::Zero();  // a curve's dp/dσ at its ends
  Vec3 center_ = Vec3::Zero();
  Vec3 u_ = Vec3::UnitX(), w_ = Vec3::UnitY();
  Vec3 axis_n_ = Vec3::Zero();  // helix direction (unit) or zero
  double helix_h_ = 0.0;        // travel along axis_n_
  double radius_ = 0.0, sweep_ = 0.0, length_ = 0.0, plane_ratio_ = 0.0;
  double dr_ = 0.0;  // spiral: end radius − start radius (0: a circle)
  double spiral_excess_ = 0.0;
  double inv_length_ = 0.0;                   // 1/length_ (0 for no length): at() is asked every period
  double sin_sweep_ = 0.0, cos_sweep_ = 1.0;  // of sweep_ (arcs): the end tangent, the limits
};

inline void SegmentGeometry::at(double s, Pose& p) const {
  const double f = std::max(0.0, s * inv_length_);
  if (length_ <= 0.0 || s >= length_ || f >= 1.0) {
    p = end_;
    return;
  }
  if (curve_) {
    const double f2 = f * f, f3 = f2 * f;
    p = (2.0 * f3 - 3.0 * f2 + 1.0) * start_ + (f3 - 2.0 * f2 + f) * d0_ + (3.0 * f2 - 2.0 * f3) * end_ +
        (f3 - f2) * d1_;
    return;
  }
  if (!arc_) {
    p = start_ + (end_ - start_) * f;
    return;
  }
  // the rotary axes linearly, X Y Z on the circle (the helix along its axis)
  p.tail<3>() = start_.tail<3>() + (end_.tail<3>() - start_.tail<3>()) * f;
  double sin_phi, cos_phi;
  detail::sin_cos(sweep_ * f, sin_phi, cos_phi);
  p.head<3>() = center_ + (radius_ + f * dr_) * (cos_phi * u_ + sin_phi * w_) + (f * helix_h_) * axis_n_;
}

// The chord end points of an arc (its end included, its start not) whose
// sag r·(1 − cos(Δφ/2)) is at most sag_mm (> 0): where an arc is replaced by
// lines (a helix on a tilted head, an arc under a rotating map).
[[nodiscard]] std::vector<Pose> arc_chord_ends(const Segment& arc, double sag_mm);

}  // namespace lcnc
