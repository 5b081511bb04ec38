// Pictures of a decomposition, as SVG text (no dependency):
//  * paths_svg: seed 004 Fig. 6 — the contour S green, the main path S1 blue
//    (left panel, part coordinates), the auxiliary path S2 = S − S1 red in
//    its field (right panel, its own scale, the field drawn as a square);
//  * accel_svg: seed 004 Fig. 8 — the effective acceleration (beam) and the
//    main-axis acceleration over time, the main-axis limit dashed.
// Long paths are thinned for drawing (a vertex within 0.75 px of the last one
// drawn is skipped; the acceleration curves keep each pixel column's peak, so
// no peak is lost).
#pragma once

#include <string>

#include "decompose/decompose_options.h"
#include "decompose/part_decomposition.h"

namespace lcnc::decompose {

[[nodiscard]] std::string paths_svg(const PartResult& r, const Options& opt,
                                    const std::string& title);
[[nodiscard]] std::string accel_svg(const PartResult& r, const Options& opt,
                                    const std::string& title);

}  // namespace lcnc::decompose
