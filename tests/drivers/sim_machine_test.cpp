#include "drivers/sim_machine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <numeric>
#include <string>
#include <thread>

#include "support/rt_watch.h"

namespace lcnc::drivers {
namespace {

const std::string kShare = std::string(LCNC_SOURCE_DIR) + "/share";
using Steps = std::array<std::int64_t, kAxisCount>;

// Moves `axis` by `steps` (either sign) in frames of at most 255 pulses, one
// pulse per tick, as the DDA would send them.
void move(SimMachine& sim, int axis, std::int64_t steps) {
  static constexpr std::uint32_t kMax = 255;
  static const auto kTicks = [] {
    std::array<std::uint32_t, kMax> t{};
    std::iota(t.begin(), t.end(), 0u);
    return t;
  }();
  while (steps != 0) {
    const auto n = static_cast<std::uint32_t>(std::min<std::int64_t>(std::abs(steps), kMax));
    PulseFrame f;
    f.ticks_per_period = kMax;
    f.axes[axis] = AxisPulses{n, steps < 0, kTicks.data()};
    sim.send(f);
    steps += steps < 0 ? std::int64_t{n} : -std::int64_t{n};
  }
}

void move_to(SimMachine& sim, int axis, std::int64_t pos_steps) {
  move(sim, axis, pos_steps - sim.position_steps(axis));
}

bool any_active(const MachineInputs& in) {
  for (int i = 0; i < kAxisCount; ++i)
    if (in.home[i] || in.limit_min[i] || in.limit_max[i]) return true;
  return in.estop;
}

TEST(SimMachine, CountsPulsesFromItsStart) {
  SimMachine sim(Steps{100, -5, 0, 0, 0, 0});
  move(sim, 0, 600);
  move(sim, 1, -300);
  EXPECT_EQ(sim.position_steps(0), 700);
  EXPECT_EQ(sim.position_steps(1), -305);
  EXPECT_EQ(sim.pulses(0), 600u);
  EXPECT_EQ(sim.pulses(1), 300u);
  EXPECT_EQ(sim.actual_position_steps(0), 700);  // a perfect screw
  EXPECT_EQ(sim.bad_frames(), 0u);
}

// A drive loses a pulse that shares a tick with the one before, or falls
// outside the period: such a frame is counted bad wherever the fault sits —
// in the first ticks, in the middle, in the last few — and a clean frame of
// any length is not.
TEST(SimMachine, CountsAFrameWithTwoPulsesOnATickOrOneOutsideThePeriodAsBad) {
  constexpr std::uint32_t kN = 300;
  for (std::uint32_t n : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 9u, 64u, 255u}) {
    std::array<std::uint32_t, 255> t{};
    for (std::uint32_t j = 0; j < n; ++j) t[j] = j * (kN / n);  // rising, inside
    PulseFrame f;
    f.ticks_per_period = kN;
    f.axes[2] = AxisPulses{n, false, t.data()};
    SimMachine sim(Steps{});
    sim.send(f);
    EXPECT_EQ(sim.bad_frames(), 0u) << "n " << n;
    std::uint64_t expected_bad = 0;
    for (std::uint32_t j = 1; j < n; ++j) {  // pulse j on the tick of pulse j − 1
      const std::uint32_t keep = t[j];
      t[j] = t[j - 1];
      sim.send(f);
      EXPECT_EQ(sim.bad_frames(), ++expected_bad) << "n " << n << " repeated tick at " << j;
      t[j] = keep;
    }
    const std::uint32_t last = t[n - 1];
    t[n - 1] = kN;  // one tick past the period
    sim.send(f);
    EXPECT_EQ(sim.bad_frames(), ++expected_bad) << "n " << n << " last tick outside";
    t[n - 1] = last;
    sim.send(f);
    EXPECT_EQ(sim.bad_frames(), expected_bad) << "n " << n;
    EXPECT_EQ(sim.pulses(2), std::uint64_t{n} * (expected_bad + 2));  // every frame still moves
  }
}

TEST(SimMachine, OldConstructorHasNoSwitches) {
  SimMachine sim(Steps{});
  EXPECT_FALSE(any_active(sim.read_inputs()));
  for (int i = 0; i < kAxisCount; ++i) move(sim, i, -2'000'000);
  EXPECT_FALSE(any_active(sim.read_inputs()));
  for (int i = 0; i < kAxisCount; ++i) move(sim, i, 4'000'000);
  EXPECT_FALSE(any_active(sim.read_inputs()));
}

// X: cam active at count ≤ 100; Y: cam active at count ≥ −50.
TEST(SimMachine, HomeSwitchIsACamFromItsTripPointOnItsSide) {
  std::array<SimSwitches, kAxisCount> sw{};
  sw[0].home = HomeSwitch{100, SwitchSide::Below};
  sw[1].home = HomeSwitch{-50, SwitchSide::Above};
  SimMachine sim(Steps{1000, -1000, 0, 0, 0, 0}, sw);
  EXPECT_FALSE(sim.read_inputs().home[0]);
  EXPECT_FALSE(sim.read_inputs().home[1]);
  struct Probe {
    int axis;
    std::int64_t pos;
    bool active;
  };
  const Probe probes[] = {{0, 101, false},      {0, 100, true},  {0, 99, true},  {0, -1'000'000, true},
                          {0, 101, false},      {1, -51, false}, {1, -50, true}, {1, -49, true},
                          {1, 1'000'000, true}, {1, -51, false}};
  for (const Probe& p : probes) {
    move_to(sim, p.axis, p.pos);
    const MachineInputs in = sim.read_inputs();
    EXPECT_EQ(in.home[p.axis], p.active) << "axis " << p.axis << " at " << p.pos;
    EXPECT_FALSE(in.limit_min[p.axis] || in.limit_max[p.axis]);
    EXPECT_FALSE(in.home[2]);  // no switch fitted
  }
}

TEST(SimMachine, HardLimitsAreActiveAtOrBeyond) {
  std::array<SimSwitches, kAxisCount> sw{};
  sw[2].limit_min_steps = -2000;
  sw[2].limit_max_steps = 502'000;
  SimMachine sim(Steps{}, sw);
  struct Probe {
    std::int64_t pos;
    bool min, max;
  };
  const Probe probes[] = {{0, false, false},      {-1999, false, false},   {-2000, true, false},
                          {-2001, true, false},   {501'999, false, false}, {502'000, false, true},
                          {600'000, false, true}, {250'000, false, false}};
  for (const Probe& p : probes) {
    move_to(sim, 2, p.pos);
    const MachineInputs in = sim.read_inputs();
    EXPECT_EQ(in.limit_min[2], p.min) << p.pos;
    EXPECT_EQ(in.limit_max[2], p.max) << p.pos;
    EXPECT_FALSE(in.home[2]) << p.pos;
  }
}

TEST(SimMachine, EstopInputIsSetFromAnotherThread) {
  SimMachine sim(Steps{});
  EXPECT_FALSE(sim.read_inputs().estop);
  std::thread([&] { sim.set_estop_input(true); }).join();
  EXPECT_TRUE(sim.read_inputs().estop);
  std::thread([&] { sim.set_estop_input(false); }).join();
  EXPECT_FALSE(sim.read_inputs().estop);
}

// The pitch-error model: actual = counted + error(counted), error in steps.
TEST(SimMachine, PitchErrorGivesTheActualPosition) {
  std::array<PitchTable, kAxisCount> screw{};
  screw[0] = PitchTable{0.0, 1000.0, {0.0, 20.0, -10.0}};  // steps
  SimMachine sim(Steps{}, {}, screw);
  EXPECT_EQ(sim.actual_position_steps(0), 0);
  move_to(sim, 0, 500);
  EXPECT_EQ(sim.actual_position_steps(0), 510);
  move_to(sim, 0, 1500);
  EXPECT_EQ(sim.actual_position_steps(0), 1505);
  move_to(sim, 0, 9000);
  EXPECT_EQ(sim.actual_position_steps(0), 8990);  // last value held
  EXPECT_EQ(sim.position_steps(0), 9000);         // the count is the pulses
  EXPECT_EQ(sim.actual_position_steps(1), 0);     // no table on Y
}

// send() and read_inputs() run on the RT thread every period.
TEST(SimMachine, RtCallsAllocateNothing) {
  auto machine = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(machine) << machine.error().to_string();
  std::array<PitchTable, kAxisCount> screw{};
  screw[0] = PitchTable{0.0, 1000.0, {0.0, 20.0, -10.0}};
  SimMachine sim(Steps{}, wired_switches(*machine), screw);
  std::array<std::uint32_t, 3> ticks{0, 5, 9};
  PulseFrame f;
  f.ticks_per_period = 10;
  for (auto& ax : f.axes) ax = AxisPulses{3, false, ticks.data()};
  const std::uint64_t before = g_allocations.load();
  t_count_allocations = true;
  std::int64_t sum = 0;
  for (int n = 0; n < 10'000; ++n) {
    f.axes[0].negative = (n / 1000) % 2 == 1;
    sim.send(f);
    const MachineInputs in = sim.read_inputs();
    sum += in.home[0] + sim.actual_position_steps(0);
  }
  t_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), before);
  EXPECT_NE(sum, 0);
}

// Default machine: hard limits 2 mm (2°) beyond min/max, home switches where
// home_position and the sign of home_search_velocity say.
TEST(WiredSwitches, FollowTheMachineConfig) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  const auto sw = wired_switches(*m);
  const SimSwitches& x = sw[index(Axis::X)];
  EXPECT_EQ(x.limit_min_steps, -2000);
  EXPECT_EQ(x.limit_max_steps, 1'002'000);
  ASSERT_TRUE(x.home);
  EXPECT_EQ(x.home->trip_steps, 0);
  EXPECT_EQ(x.home->active, SwitchSide::Below);  // searched toward −X
  const SimSwitches& z = sw[index(Axis::Z)];
  ASSERT_TRUE(z.home);
  EXPECT_EQ(z.home->trip_steps, 500'000);
  EXPECT_EQ(z.home->active, SwitchSide::Above);  // the head homes up
  EXPECT_EQ(z.limit_max_steps, 502'000);
  const SimSwitches& a = sw[index(Axis::A)];
  EXPECT_EQ(a.limit_min_steps, -97'000);
  EXPECT_EQ(a.limit_max_steps, 97'000);
  const SimSwitches& c = sw[index(Axis::C)];
  EXPECT_FALSE(c.limit_min_steps) << "a wrapping axis has no hard limits";
  EXPECT_FALSE(c.limit_max_steps);
  EXPECT_TRUE(c.home);
  const SimSwitches& b = sw[index(Axis::B)];  // not fitted
  EXPECT_FALSE(b.home || b.limit_min_steps || b.limit_max_steps);
}

TEST(WiredSwitches, DefaultHomeIsAtMinSearchedDownward) {
  auto m = parse_machine_config(
      "[axes.Y]\nmin = -10\nmax = 10\nmax_velocity = 10\nmax_acceleration = 100\n"
      "steps_per_unit = 400\n",
      "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  const SimSwitches y = wired_switches(*m)[index(Axis::Y)];
  ASSERT_TRUE(y.home);
  EXPECT_EQ(y.home->trip_steps, -4000);
  EXPECT_EQ(y.home->active, SwitchSide::Below);
  EXPECT_EQ(y.limit_min_steps, -4800);
  EXPECT_EQ(y.limit_max_steps, 4800);
}

TEST(WiredSwitches, RawOffsetShiftsEverySwitch) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m);
  const Steps offset{123'457, -9, 1, -77'000, 5, 42};
  const auto plain = wired_switches(*m);
  const auto shifted = wired_switches(*m, offset);
  for (int i = 0; i < kAxisCount; ++i) {
    if (!m->axes[i].present) continue;
    ASSERT_TRUE(shifted[i].home);
    EXPECT_EQ(shifted[i].home->trip_steps, plain[i].home->trip_steps + offset[i]) << i;
    if (plain[i].limit_min_steps) {
      EXPECT_EQ(*shifted[i].limit_min_steps, *plain[i].limit_min_steps + offset[i]) << i;
      EXPECT_EQ(*shifted[i].limit_max_steps, *plain[i].limit_max_steps + offset[i]) << i;
    }
  }
}

// The power-on story: the kernel believes X is at 0 and so does the sim's
// count, but the switches sit 250.3 mm lower (raw offset). Searching fast
// toward the switch, backing off, and latching slowly finds the trip point
// to the step; from there the kernel knows the machine position.
TEST(WiredSwitches, HomingFindsTheSwitchDespiteTheUnknownOffset) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m);
  const int x = index(Axis::X);
  Steps offset{};
  offset[x] = -250'300;
  SimMachine sim(Steps{}, wired_switches(*m, offset));
  ASSERT_FALSE(sim.read_inputs().home[x]);
  int periods = 0;
  while (!sim.read_inputs().home[x] && ++periods < 100'000) move(sim, x, -200);  // search
  while (sim.read_inputs().home[x] && ++periods < 100'000) move(sim, x, 10);     // back off
  while (!sim.read_inputs().home[x] && ++periods < 100'000) move(sim, x, -1);    // latch
  ASSERT_LT(periods, 100'000);
  // Machine position at the trip point is home_position; the sim's count there
  // is home_position·steps_per_unit + offset.
  EXPECT_EQ(sim.position_steps(x), offset[x]);
  EXPECT_FALSE(sim.read_inputs().limit_min[x]);  // the hard limit is 2 mm further
}

}  // namespace
}  // namespace lcnc::drivers
