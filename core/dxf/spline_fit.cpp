#include "dxf/spline_fit.h"

#include <cstddef>
#include <vector>

#include "dxf/dxf_tolerances.h"

namespace lcnc::dxf {

bool interpolate_fit_points(SplineData& s, std::string* why) {
  // Repeated fit points would make an interval of zero length.
  std::vector<Vec2> q;
  for (const Vec2& p : s.fit) {
    if (q.empty() || (p - q.back()).norm() > kMinEdgeMm) q.push_back(p);
  }
  if (q.size() < 2) {
    if (why) *why = "fewer than 2 distinct fit points; expected at least 2";
    return false;
  }
  const std::size_t n = q.size() - 1;  // pieces
  std::vector<double> h(n);
  for (std::size_t i = 0; i < n; ++i) h[i] = (q[i + 1] - q[i]).norm();

  // The tridiagonal system a_i·D_{i−1} + b_i·D_i + c_i·D_{i+1} = r_i, i = 0..n.
  std::vector<double> a(n + 1, 0.0), b(n + 1, 0.0), c(n + 1, 0.0);
  std::vector<Vec2> r(n + 1, Vec2::Zero());
  if (s.start_tangent) {
    b[0] = 1.0;
    r[0] = s.start_tangent->normalized();
  } else {
    b[0] = 2.0;
    c[0] = 1.0;
    r[0] = 3.0 * (q[1] - q[0]) / h[0];
  }
  for (std::size_t i = 1; i < n; ++i) {
    a[i] = h[i];
    b[i] = 2.0 * (h[i - 1] + h[i]);
    c[i] = h[i - 1];
    r[i] = 3.0 * (h[i] * (q[i] - q[i - 1]) / h[i - 1] + h[i - 1] * (q[i + 1] - q[i]) / h[i]);
  }
  if (s.end_tangent) {
    b[n] = 1.0;
    r[n] = s.end_tangent->normalized();
  } else {
    a[n] = 1.0;
    b[n] = 2.0;
    r[n] = 3.0 * (q[n] - q[n - 1]) / h[n - 1];
  }
  // Thomas algorithm: the matrix is diagonally dominant (b_i ≥ a_i + c_i,
  // strictly at the ends or in the rows between), so no pivoting is needed.
  for (std::size_t i = 1; i <= n; ++i) {
    const double m = a[i] / b[i - 1];
    b[i] -= m * c[i - 1];
    r[i] -= m * r[i - 1];
  }
  std::vector<Vec2> d(n + 1);
  d[n] = r[n] / b[n];
  for (std::size_t i = n; i-- > 0;) d[i] = (r[i] - c[i] * d[i + 1]) / b[i];

  s.degree = 3;
  s.weights.clear();
  s.control.clear();
  s.knots.clear();
  double t = 0.0;
  s.knots.insert(s.knots.end(), 4, 0.0);
  s.control.push_back(q[0]);
  for (std::size_t i = 0; i < n; ++i) {
    s.control.push_back(q[i] + h[i] * d[i] / 3.0);
    s.control.push_back(q[i + 1] - h[i] * d[i + 1] / 3.0);
    s.control.push_back(q[i + 1]);
    t += h[i];
    s.knots.insert(s.knots.end(), i + 1 < n ? 3 : 4, t);
  }
  return true;
}

}  // namespace lcnc::dxf
