// A drilling job as the machine moves it: the job's segments planned by the
// Planner, period by period, on the shipped machine (head-head). Per hole,
// from the tool tip (forward kinematics of the planned joints, taken into the
// hole's frame) while the laser is on:
//   * rings: the turns of the tip about the hole axis — the programmed number
//     (helix: one per layer; circle scan: radius_turns per layer), tilted or
//     not;
//   * feed: the tip's speed — never above the programmed feed, and over the
//     whole of the hole's lasing (the window: 1.5 … 16 s here) on average
//     within kMinFeedShare of it: only the stops at the ends of the rings and
//     radial steps, which the acceleration forces, cost time;
// and the run, quantized to steps, passes the motion check.
#include "holes/drill_job.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "machine/machine_config.h"
#include "plan/coarse_interpolator.h"
#include "plan/motion_check.h"
#include "plan/planner.h"

namespace lcnc {
namespace {

// Lasing time at the feed, averaged over a hole: ≥ this share of the feed.
// (A flat circle scan, which stops at each of its 64 ring and step ends,
// reaches 0.98; chords that stop every 0.06 mm, 0.62.)
constexpr double kMinFeedShare = 0.95;
// A whole number of turns, to within this (turns): a ring's last few
// nanometres may fall in a period whose sample already belongs to the next,
// unlit move (1e-3 turns is 3 µm on a 0.5 mm ring; a lost ring is 1).
constexpr double kTurnTolerance = 1e-3;

struct HoleMotion {
  double turns = 0.0;  // signed, about the hole axis (+z of the hole frame)
  double lasing_s = 0.0;
  double path_mm = 0.0;  // the tip's, while lasing
  double max_speed_mm_s = 0.0;
};

MachineConfig shipped() {
  Result<MachineConfig> m =
      load_machine_config(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
  EXPECT_TRUE(static_cast<bool>(m)) << m.error().to_string();
  return *m;
}

// Plans the job on `m` and measures each hole (keyed by hole number); the
// quantized run must pass the motion check.
std::map<std::uint32_t, HoleMotion> plan_and_measure(const DrillJob& job,
                                                     const std::vector<HoleProcessParams>& rows,
                                                     const MachineConfig& m) {
  const FiveAxisKinematics kin = kinematics_from(m);
  std::map<std::uint32_t, Eigen::Isometry3d> to_local;
  for (const HoleProcessParams& r : rows) to_local[r.hole_number] = hole_frame(r).inverse();

  std::size_t next = 0;
  Planner planner(m, [&](Segment& out) {
    if (next >= job.segments.size()) return SourceStatus::End;
    out = job.segments[next++];
    return SourceStatus::Item;
  });
  const Pose start = job.segments.front().start;
  StepQuantizer quant(m, start);
  std::array<std::int64_t, kAxisCount> at{};
  for (int i = 0; i < kAxisCount; ++i) at[i] = quant.commanded(i);
  MotionCheck motion(m, at);
  std::uint64_t k = 0;
  auto take = [&](const PeriodIncrement& inc) {
    ++k;
    for (int i = 0; i < kAxisCount; ++i) at[i] += inc.steps[i];
    motion.add(static_cast<std::int64_t>(k) * m.period_ns, at, inc.line);
  };

  // A sample is where its period ends, its power the period's: a lasing
  // sample's period runs from the sample before it.
  std::map<std::uint32_t, HoleMotion> out;
  const double period_s = m.period_s();
  Vec3 prev_tip = kin.forward(start).tip_mm;
  PeriodSample sample, last;
  SourceStatus st;
  while ((st = planner.next(sample)) == SourceStatus::Item) {
    take(quant.quantize(sample));
    last = sample;
    const Vec3 tip = kin.forward(sample.pose).tip_mm;
    const Vec3 from = prev_tip;
    prev_tip = tip;
    if (!(sample.power_pct > 0.0f)) continue;
    const auto frame = to_local.find(sample.line);
    EXPECT_NE(frame, to_local.end()) << "lasing outside a hole, line " << sample.line;
    if (frame == to_local.end()) continue;
    const Vec3 a = frame->second * from, b = frame->second * tip;
    double d = std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x());  // a period turns far less than π
    if (d > std::numbers::pi) d -= 2.0 * std::numbers::pi;
    if (d < -std::numbers::pi) d += 2.0 * std::numbers::pi;
    HoleMotion& h = out[sample.line];
    h.turns += d / (2.0 * std::numbers::pi);
    const double step = (tip - from).norm();
    h.path_mm += step;
    h.lasing_s += period_s;
    h.max_speed_mm_s = std::max(h.max_speed_mm_s, step / period_s);
  }
  EXPECT_EQ(st, SourceStatus::End);
  while (quant.owed()) take(quant.pay_owed(last));
  motion.finish();
  EXPECT_TRUE(motion.ok()) << (motion.ok() ? std::string() : motion.breaches().front());
  return out;
}

double programmed_turns(const HoleProcessParams& r) {
  switch (r.process) {
    case HoleProcessId::Helix: return r.layer_count;
    case HoleProcessId::Circle: return static_cast<double>(r.layer_count) * r.head.radius_turns;
    case HoleProcessId::FreeShape: return r.layer_count;  // the polygon goes once round per layer
  }
  return 0.0;
}

void expect_rings_and_feed(const std::vector<HoleProcessParams>& rows, const DrillJob& job,
                           const MachineConfig& m) {
  const std::map<std::uint32_t, HoleMotion> got = plan_and_measure(job, rows, m);
  for (const HoleProcessParams& r : rows) {
    const std::string name = "hole " + std::to_string(r.hole_number) + " (" + process_name(r.process) +
                             ", A " + std::to_string(r.position[index(Axis::A)]) + "°, C " +
                             std::to_string(r.position[index(Axis::C)]) + "°)";
    const auto it = got.find(r.hole_number);
    ASSERT_NE(it, got.end()) << name << " never lased";
    const HoleMotion& h = it->second;
    const double feed = r.feed_mm_min / 60.0;
    EXPECT_NEAR(h.turns, programmed_turns(r), kTurnTolerance) << name;
    EXPECT_LE(h.max_speed_mm_s, feed * (1.0 + 1e-9)) << name;
    EXPECT_GE(h.path_mm / h.lasing_s, kMinFeedShare * feed)
        << name << ": mean tip speed over " << h.lasing_s << " s of lasing";
  }
}

HoleProcessParams tilted(std::uint32_t n, double x, double a, double c, HoleProcessId id) {
  HoleProcessParams p;
  p.hole_number = n;
  p.position << x, 200.0, 20.0, a, 0.0, c;
  p.power_pct = 70.0;
  p.process = id;
  if (id == HoleProcessId::Helix) {
    p.feed_mm_min = 600.0;
    p.layer_feed_mm = 0.1;
    p.layer_count = 10;
    p.total_depth_mm = 1.0;
    p.head.start_radius_mm = p.head.end_radius_mm = 0.5;
  } else {
    p.feed_mm_min = 400.0;
    p.layer_feed_mm = 0.05;
    p.layer_count = 8;
    p.total_depth_mm = 0.4;
    p.head.start_radius_mm = 0.2;
    p.head.end_radius_mm = 0.8;
    p.head.radius_turns = 4;
  }
  return p;
}

TEST(DrillJobMotion, TiltedCircleScansAndHelicesRunEveryRingAtTheFeed) {
  const MachineConfig m = shipped();
  const std::vector<HoleProcessParams> rows = {
      tilted(1, 100, 30, 45, HoleProcessId::Circle), tilted(2, 130, -20, 300, HoleProcessId::Circle),
      tilted(3, 160, 30, 45, HoleProcessId::Helix),  tilted(4, 190, -20, 300, HoleProcessId::Helix),
      tilted(5, 220, 0, 0, HoleProcessId::Circle),   tilted(6, 250, 0, 0, HoleProcessId::Helix),
  };
  Result<DrillJob> job = build_drill_job(rows, kinematics_from(m), Pose::Zero());
  ASSERT_TRUE(static_cast<bool>(job)) << job.error().to_string();
  expect_rings_and_feed(rows, *job, m);
}

TEST(DrillJobMotion, SampleTableRunsEveryRingAtTheFeed) {
  const MachineConfig m = shipped();
  const std::string path = std::string(LCNC_SOURCE_DIR) + "/share/examples/holes.csv";
  Result<PreparedDrill> p = prepare_drill_job(path, m, Pose::Zero());
  ASSERT_TRUE(static_cast<bool>(p)) << p.error().to_string();
  expect_rings_and_feed(p->rows, p->job, m);
}

}  // namespace
}  // namespace lcnc
