// Chaining a drawing's entities into closed contours (Kondratenko et al. 2015: "every
// contour is checked closed"; a laser cannot cut an open one).
//
// Entity ends closer than kJoinToleranceMm are one vertex. Starting from the
// first unused entity in drawing order, the chain follows the one other
// entity that touches its free end (reversing it if needed) until it comes
// back to its start. Errors, each naming the contour, the entity and the
// point:
//   * open: the free end touches nothing;
//   * branching: three or more ends meet at one point (the contour is not a
//     simple chain, so no cutting order follows from the drawing).
#pragma once

#include <vector>

#include "common/result.h"
#include "dxf/drawing.h"

namespace lcnc::dxf {

[[nodiscard]] Result<std::vector<Contour>> chain_contours(const Drawing& d);

// "(12.345, 6.789)" in mm, 3 decimals (the machine's 1 µm).
[[nodiscard]] std::string format_point(const Vec2& p);

}  // namespace lcnc::dxf
