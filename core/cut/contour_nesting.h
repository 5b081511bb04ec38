// Which closed contour lies inside which: the nesting tree of a drawing's
// contours, from which follow parts and holes (even depth: the outline of a
// part; odd depth: a hole in the part around it; a part drawn inside a hole
// is at depth 2, its holes at 3, ...) and the cutting order (cut_order.h).
//
// The contours are known not to cross or touch (dxf::check_crossings), so
// contour A is inside B exactly when one vertex of A is inside B (even–odd
// rule). A's parent is the smallest-area contour that contains it. O(n²)
// containment tests with a bounding-box reject first.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace lcnc::cut {

inline constexpr std::size_t kNoParent = static_cast<std::size_t>(-1);

struct Nesting {
  std::vector<std::size_t> parent;                 // kNoParent for the outermost
  std::vector<int> depth;                          // 0 for the outermost
  std::vector<std::vector<std::size_t>> children;  // in input order
  std::vector<std::size_t> roots;                  // depth 0, in input order

  [[nodiscard]] bool is_hole(std::size_t i) const { return depth[i] % 2 == 1; }
};

// polys[i]: the closed polygon of contour i (any orientation).
[[nodiscard]] Nesting nest_contours(const std::vector<std::vector<Eigen::Vector2d>>& polys);

}  // namespace lcnc::cut
