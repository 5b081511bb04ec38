#include "cut/kerf_offset.h"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>

#include "cut/contour_polygon.h"
#include "cut/cut_tolerances.h"

namespace lcnc::cut {

std::vector<Vec2> simplify_closed(const std::vector<Vec2>& poly, double eps) {
  const std::size_t n = poly.size();
  if (n < 4) return poly;
  std::vector<Vec2> out{poly[0]};
  auto at = [&](std::size_t i) -> const Vec2& { return poly[i % n]; };  // at(n) closes
  std::size_t anchor = 0;
  while (anchor < n) {
    const Vec2& a = at(anchor);
    // The sleeve: directions from `a` whose ray passes within eps of every
    // point so far, as an interval of angles about the first one's.
    double base = 0.0, lo = 0.0, hi = 0.0, reach = 0.0;
    bool started = false;
    std::size_t last = anchor + 1;  // the farthest point the chord may end at
    for (std::size_t i = anchor + 1; i <= n; ++i) {
      const Vec2 v = at(i) - a;
      const double d = v.norm();
      if (d <= eps) {  // within eps of the anchor: of any chord from it
        if (!started) last = i;
        continue;
      }
      const double half = std::asin(eps / d);
      const double theta = std::atan2(v.y(), v.x());
      if (!started) {
        started = true;
        base = theta;
        lo = -half;
        hi = half;
        reach = d;
        last = i;
        continue;
      }
      const double rel = std::remainder(theta - base, 2.0 * M_PI);
      // the chord to i must pass within eps of every point before it, and
      // reach at least as far as any of them
      if (rel < lo || rel > hi || d < reach) break;
      lo = std::max(lo, rel - half);
      hi = std::min(hi, rel + half);
      reach = d;
      last = i;
    }
    if (last >= n) break;
    out.push_back(at(last));
    anchor = last;
  }
  return out.size() >= 3 ? out : poly;
}

std::vector<std::vector<Vec2>> offset_polygon(const std::vector<Vec2>& poly_in, double delta_mm) {
  const std::vector<Vec2> poly = simplify_closed(poly_in, kOffsetSimplifyMm);
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
      q.emplace_back(static_cast<double>(p.X) * kClipperUnitMm, static_cast<double>(p.Y) * kClipperUnitMm);
    }
    out.push_back(std::move(q));
  }
  std::sort(out.begin(), out.end(),
            [](const auto& a, const auto& b) { return signed_area(a) > signed_area(b); });
  return out;
}

}  // namespace lcnc::cut
