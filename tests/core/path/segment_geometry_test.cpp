#include "path/segment_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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

TEST(SegmentGeometry, HelixWithTurns) {
  const SegmentGeometry g(arc(2.0, false, 2, 3.0));  // 3 turns, 3 mm up
  const double plane = 3 * 2 * std::numbers::pi * 2.0;
  EXPECT_NEAR(g.length(), std::hypot(plane, 3.0), 1e-9);
  EXPECT_NEAR(g.at(g.length() / 3)[2], 11.0, 1e-9);  // one turn, one mm
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

}  // namespace
}  // namespace lcnc
