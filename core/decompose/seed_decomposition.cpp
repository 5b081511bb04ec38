#include "decompose/seed_decomposition.h"

#include <cmath>
#include <numbers>

#include "common/error.h"

namespace lcnc::decompose {

Result<std::vector<Vec2>> seed_smooth(const std::vector<Vec2>& s, double critical_angle_deg) {
  const std::size_t n = s.size();
  const double cos_crit = std::cos(critical_angle_deg * std::numbers::pi / 180.0);
  // A closed polygon turns 360° in all: with at most θc per vertex it needs
  // more than 360/θc vertices, or the walk would shrink it forever.
  if (static_cast<double>(n) * critical_angle_deg <= 360.0) {
    return make_error(ErrorCode::DecomposeBadOption,
                      "seed smoothing: " + std::to_string(n) + " points × critical angle " +
                          std::to_string(critical_angle_deg) +
                          "° cannot turn 360°; expected a larger critical angle or a finer step");
  }
  std::vector<Vec2> q = s;
  auto prev = [n](std::size_t j) { return j == 0 ? n - 1 : j - 1; };
  auto next = [n](std::size_t j) { return j + 1 == n ? 0 : j + 1; };
  const std::size_t max_replacements = kSeedMaxReplacementsPerPoint * n;
  std::size_t replacements = 0;
  std::size_t unchanged = 0;  // vertices passed in a row without a change
  std::size_t j = 0;
  while (unchanged < n) {
    const Vec2 d1 = q[j] - q[prev(j)];
    const Vec2 d2 = q[next(j)] - q[j];
    const double l = d1.norm() * d2.norm();
    const double alpha = l > 0.0 ? d1.dot(d2) / l : 1.0;  // eq. 1 (cosine of the turn)
    if (alpha < cos_crit) {
      q[j] = q[prev(j)] + 0.5 * (q[next(j)] - q[prev(j)]);  // eq. 2, 3
      if (++replacements > max_replacements) {
        return make_error(ErrorCode::DecomposeInfeasible,
                          "seed smoothing does not settle after " + std::to_string(replacements) +
                              " vertex replacements; expected a larger critical angle or a "
                              "finer step");
      }
      unchanged = 0;
      j = prev(j);  // step back: the angle at the previous vertex changed
    } else {
      ++unchanged;  // eq. 4, 5: the point stays
      j = next(j);
    }
  }
  return q;
}

Result<KinematicsTable> seed_decompose(const dxf::Polyline& s, const Options& opt) {
  Result<std::vector<Vec2>> s1 = seed_smooth(s.pts, opt.critical_angle_deg);
  if (!s1) return s1.error();
  const std::size_t n = s.size();
  KinematicsTable t;
  t.contour = s.contour;
  t.beam.reserve(n + 1);
  t.main.reserve(n + 1);
  t.t_s.reserve(n + 1);
  const double vk = opt.speed_mm_s;
  const double v0 = vk / 2.0;  // eq. 6
  for (std::size_t i = 0; i <= n; ++i) {
    const std::size_t k = i % n;
    t.beam.push_back(s.pts[k]);
    t.main.push_back((*s1)[k]);
    if (i == 0) {
      t.t_s.push_back(0.0);
      continue;
    }
    const std::size_t km = i - 1;
    const Vec2 step_s = s.pts[k] - s.pts[km];
    const Vec2 step_s1 = (*s1)[k] - (*s1)[km];
    const double h1 = step_s1.norm();
    const double h2 = (step_s - step_s1).norm();  // S2 = S − S1, vector by vector
    // eq. 7–11: v1 = 2 v0 h1 / (h1 + h2), Δt = h1 / v1 = (h1 + h2) / vk.
    t.t_s.push_back(t.t_s.back() + (h1 + h2) / vk);
  }
  // v1 = h1/Δt = 2 v0 k1 and v2 = h2/Δt = 2 v0 k2 exactly, so the common
  // derivative pass gives eq. 9, 10, 12, 13.
  fill_derivatives(t, v0, v0);
  // Row n is row 0 again: the loop's accelerations there, not a jump.
  std::vector<Vec2> aux(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) aux[i] = t.aux(i);
  t.a_main[0] = t.a_main[n] = loop_accel(t.main, t.t_s, 0, n);
  t.a_aux[0] = t.a_aux[n] = loop_accel(aux, t.t_s, 0, n);
  t.a_eff[0] = t.a_eff[n] = loop_accel(t.beam, t.t_s, 0, n);
  return t;
}

}  // namespace lcnc::decompose
