#include "cut/contour_nesting.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/cut/cut_test_util.h"

namespace lcnc::cut {
namespace {

using test::square;
using Vec2 = Eigen::Vector2d;

// A plate (0) with a window (1) in which a small part (2) with its own hole
// (3) is drawn, and a second hole (4) in the plate; a second plate (5).
std::vector<std::vector<Vec2>> nested() {
  return {square(0, 0, 100), square(10, 10, 60), square(20, 20, 30),
          square(30, 30, 5), square(80, 80, 10), square(200, 0, 50)};
}

TEST(ContourNesting, DepthsOfAPartInsideAHoleOfAnotherPart) {
  const Nesting n = nest_contours(nested());
  EXPECT_EQ(n.depth, (std::vector<int>{0, 1, 2, 3, 1, 0}));
  EXPECT_EQ(n.parent[1], 0u);
  EXPECT_EQ(n.parent[2], 1u);  // the smallest container, not the plate
  EXPECT_EQ(n.parent[3], 2u);
  EXPECT_EQ(n.parent[4], 0u);
  EXPECT_EQ(n.parent[0], kNoParent);
  EXPECT_EQ(n.roots, (std::vector<std::size_t>{0, 5}));
  EXPECT_FALSE(n.is_hole(0));
  EXPECT_TRUE(n.is_hole(1));
  EXPECT_FALSE(n.is_hole(2));  // a part again
  EXPECT_TRUE(n.is_hole(3));
}

TEST(ContourNesting, OrderOfInputAndOrientationDoNotMatter) {
  std::vector<std::vector<Vec2>> p = nested();
  std::reverse(p.begin(), p.end());        // 5 4 3 2 1 0
  std::reverse(p[1].begin(), p[1].end());  // the hole (old 4) clockwise
  const Nesting n = nest_contours(p);
  EXPECT_EQ(n.depth, (std::vector<int>{0, 1, 3, 2, 1, 0}));
  EXPECT_EQ(n.parent[1], 5u);
}

}  // namespace
}  // namespace lcnc::cut
