#include "cut/kerf_offset.h"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>

#include "cut/contour_polygon.h"
#include "cut/cut_tolerances.h"

namespace lcnc::cut {

std::vector<std::vector<Vec2>> offset_polygon(const std::vector<Vec2>& poly, double delta_mm) {
  ClipperLib::Path in;
  in.reserve(poly.size());
  for (const Vec2& p : poly) {
    in.emplace_back(static_cast<ClipperLib::cInt>(std::llround(p.x() / kClipperUnitMm)),
                    static_cast<ClipperLib::cInt>(std::llround(p.y() / kClipperUnitMm)));
  }
  // One polygon: Clipper orients it so that delta > 0 grows its area.
  ClipperLib::ClipperOffset co;
  co.ArcTolerance = kKerfArcToleranceMm / kClipperUnitMm;
  co.AddPath(in, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::Paths sol;
  co.Execute(sol, delta_mm / kClipperUnitMm);

  std::vector<std::vector<Vec2>> out;
  for (ClipperLib::Path& path : sol) {
    if (path.size() < 3) continue;
    // The result's outer paths are positive; a negative one is a gap the
    // grown outline closed around — not a path to cut.
    if (!ClipperLib::Orientation(path)) continue;
    std::vector<Vec2> q;
    q.reserve(path.size());
    for (const ClipperLib::IntPoint& p : path) {
      q.emplace_back(static_cast<double>(p.X) * kClipperUnitMm,
                     static_cast<double>(p.Y) * kClipperUnitMm);
    }
    out.push_back(std::move(q));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return signed_area(a) > signed_area(b);
  });
  return out;
}

}  // namespace lcnc::cut
