// A SPLINE given by fit points only (no control points — what many CAD
// programs write for a curve drawn through points): the cubic that passes
// through every fit point, as the B-spline the rest of the reader samples.
//
// Parameters by chord length: t_0 = 0, t_i = t_{i−1} + |Q_i − Q_{i−1}| (mm),
// so the curve's speed is about 1 and a unit tangent is a derivative. On each
// interval [t_i, t_{i+1}] (h_i long) the curve is the cubic Hermite piece
// between Q_i, Q_{i+1} with derivatives D_i, D_{i+1}; C² continuity at the
// inner points gives the tridiagonal system (de Boor, A Practical Guide to
// Splines, ch. IV)
//   h_i·D_{i−1} + 2(h_{i−1} + h_i)·D_i + h_{i−1}·D_{i+1}
//       = 3·(h_i·(Q_i − Q_{i−1})/h_{i−1} + h_{i−1}·(Q_{i+1} − Q_i)/h_i),
// closed at each end by the tangent the DXF gives (codes 12/22/32 at the
// start, 13/23/33 at the end: D = the unit tangent) or, without one, by the
// natural condition C'' = 0 (2·D_0 + D_1 = 3·(Q_1 − Q_0)/h_0, and mirrored).
// Two fit points and no tangents make the straight line.
//
// Each piece becomes its Bézier form (Q_i, Q_i + h_i·D_i/3,
// Q_{i+1} − h_i·D_{i+1}/3, Q_{i+1}), and the chain a degree-3 B-spline with
// every inner knot tripled: control points 3m + 1, knots 3m + 5 for m pieces.
#pragma once

#include <string>

#include "dxf/spline_curve.h"

namespace lcnc::dxf {

// Fills s.control and s.knots (degree 3, no weights) from s.fit and the end
// tangents; false with the reason in `why` when there are fewer than two
// distinct fit points.
[[nodiscard]] bool interpolate_fit_points(SplineData& s, std::string* why);

}  // namespace lcnc::dxf
