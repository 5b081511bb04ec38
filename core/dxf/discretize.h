// Discretization of a contour into n equal steps (Kondratenko et al. 2015: "the whole
// contour S is split into n equal, consecutive pieces of length Δφ").
//
// n = max(kMinContourPoints, ⌈L / step⌉), Δ = L / n ≤ step: the points lie on
// the exact curve at arc lengths 0, Δ, 2Δ, …, (n − 1)Δ; the contour is closed,
// so point n is point 0 again and is not stored. A chord is at most Δ long
// (shorter on arcs by at most Δ³/(24 r²)), and the chord's distance from an
// arc of radius r is at most Δ²/(8r).
#pragma once

#include <cstdint>
#include <vector>

#include "common/result.h"
#include "dxf/drawing.h"

namespace lcnc::dxf {

struct Polyline {
  std::uint32_t contour = 0;            // Contour::index
  std::vector<Vec2> pts;                // n points, closed (pts[n] ≡ pts[0])
  std::vector<std::uint32_t> src_line;  // DXF line of the entity each point lies on
  double length_mm = 0.0;               // L, of the exact contour
  double step_mm = 0.0;                 // Δ = L / n

  [[nodiscard]] std::size_t size() const { return pts.size(); }
};

[[nodiscard]] Polyline discretize(const Contour& c, double step_mm);

// All contours of a drawing; errors when the step is below kMinStepMm or
// the point count would pass kMaxDrawingPoints.
[[nodiscard]] Result<std::vector<Polyline>> discretize_all(const std::vector<Contour>& cs, double step_mm,
                                                           const std::string& file);

}  // namespace lcnc::dxf
