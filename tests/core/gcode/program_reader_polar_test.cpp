// Polar coordinates, LinuxCNC's @ (radius) and ^ (angle, degrees) in place
// of X and Y (tests/data/linuxcnc_compare/polar_coordinates.ngc runs them
// through LinuxCNC's own interpreter in the e2e comparison).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::pose;
using test::segments;
using test::start_at;

TEST(PolarCoordinates, AbsoluteAboutTheOriginAWordNotGivenKeepsItsValue) {
  // from (10, 10, 10), G55 = X+500 in the test machine: about G55's origin
  const auto segs = segments("G55 G1 @20 ^30 F600\n^60\n@5\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_POSE_NEAR(segs[0].end, pose(500 + 20 * std::sqrt(3.0) / 2, 10, 10), 1e-9);
  EXPECT_POSE_NEAR(segs[1].end, pose(500 + 10, 10 * std::sqrt(3.0), 10), 1e-9);
  EXPECT_POSE_NEAR(segs[2].end, pose(500 + 2.5, 2.5 * std::sqrt(3.0), 10), 1e-9);
}

TEST(PolarCoordinates, IncrementalAddsToTheRadiusAndAngleAboutTheOrigin) {
  // (10, 10): radius √200 at 45°; G91 @-√200/2 ^45 → radius √50 at 90°
  const auto segs = segments("G91 G1 @[-SQRT[200] / 2] ^45 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(0, std::sqrt(50.0), 10), 1e-9);
  const Diagnostic d = expect_error("G0 X0 Y0\nG91 G0 ^10\n", ErrorCode::GcodeSyntax, 2, 8);
  EXPECT_MENTIONS(d, "angle is undefined");
}

TEST(PolarCoordinates, NeverWithXOrYNorAsOffsetData) {
  Diagnostic d = expect_error("G0 @10 X5\n", ErrorCode::GcodeSyntax, 1, 4);
  EXPECT_MENTIONS(d, "in place of X and Y");
  d = expect_error("G92 @10\n", ErrorCode::GcodeSyntax, 1, 5);
  EXPECT_MENTIONS(d, "only on moves");
  expect_error("G0 @10 @20\n", ErrorCode::GcodeRepeatedWord, 1, 8);
}

TEST(PolarCoordinates, ACannedCycleSpacesHolesOnACircle) {
  // G91 ^60 L6 from (10, 0) in G56 (origin at machine X100 Y50): six holes
  // 60° apart on a radius of 10
  std::vector<Segment> holes;
  for (const Segment& s : segments("G56 G91 G81 ^60 R-1 Z-2 L6 F300\n", start_at(110, 50, 10)))
    if (s.kind == MotionKind::Linear) holes.push_back(s);
  ASSERT_EQ(holes.size(), 6u);
  for (int k = 0; k < 6; ++k) {
    const double t = (60.0 * (k + 1)) * std::numbers::pi / 180.0;
    EXPECT_POSE_NEAR(holes[k].end, pose(100 + 10 * std::cos(t), 50 + 10 * std::sin(t), 7), 1e-9) << k;
  }
}

}  // namespace
}  // namespace lcnc
