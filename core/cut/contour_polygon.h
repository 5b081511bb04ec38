// A contour of the drawing as the polygon the cutting works on: lines keep
// their end points exactly (corners stay corners), arcs and circles become
// chords whose sagitta r·(1 − cos(φ/2)) is at most kChordToleranceMm
// (n = ⌈|sweep| / φ⌉ equal pieces, φ = 2·acos(1 − tol/r)), splines are halved
// in arc length until each chord's midpoint is within the tolerance. All
// vertices lie on the exact curve. (dxf/discretize's equal steps would cut
// corners off: a step rarely lands on a vertex.)
#pragma once

#include "dxf/discretize.h"
#include "dxf/drawing.h"

namespace lcnc::cut {

using Vec2 = Eigen::Vector2d;

// The polygon (closed: pts.back() joins pts.front()), each point with the
// DXF line of its entity — the form dxf::check_crossings reads.
[[nodiscard]] dxf::Polyline contour_polygon(const dxf::Contour& c, double chord_tol_mm);

// Signed area (> 0 counter-clockwise, y up), shoelace formula.
[[nodiscard]] double signed_area(const std::vector<Vec2>& poly);

// Point in polygon (even–odd crossing rule).
[[nodiscard]] bool inside(const Vec2& p, const std::vector<Vec2>& poly);

// Distance from p to the closed polygon's nearest edge.
[[nodiscard]] double distance_to(const Vec2& p, const std::vector<Vec2>& poly);

}  // namespace lcnc::cut
