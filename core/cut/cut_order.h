// The order in which the contours are cut.
//
// Rule 1 (nesting): every contour inside another is cut before the contour
// that contains it — inner before outer, recursively. A part falls (or
// tilts) once its outline is cut through, so its holes, and a part drawn
// inside one of its holes, must be finished by then.
// Rule 2 (travel): among siblings (contours with the same parent), the next
// is the one nearest to where the beam is now (greedy nearest neighbour,
// distance to the sibling's nearest vertex), to keep rapid travel short.
//
// So cutting sibling S means: first S's children by the same two rules
// (their subtrees, recursively), then S itself. `cut(i, from)` is called
// once per contour in that order; it places contour i's pierce and returns
// where the beam ends (what the next choice measures from).
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "cut/contour_nesting.h"

namespace lcnc::cut {

using CutStep = std::function<Eigen::Vector2d(std::size_t contour, const Eigen::Vector2d& from)>;

// The contours in cutting order; paths[i] are the vertices of contour i's
// path (the greedy distance is measured to them).
[[nodiscard]] std::vector<std::size_t> cut_order(const Nesting& nest,
                                                 const std::vector<std::vector<Eigen::Vector2d>>& paths,
                                                 const Eigen::Vector2d& start, const CutStep& cut);

}  // namespace lcnc::cut
