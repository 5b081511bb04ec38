// A TCP move runs as one smooth joint path: planned on the shipped machine
// (head-head and table-table), the motion never comes to rest inside a
// move or a rounded corner, keeps every joint within its limits (the run's
// own check on the steps) and the tip within tolerance of the program.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "core/plan/test_machine.h"
#include "kinematics/five_axis.h"
#include "path/deviation_meter.h"
#include "plan/motion_check.h"
#include "plan/planner.h"
#include "plan/program_source.h"

namespace lcnc {
namespace {

struct TcpOutcome {
  double cycle_s = 0.0;
  // Periods at rest (speed 0) between the first and the last that move, on
  // moves (not dwells).
  int rests_inside = 0;
  bool limits_ok = false;
  std::string breach;
  double tip_excess_mm = 0.0;
};

TcpOutcome run_tcp(const std::string& text, bool table) {
  MachineConfig m = testing::shipped_machine(true);
  if (table) m.kinematics.variant = MachineVariant::TableTable;
  const std::string path = ::testing::TempDir() + "tcp_motion.ngc";
  std::ofstream(path) << text;
  Result<std::unique_ptr<ProgramSource>> src = ProgramSource::open(path, m, ReaderOptions{});
  EXPECT_TRUE(static_cast<bool>(src)) << src.error().to_string();
  if (!src) return {};
  Result<std::unique_ptr<ProgramReader>> tips = open_tip_program(path, m);
  EXPECT_TRUE(static_cast<bool>(tips));
  if (!tips) return {};
  DeviationMeter tip(reader_source(**tips), m.path_tolerance_mm, 0.002, m.tcp.tip_tolerance_mm);
  const FiveAxisKinematics kin = kinematics_from(m);
  Planner planner(m, (*src)->source());
  StepQuantizer q(m, ReaderOptions{}.start);
  std::array<std::int64_t, kAxisCount> steps{};
  for (int i = 0; i < kAxisCount; ++i) steps[i] = q.commanded(i);
  MotionCheck check(m, steps);
  TcpOutcome out;
  PeriodSample s;
  int first_move = -1, last_move = -1, k = 0;
  std::vector<bool> rest;
  while (planner.next(s) == SourceStatus::Item) {
    for (int i = 0; i < kAxisCount; ++i) steps[i] = m.axes[i].present ? q.to_steps(i, s.pose[i]) : 0;
    check.add(static_cast<std::int64_t>(std::llround(s.t_s * 1e9)), steps, s.line);
    tip.add_at_line(kin.forward(s.pose).tip_mm, s.line);
    const bool moving = s.kind != MotionKind::Dwell && s.speed > 0.0;
    if (moving) {
      if (first_move < 0) first_move = k;
      last_move = k;
    }
    rest.push_back(s.kind != MotionKind::Dwell && !moving);
    out.cycle_s = s.t_s;
    ++k;
  }
  check.finish();
  for (int i = first_move + 1; i < last_move; ++i) out.rests_inside += rest[i] ? 1 : 0;
  out.limits_ok = check.ok();
  if (!out.limits_ok) out.breach = check.breaches().front();
  out.tip_excess_mm = tip.excess_mm();
  std::remove(path.c_str());
  return out;
}

std::string coord(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}

// An R30 circle of 120 chords, the tool at A20 and C on the tangent: a
// corner of 3° in tip and joints at every chord, each rounded.
std::string tilted_circle(double cx, double cy) {
  std::string p = "G21 G90 G64 P0.01\nG0 X" + coord(cx) + " Y" + coord(cy - 30) + " Z20 A20 C0\nM3 S80\n";
  for (int k = 1; k <= 120; ++k) {
    const double phi = (3.0 * k - 90.0) * std::numbers::pi / 180.0;
    p += "G1 X" + coord(cx + 30 * std::cos(phi)) + " Y" + coord(cy + 30 * std::sin(phi)) + " C" +
         std::to_string(3 * k) + (k == 1 ? " F3000" : "") + "\n";
  }
  return p + "M5\nM2\n";
}

TEST(TcpMotion, ATiltedCircleOfChordsRunsWithoutAStopWithinTheLimits) {
  for (bool table : {false, true}) {
    const TcpOutcome o = run_tcp(tilted_circle(table ? 0.0 : 150.0, table ? 0.0 : 150.0), table);
    EXPECT_TRUE(o.limits_ok) << o.breach;
    EXPECT_EQ(o.tip_excess_mm, 0.0);
    // the initial rapid ends at rest, and so does its switch to the feed
    // move: one stop between them, none along the circle
    EXPECT_LE(o.rests_inside, 2) << (table ? "table-table" : "head-head");
    // 188.5 mm at F3000 (50 mm/s) is 3.8 s: no stop-and-go on the way
    EXPECT_LT(o.cycle_s, 8.0);
  }
}

// A rapid that turns A by 60° and C while the tip moves 10 mm: one smooth
// path, at rest only at its ends.
TEST(TcpMotion, ARapidThatTurnsTheToolDoesNotStopInside) {
  for (bool table : {false, true}) {
    const double cx = table ? 0.0 : 150.0, cy = table ? 0.0 : 150.0;
    const std::string prog = "G21 G90\nG0 X" + coord(cx) + " Y" + coord(cy) + " Z20 A30 C0\nG4 P0.05\nG0 X" +
                             coord(cx + 10) + " Y" + coord(cy) + " Z20 A-30 C18\nM2\n";
    const TcpOutcome o = run_tcp(prog, table);
    EXPECT_TRUE(o.limits_ok) << o.breach;
    EXPECT_EQ(o.tip_excess_mm, 0.0);
    EXPECT_EQ(o.rests_inside, 0) << (table ? "table-table" : "head-head");
  }
}

// A move that only turns C while the tip stands: F is degrees per minute
// of the rotary move (RS274NGC), 90° at F1800 (30°/s) in 3 s and a ramp.
TEST(TcpMotion, ARotaryOnlyMoveRunsAtFDegreesPerMinute) {
  const std::string prog = "G21 G90\nG0 X150 Y150 Z20 A30 C0\nG4 P0\nG1 C90 F1800\nM2\n";
  const TcpOutcome all = run_tcp(prog, false);
  const TcpOutcome rapid = run_tcp("G21 G90\nG0 X150 Y150 Z20 A30 C0\nG4 P0\nM2\n", false);
  EXPECT_TRUE(all.limits_ok) << all.breach;
  const double turn_s = all.cycle_s - rapid.cycle_s;
  EXPECT_GT(turn_s, 3.0);
  EXPECT_LT(turn_s, 3.3);
}

}  // namespace
}  // namespace lcnc
