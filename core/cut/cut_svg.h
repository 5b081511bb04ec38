// The picture of a cutting plan (lasercnc cut --svg): the drawing (black),
// the kerf-offset cut paths (blue), the rapids between contours (grey,
// dashed), the lead-ins (red) from their pierce points (red dots), the
// lead-outs (orange) and each contour's place in the cutting order (the
// number at its pierce point). Drawing coordinates, mm, y up.
#pragma once

#include <string>

#include "cut/cut_program.h"

namespace lcnc::cut {

[[nodiscard]] std::string plan_svg(const CutPlan& plan, const std::string& title);

}  // namespace lcnc::cut
