// Pictures of a decomposition, as SVG text (no dependency):
//  * paths_svg: Kondratenko et al. (2015) Fig. 6 — the contour S green, the main path S1 blue
//    (left panel, part coordinates), the auxiliary path S2 = S − S1 red in
//    its field (right panel, its own scale, the field drawn as a square);
//  * accel_svg: Kondratenko et al. (2015) Fig. 8 — the effective acceleration (beam) and the
//    main-axis acceleration over time, the main-axis limit dashed;
//  * axes_svg: the axis curves of a run — X, Y (main group, left scale) and
//    P, Q (auxiliary group, right scale) over time, the laser-on spans shaded.
// Long paths are thinned for drawing (a vertex within 0.75 px of the last one
// drawn is skipped; the acceleration curves keep each pixel column's peak, so
// no peak is lost).
#pragma once

#include <string>
#include <vector>

#include "decompose/decompose_options.h"
#include "decompose/part_decomposition.h"

namespace lcnc::decompose {

[[nodiscard]] std::string paths_svg(const PartResult& r, const Options& opt, const std::string& title);
[[nodiscard]] std::string accel_svg(const PartResult& r, const Options& opt, const std::string& title);

// Positions over time of the two axis groups (mm, s), one sample per entry.
struct AxisCurves {
  std::vector<double> t_s;
  std::vector<Vec2> main, aux;
  std::vector<bool> laser;
  void add(double t, const Vec2& m, const Vec2& a, bool on) {
    t_s.push_back(t);
    main.push_back(m);
    aux.push_back(a);
    laser.push_back(on);
  }
};
[[nodiscard]] std::string axes_svg(const AxisCurves& c, const std::string& title);

}  // namespace lcnc::decompose
