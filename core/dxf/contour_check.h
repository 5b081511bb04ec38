// Crossing check of discretized contours (Kondratenko et al. 2015: "all contours are checked
// ... for the absence of intersections"): no contour may cross or touch
// itself or another one — the part would fall apart or be cut twice there.
//
// Three passes, each O(n log n) for n chords whatever their lengths: a chord
// that turns straight back onto its predecessor; a point two contours share
// or one contour passes twice (sorted vertices); then a left-to-right sweep
// (Shamos and Hoey 1976) that tests each chord against its neighbours along
// the sweep line — crossing, touching and collinear overlap all count.
// Neighbouring chords of one contour share a vertex and are not tested
// against each other.
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
[[nodiscard]] Status check_crossings(const std::vector<Contour>& contours, const std::vector<Polyline>& lines,
                                     const std::string& file);

}  // namespace lcnc::dxf
