// A DXF SPLINE (a NURBS curve), sampled at exact arc lengths.
//
// C(u) = Σ N_i,p(u)·w_i·P_i / Σ N_i,p(u)·w_i over u ∈ [U_p, U_n] (n control
// points P_i with weights w_i, degree p, knot vector U of n + p + 1 values),
// evaluated by de Boor's algorithm in homogeneous coordinates.
//
// Discretization needs the point at arc length s, and the points must lie on
// the curve with equal spacing (a flattened polyline would put the curvature
// into its vertices and make the accelerations computed from the points
// jump). So: nodes u_j where each knot span is halved until the curve stays
// within kSplineFlatnessMm of the chord; S(u_j) by 5-point Gauss–Legendre on
// each node interval; at_length(s) finds the interval, then solves
// S(u) = s by Newton's method (S' = |C'(u)|) to 1e-10 mm.
#pragma once

#include "dxf/dxf_tolerances.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace lcnc::dxf {

using Vec2 = Eigen::Vector2d;

struct SplineData {
  int degree = 3;
  std::vector<double> knots;
  std::vector<Vec2> control;
  std::vector<double> weights;  // empty = all 1
  // Fit points: the curve when there are no control points (spline_fit.h
  // interpolates them), else only informative. The end tangents (DXF codes
  // 12/22, 13/23) when the file gives them.
  std::vector<Vec2> fit;
  std::optional<Vec2> start_tangent, end_tangent;
};

class SplineCurve {
 public:
  // The curve, or nullptr with the reason in `why` (knot count, order,
  // weights, too few fit points, a curve too long for its table). A spline
  // of fit points only is the cubic through them (spline_fit.h).
  // At most max_nodes table nodes (kSplineMaxNodes, or what a drawing has left).
  [[nodiscard]] static std::shared_ptr<const SplineCurve> make(const SplineData& s, std::string* why,
                                                               std::size_t max_nodes = kSplineMaxNodes);

  [[nodiscard]] double length() const { return s_.back(); }
  [[nodiscard]] std::size_t nodes() const noexcept { return u_.size(); }
  [[nodiscard]] Vec2 start() const { return at_param(u_.front()); }
  [[nodiscard]] Vec2 end() const { return at_param(u_.back()); }
  // The point at arc length s ∈ [0, length()] from the start.
  [[nodiscard]] Vec2 at_length(double s) const;
  [[nodiscard]] Vec2 at_param(double u) const;

 private:
  SplineCurve(SplineData d, std::size_t max_nodes);
  struct Eval {
    Vec2 point;    // C(u)
    Vec2 tangent;  // C'(u)
  };
  [[nodiscard]] Eval eval(double u) const;
  [[nodiscard]] std::size_t span(double u) const;
  [[nodiscard]] double speed(double u) const;            // |C'(u)|
  [[nodiscard]] double arc(double u0, double u1) const;  // Gauss–Legendre
  void subdivide(double u0, const Vec2& p0, double u1, const Vec2& p1, const Vec2& pm, int depth);
  [[nodiscard]] bool too_many_nodes() const noexcept { return u_.size() > max_nodes_; }

  SplineData d_;
  std::size_t max_nodes_;
  std::vector<Eigen::Vector3d> pw_;  // (w·x, w·y, w)
  std::vector<double> u_;            // nodes
  std::vector<double> s_;            // arc length at each node
};

}  // namespace lcnc::dxf
