#include "rt/axis_mover.h"

#include <cstdint>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "support/rt_rig.h"

namespace lcnc::rt {
namespace {

// X (Y, Z) of 0–100 mm at 1 µm a step; homing toward a switch at the minimum.
using test::rt_machine;

constexpr double kT = 75e-6;

// Runs the mover against a switch that is on at and below `switch_at`
// (steps; INT64_MIN: no switch at all) from
// `pos`; returns the events in order and the position at the end.
struct MoverRun {
  std::int64_t pos = 0;
  std::vector<AxisMover::Event> events;
  AxisMover::Step last{};
};
MoverRun drive(AxisMover& mover, std::int64_t pos, std::int64_t switch_at, int periods) {
  MoverRun r;
  r.pos = pos;
  for (int i = 0; i < periods && mover.axis() >= 0; ++i) {
    MachineInputs in{};
    in.home[0] = r.pos <= switch_at;
    const AxisMover::Step s = mover.next(in, r.pos);
    r.pos += s.steps;
    mover.travelled(s.steps);
    if (s.event != AxisMover::Event::None) {
      r.events.push_back(s.event);
      r.last = s;
    }
  }
  return r;
}

TEST(AxisMover, HomingFindsTheSwitchBacksOffAndRebases) {
  AxisMover mover(rt_machine(), 50.0);
  ASSERT_TRUE(mover.can_home(0));
  mover.start_home(0, false, kT);
  // the switch at -2.5 mm of where the machine believes it is
  const MoverRun r = drive(mover, 40'000, -2'500, 2'000'000);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0], AxisMover::Event::Homed);
  EXPECT_EQ(mover.axis(), -1);
  // it latched where the switch released: one step above it; the new
  // coordinate counts from there (home 0) to where it braked
  EXPECT_GT(r.pos, -2'500);
  EXPECT_EQ(r.last.rebased, r.pos - (-2'500 + 1));
}

TEST(AxisMover, HomingWithoutASwitchGivesUpAfterTwiceTheTravelAndBrakes) {
  AxisMover mover(rt_machine(), 50.0);
  mover.start_home(0, false, kT);
  const MoverRun r = drive(mover, 0, INT64_MIN, 20'000'000);
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.events[0], AxisMover::Event::SearchFailed);
  EXPECT_EQ(r.events[1], AxisMover::Event::Done);
  // twice the 100 mm travel searched, then the brake: less than 0.1 mm more
  // at 50 mm/s and 50 m/s² or so
  EXPECT_GT(std::llabs(r.pos), 200'000);
  EXPECT_LT(std::llabs(r.pos), 200'000 + 100);
  EXPECT_EQ(mover.axis(), -1);
}

TEST(AxisMover, AJogOfAHomedAxisStopsAtTheSoftLimitAndSaysHowShort) {
  AxisMover mover(rt_machine(), 50.0);
  EXPECT_EQ(mover.start_jog(0, 90'000, 150'000, true, kT), 50'000);
  const MoverRun r = drive(mover, 90'000, INT64_MIN, 1'000'000);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0], AxisMover::Event::Done);
  EXPECT_EQ(r.pos, 100'000);
  // unhomed: no soft limit is known
  EXPECT_EQ(mover.start_jog(0, 90'000, 150'000, false, kT), 0);
  EXPECT_EQ(drive(mover, 90'000, INT64_MIN, 1'000'000).pos, 150'000);
}

TEST(AxisMover, AnEStopCancelsAtOnce) {
  AxisMover mover(rt_machine(), 50.0);
  mover.start_home(0, false, kT);
  (void)drive(mover, 50'000, INT64_MIN, 100);
  mover.cancel();
  EXPECT_EQ(mover.axis(), -1);
  MachineInputs in{};
  EXPECT_EQ(mover.next(in, 0).steps, 0);
}

}  // namespace
}  // namespace lcnc::rt
