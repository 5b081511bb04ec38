#include "kinematics/five_axis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "kinematics/tcp_path.h"
#include "kinematics_test_util.h"
#include "path/segment_geometry.h"
#include "support/test_scale.h"

namespace lcnc {
namespace {

// Property-test size: LCNC_TEST_SCALE multiplies it for long runs.
using testing::scaled;

using testing::joints;

FiveAxisKinematics make(MachineVariant v) {
  FiveAxisGeometry g;
  g.variant = v;
  g.head_c_to_a_mm = Vec3(3.0, -5.0, -80.0);  // off-axis: every offset term counts
  g.table_c_offset_mm = Vec3(2.0, 4.0, 50.0);
  return FiveAxisKinematics(g);
}

TEST(FiveAxis, ToolAxisFollowsAThenC) {
  EXPECT_TRUE(tool_axis(0.0, 123.0).isApprox(Vec3::UnitZ()));
  EXPECT_TRUE(tool_axis(90.0, 0.0).isApprox(Vec3(0.0, -1.0, 0.0)));
  EXPECT_TRUE(tool_axis(90.0, 90.0).isApprox(Vec3(1.0, 0.0, 0.0)));
  EXPECT_TRUE(tool_axis(-30.0, 10.0).isApprox(tool_axis(30.0, 190.0)));
}

TEST(FiveAxis, InverseOfForwardIsIdentityOverTheWorkspace) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> x(0, 1000), y(0, 450), z(0, 500), a(-95, 95), c(0, 360),
      jitter(-2.0, 2.0);
  for (MachineVariant v : {MachineVariant::HeadHead, MachineVariant::TableTable}) {
    const FiveAxisKinematics kin = make(v);
    for (int i = 0; i < scaled(5000); ++i) {
      double ai = a(rng);
      if (std::abs(ai) < 1e-3) ai = 1.0;  // C is undefined on the pole
      const Pose q = joints(x(rng), y(rng), z(rng), ai, c(rng));
      const ToolPose t = kin.forward(q);
      ASSERT_NEAR(t.axis.norm(), 1.0, 1e-12);
      // The machine stood near q: the inverse must come back to q itself.
      Pose prev = q;
      prev[index(Axis::A)] += jitter(rng);
      prev[index(Axis::C)] += jitter(rng);
      const Result<Pose> back = kin.inverse(t, prev);
      ASSERT_TRUE(back.ok()) << back.error().to_string();
      ASSERT_LT((*back - q).cwiseAbs().maxCoeff(), 1e-9) << "variant " << int(v) << " i " << i;
      // Both solutions give the same tip and axis.
      for (const Pose& s : kin.inverse_solutions(t)) {
        const ToolPose ts = kin.forward(s);
        ASSERT_LT((ts.tip_mm - t.tip_mm).norm(), 1e-9);
        ASSERT_LT(angle_between_deg(ts.axis, t.axis), 1e-9);
      }
    }
  }
}

TEST(FiveAxis, ChoosesTheShorterOfTheTwoSolutions) {
  const RotaryLimits lim;
  // k(−20°, 170°) = k(20°, 350°): from (10°, 350°) the second is closer.
  Result<RotaryJoints> r = choose_rotary(tool_axis(-20.0, 170.0), {10.0, 350.0}, lim);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->a_deg, 20.0, 1e-9);
  EXPECT_NEAR(r->c_deg, 350.0, 1e-9);
  // From (−10°, 175°) the A < 0 solution is closer.
  r = choose_rotary(tool_axis(-20.0, 170.0), {-10.0, 175.0}, lim);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->a_deg, -20.0, 1e-9);
  EXPECT_NEAR(r->c_deg, 170.0, 1e-9);
}

TEST(FiveAxis, UnwrapsCToTheNearestTurn) {
  const Result<RotaryJoints> r = choose_rotary(tool_axis(40.0, 20.0), {40.0, 710.0}, {});
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->c_deg, 740.0, 1e-9);  // 720 + 20, not back to 20
  EXPECT_NEAR(wrap_360(r->c_deg), 20.0, 1e-9);
  EXPECT_NEAR(nearest_turn(359.0, 0.5), -1.0, 1e-12);
}

TEST(FiveAxis, RespectsTheARange) {
  RotaryLimits lim;
  lim.a_min_deg = 0.0;  // a machine that tilts one way only
  const Result<RotaryJoints> r = choose_rotary(tool_axis(-30.0, 0.0), {-0.0, 0.0}, lim);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->a_deg, 30.0, 1e-9);
  EXPECT_NEAR(wrap_360(r->c_deg), 180.0, 1e-9);
  // Tilted beyond ±95°: neither solution reachable.
  const Result<RotaryJoints> e = choose_rotary(tool_axis(100.0, 0.0), {0.0, 0.0}, RotaryLimits{});
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.error().code, ErrorCode::GcodeBeyondTravel);
  EXPECT_NE(e.error().message.find("100"), std::string::npos) << e.error().message;
}

TEST(FiveAxis, PoleKeepsC) {
  const Result<RotaryJoints> r = choose_rotary(Vec3::UnitZ(), {5.0, 123.0}, {});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->a_deg, 0.0);
  EXPECT_EQ(r->c_deg, 123.0);
  EXPECT_TRUE(on_pole(Vec3::UnitZ()));
  EXPECT_FALSE(on_pole(tool_axis(0.001, 0.0)));
}

TEST(FiveAxis, RotaryLimitsComeFromTheMachineConfig) {
  MachineConfig m;
  m.axis(Axis::A) = AxisConfig{};
  m.axis(Axis::A).present = true;
  m.axis(Axis::A).min = -60.0;
  m.axis(Axis::A).max = 90.0;
  m.axis(Axis::A).max_velocity = 90.0;
  m.axis(Axis::A).max_acceleration = 900.0;
  const RotaryLimits l = rotary_limits_from(m);
  EXPECT_EQ(l.a_min_deg, -60.0);
  EXPECT_EQ(l.a_max_velocity_deg_s, 90.0);
  EXPECT_EQ(l.c_max_velocity_deg_s, RotaryLimits{}.c_max_velocity_deg_s);  // no C: default
}

TEST(FiveAxis, TableTableTurnsTheHoleAxisOntoMachineZ) {
  const FiveAxisKinematics kin = make(MachineVariant::TableTable);
  const RotaryJoints r{35.0, 250.0};
  const Eigen::Isometry3d t = kin.tip_to_joints(r);
  EXPECT_LT((t.linear() * tool_axis(r) - Vec3::UnitZ()).norm(), 1e-12);
}

// TCP: the tip stays on the programmed line within 1 µm while A and C move,
// along the curve pieces as the planner runs them, and the pieces join with
// the same dq/ds (no corner, no velocity jump at any speed).
TEST(TcpControl, TipStaysOnTheLineWhileAAndCMove) {
  for (MachineVariant v : {MachineVariant::HeadHead, MachineVariant::TableTable}) {
    const FiveAxisKinematics kin = make(v);
    const Vec3 a(10.0, 20.0, 30.0), b(60.0, -10.0, 40.0);
    for (OrientationMethod m :
         {OrientationMethod::JointLinear, OrientationMethod::Vector, OrientationMethod::PoleSmoothed}) {
      const Result<OrientationMove> move =
          OrientationMove::between_joints(m, {30.0, 10.0}, {-25.0, 140.0}, kin.limits());
      ASSERT_TRUE(move.ok()) << move.error().to_string();
      Segment proto;
      proto.feed_mm_s = 20.0;
      const TcpMove tm = TcpMove::make(kin, a, b, *move);
      const Result<std::vector<Segment>> segs = tcp_curve_segments(tm, proto, 0.0005, 0.001);
      ASSERT_TRUE(segs.ok()) << segs.error().to_string();
      ASSERT_GT(segs->size(), 1u);
      EXPECT_LT((kin.forward(segs->front().start).tip_mm - a).norm(), 1e-9);
      EXPECT_LT((kin.forward(segs->back().end).tip_mm - b).norm(), 1e-9);
      double worst = 0.0, time = 0.0;
      for (std::size_t i = 0; i < segs->size(); ++i) {
        const Segment& s = (*segs)[i];
        ASSERT_TRUE(s.curve);
        EXPECT_EQ(s.smooth_in, i > 0);
        const SegmentGeometry geo(s);
        time += geo.length() / s.feed_mm_s;
        if (i > 0) {
          const Segment& before = (*segs)[i - 1];
          ASSERT_EQ(s.start, before.end);
          const Pose jump = geo.start_tangent() - SegmentGeometry(before).end_tangent();
          EXPECT_LT(jump.norm(), 1e-6 * geo.start_tangent().norm()) << "piece " << i;
        }
        for (int k = 0; k <= 40; ++k)
          worst =
              std::max(worst, distance_to_segment(kin.forward(geo.at(geo.length() * k / 40.0)).tip_mm, a, b));
      }
      EXPECT_LE(worst, 0.0005) << "variant " << int(v) << " " << method_name(m);
      EXPECT_NEAR(time, (b - a).norm() / proto.feed_mm_s, 1e-9);  // the tip at F
      // The rotary axes really moved.
      const Pose d = segs->back().end - segs->front().start;
      EXPECT_GT(std::max(std::abs(d[index(Axis::A)]), std::abs(d[index(Axis::C)])), 10.0);
    }
  }
}

// At its feed a piece takes the time the tip needs at F for its travel
// along it; where the tip stands still, the time A and C need at F deg/s
// (RS274NGC's feed of a rotary move).
TEST(TcpControl, FeedIsTheTipsSpeedOrTheRotaryAxesWhereTheTipStands) {
  const FiveAxisKinematics kin = make(MachineVariant::HeadHead);
  const Result<OrientationMove> move =
      OrientationMove::between_joints(OrientationMethod::Vector, {20.0, 0.0}, {40.0, 30.0}, kin.limits());
  ASSERT_TRUE(move.ok());
  Segment proto;
  proto.feed_mm_s = 10.0;
  const Vec3 a(0, 0, 0), b(5, 0, 0);
  const auto segs = tcp_curve_segments(TcpMove::make(kin, a, b, *move), proto, 0.001, 0.001);
  ASSERT_TRUE(segs.ok());
  for (const Segment& s : *segs) {
    const double tip = (kin.forward(s.end).tip_mm - kin.forward(s.start).tip_mm).norm();
    EXPECT_NEAR(s.curve_length / s.feed_mm_s, tip / proto.feed_mm_s, 1e-6 * tip / proto.feed_mm_s);
  }
  const Result<OrientationMove> turn = OrientationMove::between_joints(
      OrientationMethod::JointLinear, {30.0, 0.0}, {30.0, 90.0}, kin.limits());
  ASSERT_TRUE(turn.ok());
  EXPECT_NEAR(tcp_move_length(a, a, *turn), 90.0, 1e-9);
  const auto spin = tcp_curve_segments(TcpMove::make(kin, a, a, *turn), proto, 0.001, 0.001);
  ASSERT_TRUE(spin.ok());
  double time = 0.0;
  for (const Segment& s : *spin) {
    time += s.curve_length / s.feed_mm_s;
    EXPECT_LT((kin.forward(s.end).tip_mm - a).norm(), 1e-9);  // the tip stands
  }
  EXPECT_NEAR(time, 90.0 / proto.feed_mm_s, 1e-9);
}

TEST(TcpControl, RejectsZeroTolerance) {
  const FiveAxisKinematics kin;
  const auto move =
      OrientationMove::between_joints(OrientationMethod::Vector, {20.0, 0.0}, {40.0, 30.0}, kin.limits());
  ASSERT_TRUE(move.ok());
  const auto segs =
      tcp_curve_segments(TcpMove::make(kin, Vec3::Zero(), Vec3::UnitX(), *move), Segment{}, 0.0, 0.1);
  ASSERT_FALSE(segs.ok());
  EXPECT_EQ(segs.error().code, ErrorCode::GcodeBadValue);
}

}  // namespace
}  // namespace lcnc
