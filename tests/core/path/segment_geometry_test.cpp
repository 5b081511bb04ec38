#include "path/segment_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "path/deviation_meter.h"

namespace lcnc {
namespace {

Segment arc(double r, bool cw, std::uint32_t turns = 0, double dz = 0.0) {
  Segment s;
  s.kind = MotionKind::Arc;
  s.plane = Plane::XY;
  s.center = Vec3(50, 50, 10);
  s.start = Pose::Zero();
  s.start << 50 + r, 50, 10, 0, 0, 0;
  s.end = s.start;
  s.end[2] += dz;
  s.clockwise = cw;
  s.extra_turns = turns;
  return s;
}

TEST(SegmentGeometry, FullCircleLengthAndPoints) {
  const SegmentGeometry g(arc(5.0, false));
  EXPECT_NEAR(g.length(), 2 * std::numbers::pi * 5.0, 1e-12);
  const Pose quarter = g.at(g.length() / 4);
  EXPECT_NEAR(quarter[0], 50.0, 1e-12);
  EXPECT_NEAR(quarter[1], 55.0, 1e-12);  // CCW goes +Y first
  const SegmentGeometry cw(arc(5.0, true));
  EXPECT_NEAR(cw.at(cw.length() / 4)[1], 45.0, 1e-12);
}

TEST(SegmentGeometry, PointsOfSmallAndLargeSweepsAreOnTheCircle) {
  // small angles take a series instead of sin and cos: on a 1 m radius a
  // wrong term would show far above 1e-11 mm
  constexpr double r = 1000.0;
  for (const double sweep : {1e-6, 0.01, 0.015625, 0.02, 0.5}) {
    Segment s = arc(r, false);
    s.end << 50 + r * std::cos(sweep), 50 + r * std::sin(sweep), 10, 0, 0, 0;
    const SegmentGeometry g(s);
    for (int k = 1; k < 16; ++k) {
      const double f = k / 16.0, phi = g.sweep_rad() * f;
      const Pose p = g.at(g.length() * f);
      EXPECT_NEAR(p[0], 50 + r * std::cos(phi), 1e-11) << sweep << " " << f;
      EXPECT_NEAR(p[1], 50 + r * std::sin(phi), 1e-11) << sweep << " " << f;
    }
  }
}

TEST(SegmentGeometry, SmallSweepsAreTheAngleOfTheEndPoint) {
  // small sweeps take a series instead of atan2: a wrong term would show far
  // above a few ulps, in both senses and in a free plane
  for (const double sweep : {1e-9, 1e-4, 0.0155, 0.0157, 0.3}) {
    for (const bool cw : {false, true}) {
      Segment s = arc(7.0, cw);
      s.end << 50 + 7.0 * std::cos(sweep), 50 + 7.0 * (cw ? -1 : 1) * std::sin(sweep), 10, 0, 0, 0;
      // the angle of the end point as stored (its coordinates about the centre)
      const double want = std::atan2((cw ? -1 : 1) * (s.end[1] - 50), s.end[0] - 50);
      EXPECT_NEAR(SegmentGeometry(s).sweep_rad(), want, 4e-16 * want) << sweep << " " << cw;
      s.plane = Plane::Free;
      s.normal = Vec3(0, 0, cw ? -1 : 1);
      EXPECT_NEAR(SegmentGeometry(s).sweep_rad(), want, 4e-16 * want) << sweep << " free";
    }
  }
}

TEST(SegmentGeometry, HelixWithTurns) {
  const SegmentGeometry g(arc(2.0, false, 2, 3.0));  // 3 turns, 3 mm up
  const double plane = 3 * 2 * std::numbers::pi * 2.0;
  EXPECT_NEAR(g.length(), std::hypot(plane, 3.0), 1e-9);
  EXPECT_NEAR(g.at(g.length() / 3)[2], 11.0, 1e-9);  // one turn, one mm
}

// A G17 circle or helix turned by a rotation (a hole on a tilted head) is a
// Free-plane arc about the turned axis: the same length, turns and points.
// A full circle's end comes back onto its start only to rounding, a few
// 1e-17 rad either side: still one full turn (not a ring of no length).
TEST(SegmentGeometry, TurnedCirclesAndHelicesAreFreePlaneArcsOfTheSameTurns) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  int turned = 0;
  for (double a_deg = -90.0; a_deg <= 90.0; a_deg += 10.0) {
    for (double c_deg = 0.0; c_deg < 360.0; c_deg += 15.0) {
      Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
      t.translation() = Vec3(220.0, 100.0, 20.0);
      t.linear() =
          (Eigen::AngleAxisd(c_deg * kDeg, Vec3::UnitZ()) * Eigen::AngleAxisd(a_deg * kDeg, Vec3::UnitX()))
              .toRotationMatrix();
      for (const double dz : {0.0, -1.0}) {
        for (const std::uint32_t turns : {0u, 3u}) {
          Segment g17 = arc(0.6, false, turns, dz);
          const SegmentGeometry want(g17);
          Segment free = g17;
          free.plane = Plane::Free;
          free.normal = t.linear() * Vec3::UnitZ();
          free.center = t * g17.center;
          free.start.head<3>() = t * Vec3(g17.start.head<3>());
          free.end.head<3>() = t * Vec3(g17.end.head<3>());
          const SegmentGeometry got(free);
          const std::string at = "A " + std::to_string(a_deg) + " C " + std::to_string(c_deg) + " dz " +
                                 std::to_string(dz) + " turns " + std::to_string(turns);
          ASSERT_NEAR(got.sweep_rad(), want.sweep_rad(), 1e-9) << at;
          ASSERT_NEAR(got.length(), want.length(), 1e-9) << at;
          for (int k = 0; k <= 40; ++k) {
            const double sk = want.length() * k / 40.0;
            ASSERT_LT((Vec3(got.at(sk).head<3>()) - t * Vec3(want.at(sk).head<3>())).norm(), 1e-9)
                << at << " at " << k << "/40";
            ASSERT_LT(
                (Vec3(got.tangent(sk).head<3>()) - t.linear() * Vec3(want.tangent(sk).head<3>())).norm(),
                1e-9)
                << at << " tangent at " << k << "/40";
          }
          ++turned;
        }
      }
    }
  }
  EXPECT_EQ(turned, 19 * 24 * 4);
}

// An IJK arc whose end lies off its start's circle (G-code accepts radii
// differing within a tolerance) is a spiral from one radius to the other:
// it leaves its start and reaches its end without a jump, and tangent and
// curvature are the derivatives of the path.
TEST(SegmentGeometry, SpiralArcRunsFromItsStartRadiusToItsEndRadius) {
  for (const double dz : {0.0, 3.0}) {
    for (const bool cw : {false, true}) {
      Segment s;
      s.kind = MotionKind::Arc;
      s.plane = Plane::XY;
      s.clockwise = cw;
      s.center = Vec3(50, 50, 10);
      s.start << 55, 50, 10, 0, 0, 0;                       // radius 5 at angle 0
      s.end << 50, cw ? 44.972 : 55.028, 10 + dz, 0, 0, 0;  // 5.028 a quarter turn on
      const SegmentGeometry g(s);
      ASSERT_TRUE(g.is_spiral());
      EXPECT_NEAR(g.radius_max(), 5.028, 1e-12);
      const double L = g.length();
      // half way the radius is half way (the radius is linear in the angle)
      const Pose mid = g.at(L / 2);
      EXPECT_NEAR(std::hypot(mid[0] - 50, mid[1] - 50), 5.014, 1e-12);
      // no jump at the end: the last micrometre of path ends on the end point
      EXPECT_LT((g.at(L - 1e-6) - s.end).norm(), 1.01e-6);
      EXPECT_LT((g.at(L * (1 - 1e-12)) - s.end).norm(), 1e-9);
      // |dp/ds| ≤ 1: the path never runs faster than planned
      for (int k = 0; k <= 100; ++k) {
        const double at = L * k / 100.0;
        const Pose t = g.tangent(at);
        EXPECT_LE(t.norm(), 1.0 + 1e-12);
        EXPECT_GT(t.norm(), 0.99);
        if (k == 0 || k == 100) continue;
        const double h = 1e-5;
        const Pose fd = (g.at(at + h) - g.at(at - h)) / (2 * h);
        EXPECT_LT((fd - t).norm(), 1e-8) << at;
        const Pose fd2 = (g.tangent(at + h) - g.tangent(at - h)) / (2 * h);
        EXPECT_LT((fd2 - g.curvature(at)).norm(), 1e-6) << at;
      }
      EXPECT_LT((g.start_tangent() - g.tangent(0)).norm(), 1e-15);
      EXPECT_LT((g.end_tangent() - g.tangent(L)).norm(), 1e-12);
      // points on the path are at distance 0 from it; 0.1 mm outward, 0.1
      for (const double f : {0.1, 0.37, 0.8}) {
        const Pose p = g.at(f * L);
        EXPECT_LT(g.distance_xyz(p.head<3>()), 1e-9);
        Vec3 out = p.head<3>() - s.center;
        out[2] = 0;
        EXPECT_NEAR(g.distance_xyz(p.head<3>() + 0.1 * out.normalized()), 0.1, 1e-6);
      }
    }
  }
}

TEST(SegmentGeometry, RoundingOfACircleIsNoSpiral) {
  Segment s = arc(1e6, false);
  s.end[0] += 1e-7;  // 1e-13 of the radius
  EXPECT_FALSE(SegmentGeometry(s).is_spiral());
  s = arc(5.0, false);
  s.end[0] += 1e-10;
  EXPECT_FALSE(SegmentGeometry(s).is_spiral());
  s.end[0] += 1e-8;
  EXPECT_TRUE(SegmentGeometry(s).is_spiral());
}

TEST(SegmentGeometry, DistanceToLineAndArc) {
  Segment l;
  l.kind = MotionKind::Linear;
  l.start << 0, 0, 0, 0, 0, 0;
  l.end << 10, 0, 0, 0, 0, 0;
  const SegmentGeometry gl(l);
  EXPECT_NEAR(gl.distance_xyz(Vec3(5, 3, 4)), 5.0, 1e-12);
  EXPECT_NEAR(gl.distance_xyz(Vec3(13, 4, 0)), 5.0, 1e-12);  // beyond the end
  const SegmentGeometry ga(arc(5.0, false));
  EXPECT_NEAR(ga.distance_xyz(Vec3(50, 56, 10)), 1.0, 1e-12);
  EXPECT_NEAR(ga.distance_xyz(Vec3(50, 50, 10)), 5.0, 1e-12);
}

// A steep helix of a small radius: the polar angle of a point is far from
// its closest point on the helix (the rise moves it along the turn). Points
// on the helix are at distance 0, points off it at their true distance.
TEST(SegmentGeometry, DistanceToASteepHelixIsTheTrueDistance) {
  const SegmentGeometry g(arc(0.03, true, 0, 1.9));  // r 30 µm, 1.9 mm up in one turn
  for (int k = 0; k <= 100; ++k) {
    const Pose p = g.at(g.length() * k / 100.0);
    EXPECT_LT(g.distance_xyz(p.head<3>()), 1e-9) << k;
    // half a micron off along the radius: half a micron away (within the
    // curvature's share, far under the rise)
    const Vec3 c(50, 50, p[2]);
    const Vec3 off = p.head<3>() + 0.0005 * (p.head<3>() - c).normalized();
    EXPECT_NEAR(g.distance_xyz(off), 0.0005, 2e-5) << k;
  }
}

// A rotary swing with a nanometre of X Y Z: its length is the rotary
// travel, not the nanometre (which the planner would take as no motion and
// skip, the next move then starting 16° away).
TEST(SegmentGeometry, LinearTravelBelowAnyMotionLeavesTheRotaryLength) {
  Segment l;
  l.kind = MotionKind::Rapid;
  l.start << 169.177048399, 188.863663934, 144.934388443, 0, 0, 28.6326095181;
  l.end << 169.177048399, 188.863663933, 144.934388443, 0, 0, 44.8805314402;
  EXPECT_NEAR(SegmentGeometry(l).length(), 44.8805314402 - 28.6326095181, 1e-9);
  EXPECT_NEAR(path_length(l), 44.8805314402 - 28.6326095181, 1e-9);
}

// One of each kind: arcs (whole turns, a helix, a quarter), a free-plane
// arc as the blender makes them, a line with a rotary axis, a rotary-only move.
std::vector<Segment> segments_of_every_kind() {
  std::vector<Segment> segs = {arc(5.0, false), arc(5.0, true, 1), arc(2.0, false, 2, 3.0)};
  Segment l;
  l.kind = MotionKind::Linear;
  l.start << 1, 2, 3, 0, 0, 0;
  l.end << 4, -2, 3.5, 0, 0, 10;
  segs.push_back(l);
  Segment rot = l;
  rot.end.head<3>() = rot.start.head<3>();  // rotary only
  segs.push_back(rot);
  Segment part = arc(3.0, false);  // a quarter
  part.end << 50, 53, 10, 0, 0, 0;
  segs.push_back(part);
  Segment blend = part;  // a free-plane arc
  blend.plane = Plane::Free;
  blend.center = Vec3(50, 50, 10);
  blend.end << 50 + 3 * std::cos(0.3), 50 + 3 * std::sin(0.3), 10, 0, 0, 0;
  blend.normal = Vec3(0, 0, 1);
  segs.push_back(blend);
  return segs;
}

// start_tangent(), end_tangent() and path_length() skip work (sin and cos of
// the ends, the arc set-up of a line) but must give the same bits.
TEST(SegmentGeometry, EndTangentsAndPathLengthMatchTheGeneralForms) {
  for (const Segment& s : segments_of_every_kind()) {
    const SegmentGeometry g(s);
    EXPECT_EQ(g.start_tangent(), g.tangent(0.0));
    // the sweep's sine and cosine come from the end point, not from sin and
    // cos of the angle: the same to rounding (and exact on whole turns)
    EXPECT_LT((g.end_tangent() - g.tangent(g.length())).norm(), 1e-14);
    EXPECT_EQ(path_length(s), g.length());
    EXPECT_NEAR(g.sin_sweep(), std::sin(g.sweep_rad()), 1e-15);
    EXPECT_NEAR(g.cos_sweep(), std::cos(g.sweep_rad()), 1e-15);
  }
}

// set() reuses a geometry in place (the blender's slots hold lines, arcs and
// blends in turn): whatever it held before, it becomes the fresh one's.
TEST(SegmentGeometry, SetOverAUsedGeometryIsAFreshOne) {
  const std::vector<Segment> segs = segments_of_every_kind();
  for (const Segment& before : segs) {
    for (const Segment& s : segs) {
      SegmentGeometry g(before);
      g.set(s);
      const SegmentGeometry fresh(s);
      ASSERT_EQ(g.is_arc(), fresh.is_arc());
      EXPECT_EQ(g.length(), fresh.length());
      EXPECT_EQ(g.radius(), fresh.radius());
      EXPECT_EQ(g.sweep_rad(), fresh.sweep_rad());
      EXPECT_EQ(g.sin_sweep(), fresh.sin_sweep());
      EXPECT_EQ(g.cos_sweep(), fresh.cos_sweep());
      EXPECT_EQ(g.plane_speed_ratio(), fresh.plane_speed_ratio());
      EXPECT_EQ(g.start_tangent(), fresh.start_tangent());
      EXPECT_EQ(g.end_tangent(), fresh.end_tangent());
      for (int k = -1; k <= 8; ++k) {
        const double at_s = fresh.length() * k / 7.0;
        EXPECT_EQ(g.at(at_s), fresh.at(at_s)) << k;
        Pose in_place = Pose::Constant(-1.0);
        g.at(at_s, in_place);
        EXPECT_EQ(in_place, fresh.at(at_s)) << k;
      }
      EXPECT_EQ(g.tangent(fresh.length() / 3), fresh.tangent(fresh.length() / 3));
      EXPECT_EQ(g.curvature(fresh.length() / 3), fresh.curvature(fresh.length() / 3));
    }
  }
}

TEST(DeviationMeter, MeasuresAgainstTheWindowOfSegments) {
  std::vector<Segment> segs(3);
  for (int k = 0; k < 3; ++k) {
    segs[k].kind = MotionKind::Linear;
    segs[k].start << k * 10.0, 0, 0, 0, 0, 0;
    segs[k].end << (k + 1) * 10.0, 0, 0, 0, 0, 0;
  }
  std::size_t i = 0;
  DeviationMeter dm([&](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  });
  EXPECT_NEAR(dm.add(Vec3(5, 0.001, 0), 0), 0.001, 1e-12);
  EXPECT_NEAR(dm.add(Vec3(25, 0.002, 0), 2), 0.002, 1e-12);
  EXPECT_NEAR(dm.max_mm(), 0.002, 1e-12);
}

// A point known by its program line only (the tool tip under TCP) is
// compared with that line's segment and those before it, and held to the
// tolerance plus the extra allowance.
TEST(DeviationMeter, AtLineFindsTheLinesSegmentAndHoldsTheExtraAllowance) {
  std::vector<Segment> segs(3);
  for (int k = 0; k < 3; ++k) {
    segs[k].kind = MotionKind::Linear;
    segs[k].start << 0, k * 10.0, 0, 0, 0, 0;  // a staircase: lines 3, 5, 9
    segs[k].end << 0, (k + 1) * 10.0, 0, 0, 0, 0;
    segs[k].line = k == 0 ? 3 : k == 1 ? 5 : 9;
  }
  segs[2].start << 0, 20, 0, 0, 0, 0;
  segs[2].end << 10, 20, 0, 0, 0, 0;  // line 9 turns along X
  std::size_t i = 0;
  DeviationMeter dm(
      [&](Segment& out) {
        if (i == segs.size()) return SourceStatus::End;
        out = segs[i++];
        return SourceStatus::Item;
      },
      0.0, 0.0, 0.001);
  EXPECT_NEAR(dm.add_at_line(Vec3(0.0005, 5, 0), 3), 0.0005, 1e-12);
  EXPECT_EQ(dm.excess_mm(), 0.0);                                // within the extra 1 µm
  EXPECT_NEAR(dm.add_at_line(Vec3(0.5, 15, 0), 5), 0.5, 1e-12);  // line 5's segment, not line 9's
  EXPECT_NEAR(dm.excess_mm(), 0.5 - 0.001 - DeviationMeter::kDeviationSlackMm, 1e-12);
  EXPECT_EQ(dm.excess_line(), 5u);
  EXPECT_NEAR(dm.add_at_line(Vec3(5, 20.2, 0), 9), 0.2, 1e-12);
}

}  // namespace
}  // namespace lcnc
