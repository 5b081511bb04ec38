#include "cut/cut_order.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/cut/cut_test_util.h"

namespace lcnc::cut {
namespace {

using test::square;
using Vec2 = Eigen::Vector2d;

std::vector<std::size_t> order_of(const std::vector<std::vector<Vec2>>& p, const Vec2& start) {
  const Nesting n = nest_contours(p);
  return cut_order(n, p, start, [&](std::size_t i, const Vec2&) { return p[i].front(); });
}

std::size_t pos(const std::vector<std::size_t>& order, std::size_t i) {
  return static_cast<std::size_t>(std::find(order.begin(), order.end(), i) - order.begin());
}

TEST(CutOrder, EveryContourAfterAllThatLieInsideIt) {
  // plate 0 ⊃ window 1 ⊃ part 2 ⊃ hole 3; hole 4 in the plate; plate 5
  const std::vector<std::vector<Vec2>> p = {square(0, 0, 100), square(10, 10, 60), square(20, 20, 30),
                                            square(30, 30, 5), square(80, 80, 10), square(200, 0, 50)};
  const std::vector<std::size_t> order = order_of(p, Vec2(0, 0));
  ASSERT_EQ(order.size(), p.size());
  const Nesting n = nest_contours(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t a = n.parent[i]; a != kNoParent; a = n.parent[a]) {
      EXPECT_LT(pos(order, i), pos(order, a)) << "contour " << i << " inside " << a;
    }
  }
  // the innermost first, the plate around them last of its subtree
  EXPECT_EQ(order[0], 3u);
  EXPECT_EQ(order[1], 2u);
  EXPECT_EQ(order[2], 1u);
  EXPECT_EQ(order[3], 4u);
  EXPECT_EQ(order[4], 0u);
  EXPECT_EQ(order[5], 5u);
}

TEST(CutOrder, SiblingsNearestFirstFromWhereTheBeamIs) {
  // four holes in a row in a plate; starting at the right end they go right to left
  const std::vector<std::vector<Vec2>> p = {square(0, 0, 100), square(10, 10, 5), square(30, 10, 5),
                                            square(50, 10, 5), square(70, 10, 5)};
  EXPECT_EQ(order_of(p, Vec2(100, 0)), (std::vector<std::size_t>{4, 3, 2, 1, 0}));
  EXPECT_EQ(order_of(p, Vec2(0, 0)), (std::vector<std::size_t>{1, 2, 3, 4, 0}));
}

}  // namespace
}  // namespace lcnc::cut
