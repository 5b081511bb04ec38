// `lasercnc run --fast`, the simulated clock, against the wall clock: the
// same planner and kernel code, the same periods, so the same cycle time,
// path deviation and steps — on the sample job, the 5-axis example under
// tool-centre-point control and a program of 100,000 segments.
//
// The wall-clock run is the real-time path itself (label `realtime`): on a
// loaded computer its planner may fall behind, and the kernel then slows
// the path to refill its buffer (starvations) or holds (underruns). Such a
// run is longer than the plan, never different in its steps: the test then
// holds the simulated run to "no longer than the wall-clock run" and to
// the same steps, and still compares everything the load cannot touch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "e2e_support.h"

namespace {

using namespace e2e;

nlohmann::json run(const std::string& args) {
  const CmdResult r = lasercnc("run " + args + " --json --no-progress");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err << r.out;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  EXPECT_TRUE(j.is_object()) << r.out;
  return j;
}

void expect_same_run(const std::string& args) {
  const nlohmann::json wall = run(args + " --no-realtime");
  const nlohmann::json fast = run(args + " --fast");
  ASSERT_TRUE(wall.is_object() && fast.is_object());
  EXPECT_EQ(wall["clock"], "wall");
  EXPECT_EQ(fast["clock"], "simulated");
  EXPECT_TRUE(fast["succeeded"].get<bool>()) << fast.dump();
  EXPECT_EQ(fast["starvations"], 0);
  EXPECT_EQ(fast["underruns"], 0);
  EXPECT_EQ(fast["trace_drops"], 0);
  // the steps: every axis, sent and commanded, whatever the load
  for (const auto& [name, ax] : fast["axes"].items()) {
    EXPECT_EQ(ax["steps_sent"], wall["axes"][name]["steps_sent"]) << name;
    EXPECT_EQ(ax["steps_commanded"], wall["axes"][name]["steps_commanded"]) << name;
    EXPECT_EQ(ax["peak_velocity"], wall["axes"][name]["peak_velocity"]) << name;
    EXPECT_EQ(ax["peak_acceleration"], wall["axes"][name]["peak_acceleration"]) << name;
  }
  EXPECT_EQ(fast["segments"], wall["segments"]);
  const bool wall_slowed = wall["starvations"].get<long long>() > 0 || wall["underruns"].get<long long>() > 0;
  if (wall_slowed) {
    // the wall-clock planner fell behind on this computer: its run is the
    // plan slowed down
    std::printf(
        "wall-clock run slowed by the load (%lld starvations, %lld underruns): "
        "compared as no longer than it\n",
        wall["starvations"].get<long long>(), wall["underruns"].get<long long>());
    EXPECT_LE(fast["cycle_time_s"].get<double>(), wall["cycle_time_s"].get<double>() + 1e-9);
    EXPECT_LE(fast["periods"].get<long long>(), wall["periods"].get<long long>());
    return;
  }
  // the same periods of the same lengths: the same machine time to the ns
  EXPECT_EQ(fast["periods"], wall["periods"]);
  EXPECT_EQ(fast["cycle_time_s"], wall["cycle_time_s"]);
  EXPECT_EQ(fast["laser_on_s"], wall["laser_on_s"]);
  EXPECT_EQ(fast["max_deviation_mm"], wall["max_deviation_mm"]);
  for (const auto& [name, ax] : fast["axes"].items()) {
    EXPECT_EQ(ax["measured_velocity"], wall["axes"][name]["measured_velocity"]) << name;
    EXPECT_EQ(ax["measured_acceleration"], wall["axes"][name]["measured_acceleration"]) << name;
  }
}

TEST(SimulatedClock, TheSampleJobRunsAsOnTheWallClock) { expect_same_run(kShare + "/examples/bracket.ngc"); }

TEST(SimulatedClock, TheFiveAxisExampleRunsAsOnTheWallClock) {
  const fs::path machine = temp_dir() / "tcp.toml";
  std::string text = slurp(kShare + "/machines/default.toml");
  const std::size_t at = text.find("tcp = false");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "tcp = true");
  std::ofstream(machine) << text;
  expect_same_run(kShare + "/examples/tcp_bevel.ngc --machine " + machine.string());
}

// 100,000 chords of a wave along X (CAM's dense code), blended in G64.
TEST(SimulatedClock, AHundredThousandSegmentsRunAsOnTheWallClock) {
  const fs::path prog = temp_dir() / "wave_100k.ngc";
  {
    std::ofstream out(prog);
    out << "G21 G90 G64 P0.01\nG0 X10 Y200 Z5\nM3 S60\nF30000\n";
    constexpr int kChords = 100'000;
    char line[64];
    for (int i = 1; i <= kChords; ++i) {
      const double x = 10.0 + 980.0 * i / kChords;
      const double y = 200.0 + 20.0 * std::sin(2.0 * std::numbers::pi * (x - 10.0) / 100.0);
      std::snprintf(line, sizeof line, "G1 X%.4f Y%.4f\n", x, y);
      out << line;
    }
    out << "M5\nM2\n";
  }
  expect_same_run(prog.string());
}

}  // namespace
