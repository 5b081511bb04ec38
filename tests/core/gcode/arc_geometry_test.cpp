// Arc sweep, length and bounds on Segment arcs, in all three planes.
#include "gcode/arc_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace lcnc::gcode {
namespace {

constexpr double kPiArcGeometry = std::numbers::pi;

Segment arc_xy(Vec3 c, double r, double a0, double a1, bool cw, std::uint32_t turns = 0) {
  Segment s;
  s.kind = MotionKind::Arc;
  s.plane = Plane::XY;
  s.center = c;
  s.clockwise = cw;
  s.extra_turns = turns;
  s.start = Pose::Zero();
  s.end = Pose::Zero();
  s.start.head<3>() = c + Vec3(r * std::cos(a0), r * std::sin(a0), 0);
  s.end.head<3>() = c + Vec3(r * std::cos(a1), r * std::sin(a1), 0);
  return s;
}

TEST(GcodeArcGeometry, SweepFollowsTheDirection) {
  EXPECT_NEAR(arc_sweep_rad(arc_xy(Vec3::Zero(), 1, 0, kPiArcGeometry / 2, false)), kPiArcGeometry / 2,
              1e-12);
  EXPECT_NEAR(arc_sweep_rad(arc_xy(Vec3::Zero(), 1, 0, kPiArcGeometry / 2, true)), 1.5 * kPiArcGeometry,
              1e-12);
  EXPECT_NEAR(arc_sweep_rad(arc_xy(Vec3::Zero(), 1, 0, 0, true)), 2 * kPiArcGeometry, 1e-12);
  EXPECT_NEAR(arc_sweep_rad(arc_xy(Vec3::Zero(), 1, 0, 0, false, 2)), 6 * kPiArcGeometry, 1e-12);
}

TEST(GcodeArcGeometry, ArcPlaneAxesAreRightHanded) {
  EXPECT_EQ(arc_plane_axes(Plane::XY), (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(arc_plane_axes(Plane::ZX), (std::array<int, 3>{2, 0, 1}));
  EXPECT_EQ(arc_plane_axes(Plane::YZ), (std::array<int, 3>{1, 2, 0}));
}

TEST(GcodeArcGeometry, LengthOfAHelix) {
  Segment s = arc_xy(Vec3::Zero(), 2, 0, 0, false, 1);
  s.end[2] = 3.0;
  EXPECT_NEAR(arc_length_mm(s), std::hypot(2 * 4 * kPiArcGeometry, 3.0), 1e-12);
}

TEST(GcodeArcGeometry, BoundsIncludeOnlyTheExtremesPassed) {
  Vec3 lo, hi;
  arc_bounds(arc_xy(Vec3(10, 10, 0), 5, kPiArcGeometry / 4, 3 * kPiArcGeometry / 4, false), lo, hi);
  EXPECT_NEAR(hi[1], 15, 1e-12);                                     // passes +Y
  EXPECT_NEAR(hi[0], 10 + 5 * std::cos(kPiArcGeometry / 4), 1e-12);  // but not +X
  arc_bounds(arc_xy(Vec3(10, 10, 0), 5, kPiArcGeometry / 4, 3 * kPiArcGeometry / 4, true), lo, hi);
  EXPECT_NEAR(lo[1], 5, 1e-12);  // clockwise: the long way, through −Y
  EXPECT_NEAR(lo[0], 5, 1e-12);
  EXPECT_NEAR(hi[0], 15, 1e-12);
  EXPECT_NEAR(hi[1], 10 + 5 * std::sin(kPiArcGeometry / 4), 1e-12);
}

// Fixed-seed property test: points sampled along random arcs in every plane
// lie inside arc_bounds, and the bounds are reached (tight).
TEST(GcodeArcGeometry, BoundsContainAndTouchSampledPoints) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ang(-kPiArcGeometry, kPiArcGeometry);
  std::uniform_real_distribution<double> rad(0.1, 50);
  std::bernoulli_distribution coin(0.5);
  for (int i = 0; i < 2000; ++i) {
    const Plane plane = static_cast<Plane>(i % 3);
    const auto [ia, ib, in] = arc_plane_axes(plane);
    (void)in;
    Segment s;
    s.kind = MotionKind::Arc;
    s.plane = plane;
    s.clockwise = coin(rng);
    s.center = Vec3(100, 200, 300);
    const double r = rad(rng);
    const double a0 = ang(rng);
    const double a1 = ang(rng);
    s.start = Pose::Zero();
    s.start.head<3>() = s.center;
    s.end = s.start;
    s.start[ia] += r * std::cos(a0);
    s.start[ib] += r * std::sin(a0);
    s.end[ia] += r * std::cos(a1);
    s.end[ib] += r * std::sin(a1);
    Vec3 lo, hi;
    arc_bounds(s, lo, hi);
    const double sweep = arc_sweep_rad(s) * (s.clockwise ? -1 : 1);
    Vec3 seen_lo = Vec3::Constant(1e300), seen_hi = Vec3::Constant(-1e300);
    const int n = 4000;
    for (int k = 0; k <= n; ++k) {
      const double a = a0 + sweep * k / n;
      Vec3 p = s.center;
      p[ia] += r * std::cos(a);
      p[ib] += r * std::sin(a);
      for (int d = 0; d < 3; ++d) {
        ASSERT_GE(p[d], lo[d] - 1e-9) << "arc " << i;
        ASSERT_LE(p[d], hi[d] + 1e-9) << "arc " << i;
      }
      seen_lo = seen_lo.cwiseMin(p);
      seen_hi = seen_hi.cwiseMax(p);
    }
    // Sampling every sweep/4000 rad misses an extreme by at most r·(1−cos(step/2)).
    const double slack = r * (1 - std::cos(std::fabs(sweep) / n / 2)) + 1e-9;
    EXPECT_LE((seen_lo - lo).maxCoeff(), slack) << "arc " << i;
    EXPECT_LE((hi - seen_hi).maxCoeff(), slack) << "arc " << i;
  }
}

}  // namespace
}  // namespace lcnc::gcode
