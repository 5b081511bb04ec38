#include "cut/kerf_offset.h"

#include <gtest/gtest.h>

#include "cut/contour_polygon.h"
#include "cut/cut_tolerances.h"
#include "core/cut/cut_test_util.h"

namespace lcnc::cut {
namespace {

// Every vertex and edge midpoint of `path` is `d` from `poly`, within the
// arc tolerance of the round joins (and the integer grid).
void expect_at_distance(const std::vector<Vec2>& path, const std::vector<Vec2>& poly, double d) {
  const double tol = kKerfArcToleranceMm + 2 * kClipperUnitMm;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Vec2 mid = 0.5 * (path[i] + path[(i + 1) % path.size()]);
    EXPECT_NEAR(distance_to(path[i], poly), d, 2 * kClipperUnitMm) << "vertex " << i;
    EXPECT_NEAR(distance_to(mid, poly), d, tol) << "after vertex " << i;
  }
}

TEST(KerfOffset, OutwardPathIsHalfTheKerfFromASquareWithRoundCorners) {
  const std::vector<Vec2> sq = test::square(0, 0, 10);
  const auto off = offset_polygon(sq, 0.1);
  ASSERT_EQ(off.size(), 1u);
  expect_at_distance(off[0], sq, 0.1);
  for (const Vec2& p : off[0]) EXPECT_FALSE(inside(p, sq));
  EXPECT_GT(signed_area(off[0]), 0.0);  // counter-clockwise
  // area of the grown square: a² + 4·a·d + π·d² (round corners)
  EXPECT_NEAR(signed_area(off[0]), 100 + 4 * 10 * 0.1 + M_PI * 0.01, 1e-3);
  EXPECT_GT(off[0].size(), 8u);  // the corners are arcs
}

TEST(KerfOffset, InwardPathOfAClockwiseHoleKeepsSharpCorners) {
  std::vector<Vec2> sq = test::square(0, 0, 10);
  std::reverse(sq.begin(), sq.end());  // orientation must not matter
  const auto off = offset_polygon(sq, -0.25);
  ASSERT_EQ(off.size(), 1u);
  ASSERT_EQ(off[0].size(), 4u);
  expect_at_distance(off[0], sq, 0.25);
  for (const Vec2& p : off[0]) EXPECT_TRUE(inside(p, sq));
  EXPECT_NEAR(signed_area(off[0]), 9.5 * 9.5, 1e-6);
}

TEST(KerfOffset, CircleGrowsAndShrinksByTheDistance) {
  const std::vector<Vec2> c = test::ngon(5, 5, 3, 720);
  for (double d : {0.1, -0.1, 1.0, -1.0}) {
    const auto off = offset_polygon(c, d);
    ASSERT_EQ(off.size(), 1u);
    for (const Vec2& p : off[0]) EXPECT_NEAR((p - Vec2(5, 5)).norm(), 3 + d, 2e-4) << d;
  }
}

TEST(KerfOffset, AHoleNarrowerThanTheKerfVanishesAndAWaistSplits) {
  EXPECT_TRUE(offset_polygon(test::square(0, 0, 0.3), -0.2).empty());
  // two 4 mm squares joined by a 0.2 mm wide neck
  const std::vector<Vec2> dumbbell = {{0, 0}, {4, 0}, {4, 1.9}, {6, 1.9}, {6, 0}, {10, 0},
                                      {10, 4}, {6, 4}, {6, 2.1}, {4, 2.1}, {4, 4}, {0, 4}};
  EXPECT_EQ(offset_polygon(dumbbell, -0.15).size(), 2u);
}

}  // namespace
}  // namespace lcnc::cut
