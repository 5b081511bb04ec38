#include "dxf/spline_curve.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dxf/dxf_tolerances.h"
#include "dxf/spline_fit.h"

namespace lcnc::dxf {
namespace {

double dist_to_chord(const Vec2& q, const Vec2& a, const Vec2& b) {
  // plain doubles: the table's inner loop
  const double abx = b.x() - a.x(), aby = b.y() - a.y();
  const double aqx = q.x() - a.x(), aqy = q.y() - a.y();
  const double l2 = abx * abx + aby * aby;
  if (l2 <= 0.0) return std::sqrt(aqx * aqx + aqy * aqy);
  const double t = std::clamp((aqx * abx + aqy * aby) / l2, 0.0, 1.0);
  const double dx = aqx - t * abx, dy = aqy - t * aby;
  return std::sqrt(dx * dx + dy * dy);
}

// Arc length to this precision (mm): far below the 1 µm grid, so equal
// steps stay equal to the last digit the CSV prints.
constexpr double kArcLengthTolMm = 1e-10;

}  // namespace

std::shared_ptr<const SplineCurve> SplineCurve::make(const SplineData& given, std::string* why,
                                                     std::size_t max_nodes) {
  SplineData fitted;
  if (given.control.empty() && !given.fit.empty()) {
    fitted = given;
    if (!interpolate_fit_points(fitted, why)) return nullptr;
  }
  const SplineData& s = fitted.control.empty() ? given : fitted;
  const std::size_t n = s.control.size();
  const auto p = static_cast<std::size_t>(std::max(s.degree, 0));
  auto fail = [&](std::string msg) {
    if (why) *why = std::move(msg);
    return std::shared_ptr<const SplineCurve>();
  };
  if (s.degree < 1 || s.degree > kSplineMaxDegree) {
    return fail("degree " + std::to_string(s.degree) + "; expected 1 to " + std::to_string(kSplineMaxDegree));
  }
  if (n == 0) {
    return fail("no control points and no fit points; expected either");
  }
  if (n < p + 1) {
    return fail(std::to_string(n) + " control points for degree " + std::to_string(p) +
                "; expected at least " + std::to_string(p + 1));
  }
  if (s.knots.size() != n + p + 1) {
    return fail(std::to_string(s.knots.size()) + " knots for " + std::to_string(n) +
                " control points of degree " + std::to_string(p) + "; expected " + std::to_string(n + p + 1));
  }
  for (std::size_t i = 1; i < s.knots.size(); ++i) {
    if (!(s.knots[i] >= s.knots[i - 1])) {
      return fail("knots decrease; expected a non-decreasing knot vector");
    }
  }
  if (!s.weights.empty()) {
    if (s.weights.size() != n) return fail("weights and control points differ in number");
    for (double w : s.weights) {
      if (!(w > 0.0)) return fail("a weight <= 0; expected positive weights");
    }
  }
  if (!(s.knots[n] > s.knots[p])) return fail("empty parameter range (all knots equal)");
  std::shared_ptr<SplineCurve> c(new SplineCurve(s, max_nodes));
  if (c->too_many_nodes()) {
    Vec2 lo = s.control.front(), hi = lo;
    for (const Vec2& q : s.control) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "a curve spanning %.6g mm needs more than %zu pieces; expected a part of machine "
                  "size (are the drawing's units right?)",
                  (hi - lo).norm(), max_nodes);
    return fail(msg);
  }
  if (!(c->length() > 0.0)) return fail("zero length");
  return c;
}

SplineCurve::SplineCurve(SplineData d, std::size_t max_nodes) : d_(std::move(d)), max_nodes_(max_nodes) {
  for (std::size_t i = 0; i < d_.control.size(); ++i) {
    const double w = d_.weights.empty() ? 1.0 : d_.weights[i];
    pw_.emplace_back(w * d_.control[i].x(), w * d_.control[i].y(), w);
  }
  const auto p = static_cast<std::size_t>(d_.degree);
  const std::size_t n = d_.control.size();
  for (std::size_t k = p; k < n; ++k) {
    const double u0 = d_.knots[k], u1 = d_.knots[k + 1];
    if (!(u1 > u0)) continue;
    if (u_.empty()) {
      u_.push_back(u0);
      s_.push_back(0.0);
    }
    subdivide(u0, at_param(u0), u1, at_param(u1), at_param(0.5 * (u0 + u1)), 0);
    if (too_many_nodes()) return;
  }
}

void SplineCurve::subdivide(double u0, const Vec2& p0, double u1, const Vec2& p1, const Vec2& pm, int depth) {
  if (too_many_nodes()) return;  // make() refuses the curve
  // pm = C(middle) comes from the parent (its quarter point): two new
  // evaluations per interval instead of three.
  const double um = 0.5 * (u0 + u1);
  const Vec2 qa = at_param(0.5 * (u0 + um)), qb = at_param(0.5 * (um + u1));
  if (depth < kSplineMaxDepth &&
      (depth < 2 || dist_to_chord(pm, p0, p1) > kSplineFlatnessMm ||
       dist_to_chord(qa, p0, p1) > kSplineFlatnessMm || dist_to_chord(qb, p0, p1) > kSplineFlatnessMm)) {
    subdivide(u0, p0, um, pm, qa, depth + 1);
    subdivide(um, pm, u1, p1, qb, depth + 1);
    return;
  }
  s_.push_back(s_.back() + arc(u0, u1));
  u_.push_back(u1);
}

std::size_t SplineCurve::span(double u) const {
  const auto p = static_cast<std::size_t>(d_.degree);
  const std::size_t n = d_.control.size();
  // The last k in [p, n−1] with U_k ≤ u (and U_k < U_k+1).
  std::size_t k = static_cast<std::size_t>(std::upper_bound(d_.knots.begin() + static_cast<long>(p),
                                                            d_.knots.begin() + static_cast<long>(n), u) -
                                           d_.knots.begin()) -
                  1;
  k = std::clamp(k, p, n - 1);
  while (k > p && !(d_.knots[k + 1] > d_.knots[k])) --k;
  return k;
}

SplineCurve::Eval SplineCurve::eval(double u) const {
  // de Boor in homogeneous coordinates: after p − 1 levels the two points
  // left, Q0 and Q1, span the last one linearly over [U_k, U_k+1], so the
  // homogeneous curve is (1 − a)·Q0 + a·Q1 and its derivative
  // p·(Q1 − Q0)/(U_k+1 − U_k). Plain arrays: this is the table's inner loop.
  const auto p = static_cast<std::size_t>(d_.degree);
  const std::size_t k = span(u);
  const double* U = d_.knots.data();
  double x[kSplineMaxDegree + 1], y[kSplineMaxDegree + 1], w[kSplineMaxDegree + 1];
  for (std::size_t j = 0; j <= p; ++j) {
    const Eigen::Vector3d& q = pw_[j + k - p];
    x[j] = q.x();
    y[j] = q.y();
    w[j] = q.z();
  }
  for (std::size_t r = 1; r < p; ++r) {
    for (std::size_t j = p; j >= r; --j) {
      const std::size_t i = j + k - p;
      const double den = U[i + p + 1 - r] - U[i];
      const double a = den > 0.0 ? (u - U[i]) / den : 0.0;
      x[j] = (1.0 - a) * x[j - 1] + a * x[j];
      y[j] = (1.0 - a) * y[j - 1] + a * y[j];
      w[j] = (1.0 - a) * w[j - 1] + a * w[j];
    }
  }
  const double den = U[k + 1] - U[k];  // > 0: span() picks a non-empty span
  const double a = (u - U[k]) / den, g = static_cast<double>(p) / den;
  const double cx = (1.0 - a) * x[p - 1] + a * x[p], cy = (1.0 - a) * y[p - 1] + a * y[p];
  const double cw = (1.0 - a) * w[p - 1] + a * w[p];
  const double dx = g * (x[p] - x[p - 1]), dy = g * (y[p] - y[p - 1]), dw = g * (w[p] - w[p - 1]);
  Eval e;
  e.point = Vec2(cx / cw, cy / cw);
  e.tangent = Vec2((dx - dw * e.point.x()) / cw, (dy - dw * e.point.y()) / cw);  // (A' − w'·C) / w
  return e;
}

Vec2 SplineCurve::at_param(double u) const { return eval(u).point; }

double SplineCurve::speed(double u) const { return eval(u).tangent.norm(); }

double SplineCurve::arc(double u0, double u1) const {
  // 5-point Gauss–Legendre on [u0, u1].
  static constexpr double kX[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                   0.9061798459386640};
  static constexpr double kW[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                   0.2369268850561891, 0.2369268850561891};
  const double c = 0.5 * (u0 + u1), h = 0.5 * (u1 - u0);
  double sum = 0.0;
  for (int i = 0; i < 5; ++i) sum += kW[i] * speed(c + h * kX[i]);
  return sum * h;
}

Vec2 SplineCurve::at_length(double s) const {
  s = std::clamp(s, 0.0, length());
  const std::size_t j = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin()), s_.size() - 1);
  const std::size_t j0 = j == 0 ? 0 : j - 1;
  const double ua = u_[j0], ub = u_[j0 + 1 < u_.size() ? j0 + 1 : j0];
  const double sa = s_[j0], sb = s_[j0 + 1 < s_.size() ? j0 + 1 : j0];
  if (!(sb > sa)) return at_param(ua);
  double u = ua + (s - sa) / (sb - sa) * (ub - ua);
  for (int it = 0; it < 8; ++it) {
    const double f = sa + arc(ua, u) - s;
    if (std::abs(f) <= kArcLengthTolMm) break;
    const double v = speed(u);
    if (!(v > 0.0)) break;
    u = std::clamp(u - f / v, ua, ub);
  }
  return at_param(u);
}

}  // namespace lcnc::dxf
