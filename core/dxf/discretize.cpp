#include "dxf/discretize.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "dxf/dxf_tolerances.h"

namespace lcnc::dxf {
namespace {

std::size_t point_count(double length_mm, double step_mm) {
  const double n = std::ceil(length_mm / step_mm - 1e-9);
  return std::max<std::size_t>(kMinContourPoints, static_cast<std::size_t>(std::max(n, 0.0)));
}

}  // namespace

Polyline discretize(const Contour& c, double step_mm) {
  Polyline p;
  p.contour = c.index;
  std::vector<double> cum(c.edges.size() + 1, 0.0);  // arc length at each edge start
  for (std::size_t i = 0; i < c.edges.size(); ++i) cum[i + 1] = cum[i] + edge_length(c.edges[i]);
  p.length_mm = cum.back();
  const std::size_t n = point_count(p.length_mm, step_mm);
  p.step_mm = p.length_mm / static_cast<double>(n);
  p.pts.reserve(n);
  p.src_line.reserve(n);
  std::size_t e = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) * p.step_mm;  // kΔ, not a running sum
    while (e + 1 < c.edges.size() && cum[e + 1] <= s) ++e;
    p.pts.push_back(edge_point(c.edges[e], std::min(s - cum[e], cum[e + 1] - cum[e])));
    p.src_line.push_back(c.edges[e].line);
  }
  return p;
}

Result<std::vector<Polyline>> discretize_all(const std::vector<Contour>& cs, double step_mm,
                                             const std::string& file) {
  if (!(step_mm >= kMinStepMm * (1.0 - 1e-9))) {
    return make_error(ErrorCode::DecomposeBadOption,
                      "discretization step " + std::to_string(step_mm) + " mm; expected at least " +
                          std::to_string(kMinStepMm) + " mm (1 µm)",
                      file);
  }
  double total = 0.0;
  for (const Contour& c : cs) total += static_cast<double>(point_count(c.length(), step_mm));
  if (total > static_cast<double>(kMaxDrawingPoints)) {
    return make_error(ErrorCode::DecomposeBadOption,
                      "step " + std::to_string(step_mm) + " mm gives " +
                          std::to_string(static_cast<long long>(total)) + " points; expected at most " +
                          std::to_string(kMaxDrawingPoints) + " (use a coarser step)",
                      file);
  }
  std::vector<Polyline> out;
  out.reserve(cs.size());
  for (const Contour& c : cs) out.push_back(discretize(c, step_mm));
  return out;
}

}  // namespace lcnc::dxf
