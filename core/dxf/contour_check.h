// Crossing check of discretized contours (Kondratenko et al. 2015: "all contours are checked
// ... for the absence of intersections"): no contour may cross or touch
// itself or another one — the part would fall apart or be cut twice there.
//
// Every chord goes into the cells of a uniform grid (cell = 4 × the longest
// chord, so a chord touches at most 4 cells); the chords that share a cell
// are tested pairwise (orientation tests; collinear overlap and touching
// count as crossing). Neighbouring chords of one contour share a vertex and
// are only tested for folding back onto each other. O(n log n) for n chords.
// The check runs on the same points the machine will follow.
#pragma once

#include <string>
#include <vector>

#include "common/result.h"
#include "dxf/discretize.h"
#include "dxf/drawing.h"

namespace lcnc::dxf {

// `contours[i]` is the contour of `lines[i]`. The first crossing found is an
// error naming both contours (or one, crossing itself), the point, and the
// DXF lines of the two entities.
[[nodiscard]] Status check_crossings(const std::vector<Contour>& contours,
                                     const std::vector<Polyline>& lines,
                                     const std::string& file);

}  // namespace lcnc::dxf
