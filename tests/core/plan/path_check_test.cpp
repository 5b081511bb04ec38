// A run's path check: the joints against the planner's segments, and under
// tool-centre-point control the tool tip against the program as written.
#include "plan/path_check.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "core/plan/test_machine.h"

namespace lcnc {
namespace {

bool mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (const std::string& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

TEST(PathCheck, SegmentsOfAJobHoldTheJointsToTheirPath) {
  const MachineConfig m = testing::shipped_machine(false);
  auto segs = std::make_shared<std::vector<Segment>>(1);
  Segment& s = (*segs)[0];
  s.kind = MotionKind::Linear;
  s.start << 100, 100, 100, 0, 0, 0;
  s.end << 110, 100, 100, 0, 0, 0;
  s.feed_mm_s = 10.0;
  s.line = 4;
  std::unique_ptr<PathCheck> c = PathCheck::for_segments(segs, m);
  Pose p = s.start;
  for (int k = 0; k <= 10; ++k) {
    p[0] = 100 + k;
    c->add(p, 0, 4);
  }
  EXPECT_TRUE(c->breaches().empty());
  p[1] = 100.1;  // 0.1 mm off an exact path (G61)
  c->add(p, 0, 4);
  ASSERT_EQ(c->breaches().size(), 1u);
  EXPECT_TRUE(mentions(c->breaches(), "path deviation 0.1000 mm")) << c->breaches().front();
  EXPECT_TRUE(mentions(c->breaches(), "at line 4")) << c->breaches().front();
  EXPECT_NEAR(c->max_mm(), 0.1, 1e-9);
}

// Under TCP the joints may keep the joint path and still turn the tool about
// the wrong point: only the tip shows it.
TEST(PathCheck, UnderTcpTheToolTipIsHeldToTheProgramAsWritten) {
  const MachineConfig m = testing::shipped_machine(true);
  const FiveAxisKinematics kin = kinematics_from(m);
  const std::string path = ::testing::TempDir() + "/path_check_tcp.ngc";
  std::ofstream(path) << "G21 G90 G61\nG1 X300 Y200 Z100 A20 C30 F600\nG1 X310\nM2\n";
  ReaderOptions o;
  o.start = kin.joints_for_tip(Vec3(300, 200, 100), RotaryJoints{20, 30});
  Result<std::unique_ptr<PathCheck>> c = PathCheck::for_program(path, m, o);
  ASSERT_TRUE(static_cast<bool>(c)) << c.error().to_string();
  // along line 3 (segment 0: line 2 is no motion from there)
  for (int k = 0; k <= 10; ++k)
    (*c)->add(kin.joints_for_tip(Vec3(300 + k, 200, 100), RotaryJoints{20, 30}), 0, 3);
  EXPECT_TRUE((*c)->breaches().empty()) << (*c)->breaches().front();
  EXPECT_LT((*c)->max_mm(), 1e-6);
  // the same head position with A half a degree off: the tip moves ~1 mm
  Pose off = kin.joints_for_tip(Vec3(305, 200, 100), RotaryJoints{20, 30});
  off[index(Axis::A)] += 0.5;
  (*c)->add(off, 0, 3);
  EXPECT_TRUE(mentions((*c)->breaches(), "tool tip deviation")) << ::testing::PrintToString((*c)->breaches());
  EXPECT_FALSE(mentions((*c)->breaches(), "path deviation"));  // the joints' X Y Z are on theirs
  EXPECT_GT((*c)->max_mm(), 0.5);
}

}  // namespace
}  // namespace lcnc
