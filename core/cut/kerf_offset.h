// Kerf compensation: the beam burns a slot kerf wide, centred on its path,
// so the path runs kerf/2 beside the drawn line on the scrap side — outward
// of a part's outline, inward of a hole — and the part comes out at its
// drawn size.
//
// The offset is Clipper's (libpolyclipping 6.4.2, ClipperOffset): the
// polygon's edges moved by d along their normals, convex corners joined by
// round arcs (jtRound: the true offset of a corner is an arc of radius d
// about it; chords within kKerfArcToleranceMm of it), concave corners
// trimmed where the moved edges meet. Every point of the result is then d
// from the polygon (within the arc tolerance), and no point is nearer.
// Coordinates go to Clipper's integers at kClipperUnitMm per unit and back.
//
// Runs of dense vertices are first thinned to chords they lie within
// kOffsetSimplifyMm of (simplify_closed), so a polyline of a million points
// is offset in seconds.
//
// Moving inward may leave nothing (a hole narrower than the kerf) or split a
// hole in two (a narrow waist): the caller decides what is an error.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace lcnc::cut {

// The closed polygons at signed distance delta_mm from `poly` (> 0 grows the
// area it encloses, < 0 shrinks it), each counter-clockwise (y up), the
// largest first. Empty when the shrunk area vanishes.
[[nodiscard]] std::vector<std::vector<Eigen::Vector2d>> offset_polygon(
    const std::vector<Eigen::Vector2d>& poly, double delta_mm);

// The closed polygon with runs of vertices that lie within eps of one chord
// replaced by that chord (Zhao and Saalfeld's sleeve fitting, 1997: each
// chord is extended while the directions that pass within eps of every
// point it covers still include it), in one pass. Every dropped vertex lies
// within eps of the chord that replaced it; the first vertex stays.
[[nodiscard]] std::vector<Eigen::Vector2d> simplify_closed(const std::vector<Eigen::Vector2d>& poly,
                                                           double eps);

}  // namespace lcnc::cut
