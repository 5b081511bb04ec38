#include "cut/contour_nesting.h"

#include <cmath>

#include <Eigen/Geometry>

#include "cut/contour_polygon.h"

namespace lcnc::cut {

Nesting nest_contours(const std::vector<std::vector<Vec2>>& polys) {
  const std::size_t n = polys.size();
  Nesting out;
  out.parent.assign(n, kNoParent);
  out.depth.assign(n, 0);
  out.children.assign(n, {});
  std::vector<double> area(n);
  std::vector<Eigen::AlignedBox2d> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    area[i] = std::abs(signed_area(polys[i]));
    for (const Vec2& p : polys[i]) box[i].extend(p);
  }
  for (std::size_t a = 0; a < n; ++a) {
    if (polys[a].empty()) continue;
    for (std::size_t b = 0; b < n; ++b) {
      if (a == b || polys[b].empty() || !(area[b] > area[a]) || !box[b].contains(box[a])) continue;
      if (!inside(polys[a].front(), polys[b])) continue;
      if (out.parent[a] == kNoParent || area[b] < area[out.parent[a]]) out.parent[a] = b;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (out.parent[i] == kNoParent) {
      out.roots.push_back(i);
    } else {
      out.children[out.parent[i]].push_back(i);
    }
    for (std::size_t p = out.parent[i]; p != kNoParent; p = out.parent[p]) ++out.depth[i];
  }
  return out;
}

}  // namespace lcnc::cut
