#include "cut/kerf_offset.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/cut/cut_test_util.h"
#include "cut/contour_polygon.h"
#include "cut/cut_tolerances.h"

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
  const std::vector<Vec2> dumbbell = {{0, 0},  {4, 0}, {4, 1.9}, {6, 1.9}, {6, 0}, {10, 0},
                                      {10, 4}, {6, 4}, {6, 2.1}, {4, 2.1}, {4, 4}, {0, 4}};
  EXPECT_EQ(offset_polygon(dumbbell, -0.15).size(), 2u);
}

}  // namespace
}  // namespace lcnc::cut

namespace lcnc::cut {
namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Thinning keeps the first vertex and only vertices of the polygon, in order;
// every dropped vertex lies within eps of the chord that replaced it; a
// dense circle thins to what its curvature needs, corners all stay.
TEST(KerfOffset, ThinningKeepsEveryVertexWithinItsToleranceAndDropsTheRest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.4e-4, 0.4e-4);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Vec2> poly = test::ngon(0, 0, 20.0 + trial, 20000 + 1000 * trial);
    for (Vec2& p : poly) p += Vec2(noise(rng), noise(rng));  // within ±0.04 µm
    if (trial % 3 == 1) {                                    // a square corner in it
      for (std::size_t i = 0; i < poly.size() / 4; ++i) poly[i] = Vec2(30.0 + trial, 30.0 + trial);
      poly.erase(poly.begin() + 1, poly.begin() + static_cast<long>(poly.size() / 4));
    }
    const std::vector<Vec2> thin = simplify_closed(poly, kOffsetSimplifyMm);
    ASSERT_GE(thin.size(), 3u);
    EXPECT_LT(thin.size(), poly.size() / 5) << "trial " << trial;
    ASSERT_EQ(thin.front(), poly.front());
    // each dropped vertex between two kept ones lies within eps of their chord
    std::size_t k = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      if (k + 1 < thin.size() && poly[i] == thin[k + 1]) {
        ++k;
        continue;
      }
      if (poly[i] == thin[k]) continue;
      const Vec2& a = thin[k];
      const Vec2& b = thin[(k + 1) % thin.size()];
      ASSERT_LE(segment_distance(poly[i], a, b), kOffsetSimplifyMm * (1 + 1e-9))
          << "trial " << trial << " vertex " << i;
    }
    EXPECT_EQ(k + 1, thin.size()) << "trial " << trial << ": kept vertices out of order";
  }
  // a polygon of real corners keeps them all
  const std::vector<Vec2> star = {{0, 0}, {10, 1}, {20, 0}, {19, 10}, {20, 20}, {10, 19}, {0, 20}, {1, 10}};
  EXPECT_EQ(simplify_closed(star, kOffsetSimplifyMm), star);
}

// A million chords on a circle are offset as the circle: in seconds, the
// path half the kerf from the drawing (the cut of dense polylines).
TEST(KerfOffset, AMillionChordCircleIsOffsetWithinTolerance) {
  const std::vector<Vec2> circle = test::ngon(0, 0, 200.0, 1'000'000);
  const auto off = offset_polygon(circle, 0.1);
  ASSERT_EQ(off.size(), 1u);
  EXPECT_LT(off[0].size(), 20000u);
  for (std::size_t i = 0; i < off[0].size(); i += 7) {
    EXPECT_NEAR(off[0][i].norm(), 200.1, kKerfArcToleranceMm + kOffsetSimplifyMm + 2 * kClipperUnitMm);
  }
}

}  // namespace
}  // namespace lcnc::cut
