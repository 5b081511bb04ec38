#include "plan/arc_transition.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "path/segment_geometry.h"

namespace lcnc {
namespace {

Segment line(const Vec3& a, const Vec3& b) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.path_mode = PathMode::Blend;
  s.start.head<3>() = a;
  s.end.head<3>() = b;
  s.feed_mm_s = 100.0;
  return s;
}

// Checks the blend of corner a→b: tangent to both lines at its ends, inside
// the tolerance at the corner, and using no more than allowed.
void expect_good_blend(const Segment& a, const Segment& b, double tol, double max_a, double max_b) {
  const ArcTransition t = arc_transition(a, b, tol, max_a, max_b);
  ASSERT_TRUE(t.blended);
  const SegmentGeometry g(t.arc);
  const Vec3 d1 = (a.end - a.start).head<3>().normalized();
  const Vec3 d2 = (b.end - b.start).head<3>().normalized();
  // ends on the lines, tangent there
  EXPECT_NEAR((g.at(0).head<3>() - t.q0.head<3>()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((g.at(g.length()).head<3>() - t.q2.head<3>()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((g.tangent(0).head<3>() - d1).norm(), 0.0, 1e-9);
  EXPECT_NEAR((g.tangent(g.length()).head<3>() - d2).norm(), 0.0, 1e-9);
  // the closest approach to the corner is within the tolerance, and equals it
  // when the tolerance (not the length) bounds the blend
  const Vec3 corner = b.start.head<3>();
  const double dist = g.distance_xyz(corner);
  EXPECT_LE(dist, tol * (1 + 1e-9));
  const double theta = std::acos(std::clamp(d1.dot(d2), -1.0, 1.0));
  const double l_c = tol * std::sin(theta / 2) / (1 - std::cos(theta / 2));
  if (l_c < std::min(max_a, max_b)) {
    EXPECT_NEAR(dist, tol, 1e-9);
    EXPECT_NEAR(t.trim, l_c, 1e-12);
  } else {
    EXPECT_NEAR(t.trim, std::min(max_a, max_b), 1e-12);
  }
  EXPECT_LE(t.trim, std::min(max_a, max_b) + 1e-15);
  // every point of the arc stays within the tolerance of the two lines
  for (int k = 0; k <= 100; ++k) {
    const Vec3 p = g.at(g.length() * k / 100.0).head<3>();
    const double da = SegmentGeometry(a).distance_xyz(p), db = SegmentGeometry(b).distance_xyz(p);
    EXPECT_LE(std::min(da, db), tol * (1 + 1e-9));
  }
}

TEST(ArcTransition, RightAngleCornerFollowsTheFormula) {
  const Segment a = line({0, 0, 0}, {10, 0, 0}), b = line({10, 0, 0}, {10, 10, 0});
  const ArcTransition t = arc_transition(a, b, 0.01, 5.0, 5.0);
  ASSERT_TRUE(t.blended);
  // θ = 90°: l = E·sin45/(1−cos45) = 0.024142 mm, r = l
  EXPECT_NEAR(t.trim, 0.01 * std::sin(std::numbers::pi / 4) / (1 - std::cos(std::numbers::pi / 4)), 1e-12);
  EXPECT_NEAR(SegmentGeometry(t.arc).radius(), t.trim, 1e-12);
  expect_good_blend(a, b, 0.01, 5.0, 5.0);
}

TEST(ArcTransition, HalfSegmentLimitBoundsTheBlend) {
  // a shallow corner wants a long tangent; the short neighbour caps it
  const Segment a = line({0, 0, 0}, {0.1, 0, 0});
  const Segment b = line({0.1, 0, 0}, {0.2, 0.001, 0});
  expect_good_blend(a, b, 0.01, 0.05, 0.05);
  EXPECT_NEAR(arc_transition(a, b, 0.01, 0.05, 0.05).trim, 0.05, 1e-15);
}

TEST(ArcTransition, RandomCornersIn3DAreTangentAndWithinTolerance) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    const Vec3 p0(u(rng) * 10, u(rng) * 10, u(rng) * 10), p1(0, 0, 0);
    const Vec3 p2(u(rng) * 10, u(rng) * 10, u(rng) * 10);
    const Segment a = line(p0 + Vec3(50, 50, 50), p1 + Vec3(50, 50, 50));
    const Segment b = line(p1 + Vec3(50, 50, 50), p2 + Vec3(50, 50, 50));
    const double d1 = (p1 - p0).norm(), d2 = (p2 - p1).norm();
    const double ang = std::acos(std::clamp((p1 - p0).normalized().dot((p2 - p1).normalized()), -1.0, 1.0));
    if (ang > 3.1 || ang < 1e-3) continue;
    expect_good_blend(a, b, 0.005 + 0.1 * std::abs(u(rng)), d1 / 2, d2 / 2);
  }
}

TEST(ArcTransition, RotaryAxesMoveLinearlyAcrossTheBlend) {
  Segment a = line({0, 0, 0}, {10, 0, 0}), b = line({10, 0, 0}, {10, 10, 0});
  a.end[5] = 10.0;  // C turns 10° along a
  b.start[5] = 10.0;
  b.end[5] = 30.0;
  const ArcTransition t = arc_transition(a, b, 0.01, 5.0, 5.0);
  ASSERT_TRUE(t.blended);
  EXPECT_NEAR(t.q0[5], 10.0 - t.trim, 1e-12);        // 1°/mm on a
  EXPECT_NEAR(t.q2[5], 10.0 + 2.0 * t.trim, 1e-12);  // 2°/mm on b
  EXPECT_EQ(t.arc.start[5], t.q0[5]);
  EXPECT_EQ(t.arc.end[5], t.q2[5]);
}

TEST(ArcTransition, CollinearAndReversedCornersAreNotBlended) {
  const Segment a = line({0, 0, 0}, {10, 0, 0});
  EXPECT_FALSE(arc_transition(a, line({10, 0, 0}, {20, 0, 0}), 0.01, 5, 5).blended);
  EXPECT_FALSE(arc_transition(a, line({10, 0, 0}, {0, 0, 0}), 0.01, 5, 5).blended);
  EXPECT_FALSE(arc_transition(a, line({10, 0, 0}, {10, 5, 0}), 0.0, 5, 5).blended);
}

}  // namespace
}  // namespace lcnc

namespace lcnc {
namespace {

Segment arc_xy_arc_transition(const Vec3& start, const Vec3& end, const Vec3& center, bool cw) {
  Segment s;
  s.kind = MotionKind::Arc;
  s.plane = Plane::XY;
  s.path_mode = PathMode::Blend;
  s.start.head<3>() = start;
  s.end.head<3>() = end;
  s.center = center;
  s.clockwise = cw;
  s.feed_mm_s = 100.0;
  return s;
}

// A fillet must be tangent to both neighbours where it meets them, lie on
// them, and stay within the tolerance of the corner.
void expect_good_fillet(const Segment& a, const Segment& b, double tol, double max_a, double max_b) {
  const ArcTransition t = fillet_transition(a, b, tol, max_a, max_b);
  ASSERT_TRUE(t.blended);
  Segment a2 = a, b2 = b;
  a2.end = t.q0;
  b2.start = t.q2;
  const SegmentGeometry ga(a2), gb(b2), gf(t.arc);
  // on the curves: the trimmed neighbours end/start where the fillet does
  EXPECT_NEAR(SegmentGeometry(a).distance_xyz(t.q0.head<3>()), 0.0, 1e-9);
  EXPECT_NEAR(SegmentGeometry(b).distance_xyz(t.q2.head<3>()), 0.0, 1e-9);
  // tangent at both joins
  EXPECT_NEAR((ga.tangent(ga.length()) - gf.tangent(0)).head<3>().norm(), 0.0, 1e-7);
  EXPECT_NEAR((gf.tangent(gf.length()) - gb.tangent(0)).head<3>().norm(), 0.0, 1e-7);
  // within the tolerance of the corner, and at it unless the trims bound it
  EXPECT_LE(gf.distance_xyz(b.start.head<3>()), tol * (1 + 1e-9));
  // the trimmed neighbours keep their direction of travel (no full circles)
  EXPECT_LT(ga.length(), SegmentGeometry(a).length());
  EXPECT_LT(gb.length(), SegmentGeometry(b).length());
  EXPECT_LE(SegmentGeometry(a).length() - ga.length(), max_a + 1e-9);
  EXPECT_LE(SegmentGeometry(b).length() - gb.length(), max_b + 1e-9);
}

TEST(FilletTransition, LineIntoArcAtAnAngle) {
  // a line going +X meets a CCW arc that starts heading +Y (90° corner)
  const Segment a = line({0, 0, 0}, {10, 0, 0});
  const Segment b = arc_xy_arc_transition({10, 0, 0}, {5, 5, 0}, {5, 0, 0}, false);
  expect_good_fillet(a, b, 0.01, 5.0, 3.0);
}

TEST(FilletTransition, ArcIntoLineBothTurnDirections) {
  const Segment a = arc_xy_arc_transition({0, 0, 0}, {5, 5, 0}, {5, 0, 0}, true);  // CW, ends heading +X
  expect_good_fillet(a, line({5, 5, 0}, {5, 15, 0}), 0.01, 3.0, 5.0);              // turn left
  expect_good_fillet(a, line({5, 5, 0}, {5, -5, 0}), 0.01, 3.0, 5.0);              // turn right
}

TEST(FilletTransition, ArcIntoArc) {
  // two CCW arcs meeting at a 90° corner
  const Segment a = arc_xy_arc_transition({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, false);     // ends heading −X
  const Segment b = arc_xy_arc_transition({0, 10, 0}, {-5, 15, 0}, {-5, 10, 0}, false);  // starts heading +Y
  expect_good_fillet(a, b, 0.02, 5.0, 5.0);
  // and a CW one turning the other way
  const Segment c = arc_xy_arc_transition({0, 10, 0}, {-5, 5, 0}, {-5, 10, 0}, true);  // starts heading −Y
  expect_good_fillet(a, c, 0.02, 5.0, 5.0);
}

TEST(FilletTransition, OtherPlanesAndTangentJoins) {
  // G18: a line along +Z into a counter-clockwise ZX arc that starts heading +X
  const Segment a = line({0, 0, 0}, {0, 0, 10});
  Segment b = arc_xy_arc_transition({0, 0, 10}, {5, 0, 5}, {0, 0, 5}, false);
  b.plane = Plane::ZX;
  expect_good_fillet(a, b, 0.01, 5, 3);
  // a tangent join needs no fillet
  const Segment t1 = line({0, 0, 0}, {10, 0, 0});
  const Segment t2 = arc_xy_arc_transition({10, 0, 0}, {15, 5, 0}, {10, 5, 0}, false);  // starts heading +X
  EXPECT_FALSE(fillet_transition(t1, t2, 0.01, 5, 3).blended);
}

}  // namespace
}  // namespace lcnc
