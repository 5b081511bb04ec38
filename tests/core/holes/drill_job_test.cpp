// A drilling job: travel, settle, approach, the hole, retract — per hole, in
// joints, with the hole number as the line; checked against the travel.
#include "holes/drill_job.h"

#include <gtest/gtest.h>

#include "core/plan/test_machine.h"
#include "machine/machine_config.h"

namespace lcnc {
namespace {

HoleProcessParams hole(std::uint32_t n, double x, double a, double c) {
  HoleProcessParams p;
  p.hole_number = n;
  p.position << x, 100.0, 20.0, a, 0.0, c;
  p.feed_mm_min = 600.0;
  p.layer_feed_mm = 0.1;
  p.layer_count = 3;
  p.total_depth_mm = 0.3;
  p.power_pct = 70.0;
  p.head.start_radius_mm = 0.5;
  p.head.end_radius_mm = 0.5;
  return p;
}

TEST(DrillJob, EachHoleIsTravelSettleApproachHoleRetract) {
  const FiveAxisKinematics kin;
  const std::vector<HoleProcessParams> rows = {hole(4, 100, 0, 0), hole(9, 150, -20, 90)};
  DrillOptions o;
  o.clearance_mm = 5.0;
  o.head_settle_s = 0.25;
  Result<DrillJob> job = build_drill_job(rows, kin, Pose::Zero(), o);
  ASSERT_TRUE(static_cast<bool>(job)) << job.error().to_string();
  ASSERT_EQ(job->holes.size(), 2u);
  const std::vector<Segment>& s = job->segments;
  // continuous: every segment starts where the one before ends
  EXPECT_EQ(s.front().start, Pose::Zero());
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_LT((s[i].start - s[i - 1].end).norm(), 1e-9) << i;
  for (std::size_t k = 0; k < 2; ++k) {
    const DrillStep& h = job->holes[k];
    EXPECT_EQ(h.hole_number, rows[k].hole_number);
    EXPECT_EQ(h.head_segment, h.first_segment + 1);
    EXPECT_EQ(s[h.first_segment].kind, MotionKind::Rapid);  // travel
    const Segment& settle = s[h.head_segment];
    EXPECT_EQ(settle.kind, MotionKind::Dwell);
    EXPECT_EQ(settle.dwell_s, 0.25);
    EXPECT_EQ(settle.laser, LaserMode::Off);
    EXPECT_EQ(s[h.head_segment + 1].kind, MotionKind::Rapid);  // approach
    EXPECT_EQ(s[h.end_segment - 1].kind, MotionKind::Rapid);   // retract
    for (std::size_t i = h.first_segment; i < h.end_segment; ++i) {
      EXPECT_EQ(s[i].line, rows[k].hole_number);
      EXPECT_EQ(s[i].start[3], i == h.first_segment ? s[i].start[3] : rows[k].position[3]);
      if (s[i].kind == MotionKind::Rapid || s[i].kind == MotionKind::Dwell) {
        EXPECT_EQ(s[i].laser, LaserMode::Off);
      } else {
        EXPECT_EQ(s[i].laser, LaserMode::Constant);
        EXPECT_EQ(s[i].power_pct, 70.0);
      }
    }
    EXPECT_EQ(h.head.start_radius_mm, 0.5);
    // the clearance point is 5 mm from the surface point along the tool axis
    const Pose& above = settle.start;
    const Pose& surface = s[h.head_segment + 1].end;
    EXPECT_NEAR((above.head<3>() - surface.head<3>()).norm(), 5.0, 1e-9);
    EXPECT_EQ(above[3], rows[k].position[3]);
    EXPECT_EQ(above[5], rows[k].position[5]);
    // the retract runs straight up the wall to the clearance height: along
    // the axis, ending a scan radius beside the clearance point
    const Vec3 axis = (above.head<3>() - surface.head<3>()).normalized();
    const Segment& retract = s[h.end_segment - 1];
    const Vec3 up = retract.end.head<3>() - retract.start.head<3>();
    EXPECT_NEAR(up.normalized().dot(axis), 1.0, 1e-12);
    const Vec3 beside = retract.end.head<3>() - above.head<3>();
    EXPECT_NEAR(beside.dot(axis), 0.0, 1e-9);
    EXPECT_NEAR(beside.norm(), 0.5, 1e-9);
  }
  EXPECT_EQ(job->holes[1].first_segment, job->holes[0].end_segment);
  EXPECT_EQ(job->holes[1].end_segment, s.size());
}

TEST(DrillJob, CheckSumsTheJobAndNamesAHoleBeyondTheTravel) {
  const MachineConfig m = testing::test_machine();
  const FiveAxisKinematics kin;
  Result<DrillJob> job = build_drill_job({hole(1, 100, 0, 0), hole(2, 200, 0, 0)}, kin, Pose::Zero());
  ASSERT_TRUE(static_cast<bool>(job));
  Result<ProgramSummary> sum = check_drill_job(*job, m, "t.csv");
  ASSERT_TRUE(static_cast<bool>(sum)) << sum.error().to_string();
  EXPECT_EQ(sum->lines, 2u);
  EXPECT_EQ(sum->segments, job->segments.size());
  // each hole: 3 helix turns of r 0.5 plus the radial lead-in … at least 3·π mm cut
  EXPECT_GT(sum->feed_length_mm, 2 * 3 * 3.14159);
  EXPECT_GT(sum->path_length_mm, sum->feed_length_mm + 200.0);
  // hole 3 at Z near the top of the travel: its clearance point is beyond it
  HoleProcessParams high = hole(3, 300, 0, 0);
  high.position[2] = m.axes[2].max - 1.0;
  Result<DrillJob> bad = build_drill_job({hole(1, 100, 0, 0), high}, kin, Pose::Zero());
  ASSERT_TRUE(static_cast<bool>(bad));
  Result<ProgramSummary> refused = check_drill_job(*bad, m, "t.csv");
  ASSERT_FALSE(static_cast<bool>(refused));
  EXPECT_EQ(refused.error().code, ErrorCode::GcodeBeyondTravel);
  EXPECT_EQ(refused.error().line, 3u);
  EXPECT_NE(refused.error().message.find("hole 3: axis Z"), std::string::npos) << refused.error().message;
}

// The machine's [kinematics] decide the joints: on a table-table machine a
// tilted hole's axis becomes machine Z and its helix stays one G17 helix; on
// the head-head default it does not.
TEST(DrillJob, TheMachinesKinematicsPlaceTheHoles) {
  MachineConfig m = testing::test_machine();
  m.kinematics.variant = MachineVariant::TableTable;
  const std::vector<HoleProcessParams> rows = {hole(1, 100, -20, 90)};
  Result<DrillJob> table = build_drill_job(rows, kinematics_from(m), Pose::Zero());
  ASSERT_TRUE(static_cast<bool>(table)) << table.error().to_string();
  int xy_arcs = 0;
  for (const Segment& s : table->segments) {
    if (s.kind != MotionKind::Arc) continue;
    EXPECT_EQ(s.plane, Plane::XY);
    ++xy_arcs;
  }
  EXPECT_EQ(xy_arcs, 1);  // one helix of layer_count turns
  m.kinematics.variant = MachineVariant::HeadHead;
  Result<DrillJob> head = build_drill_job(rows, kinematics_from(m), Pose::Zero());
  ASSERT_TRUE(static_cast<bool>(head));
  for (const Segment& s : head->segments) EXPECT_FALSE(s.kind == MotionKind::Arc && s.plane == Plane::XY);
}

TEST(DrillJob, BadRowIsAnErrorNamingTheHole) {
  HoleProcessParams p = hole(5, 100, 0, 0);
  p.total_depth_mm = 2.0;
  Result<DrillJob> job = build_drill_job({p}, FiveAxisKinematics{}, Pose::Zero());
  ASSERT_FALSE(static_cast<bool>(job));
  EXPECT_NE(job.error().message.find("hole 5"), std::string::npos);
}

}  // namespace

// The moments of three holes (segments: hole k travels at 10k, settles at
// 10k + 3): looked at every segment, and looked at seldom — a jump over a
// dwell, over a whole hole, to the end. Each way every moment comes once,
// in order; a head block whose dwell passed unseen is still due (it was
// missed before: a loaded run skipped hole 2's head block).
TEST(DrillProgress, EveryMomentOnceInOrderHoweverSeldomItIsLookedAt) {
  std::vector<DrillStep> holes(3);
  for (std::size_t k = 0; k < 3; ++k) {
    holes[k].first_segment = 10 * k;
    holes[k].head_segment = 10 * k + 3;
    holes[k].end_segment = 10 * k + 9;
  }
  using K = DrillMoment::Kind;
  const std::vector<std::pair<K, std::size_t>> expected = {{K::Start, 0}, {K::Head, 0}, {K::End, 0},
                                                           {K::Start, 1}, {K::Head, 1}, {K::End, 1},
                                                           {K::Start, 2}, {K::Head, 2}, {K::End, 2}};
  auto run = [&](const std::vector<std::size_t>& looks) {
    DrillProgress p(holes);
    std::vector<std::pair<K, std::size_t>> got;
    for (std::size_t seg : looks)
      for (const DrillMoment& m : p.advance(seg)) got.emplace_back(m.kind, m.hole);
    for (const DrillMoment& m : p.finish()) got.emplace_back(m.kind, m.hole);
    return got;
  };
  std::vector<std::size_t> every;
  for (std::size_t s = 0; s < 30; ++s) every.push_back(s);
  EXPECT_EQ(run(every), expected);
  EXPECT_EQ(run({0, 2, 11, 12, 25}), expected);  // hole 0's dwell and hole 2's start unseen
  EXPECT_EQ(run({1, 29}), expected);             // holes 1 and 2 wholly unseen
  EXPECT_EQ(run({}), (std::vector<std::pair<K, std::size_t>>{}));
  // the head block comes at its dwell, not before
  DrillProgress p(holes);
  EXPECT_EQ(p.advance(2).size(), 1u);  // Start 0
  ASSERT_EQ(p.advance(3).size(), 1u);  // Head 0
}

}  // namespace lcnc
