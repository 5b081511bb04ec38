// End to end: the lasercnc CLI runs real programs on the simulated machine
// (real planner and RT threads) and reports honestly.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "e2e_support.h"

namespace {

using namespace e2e;

// Checks the default machine's X Y Z velocity limits on a trace: velocity
// over 10-row windows against the trace's own time column, allowing the ±1
// step quantization at each end. Returns the largest X velocity seen.
double expect_within_velocity_limits(const std::vector<TraceRow>& rows) {
  const double vmax[3] = {500.0, 500.0, 250.0};
  const std::size_t w = 10;
  double peak_x = 0.0;
  for (std::size_t k = w; k < rows.size(); ++k) {
    const double dt = rows[k].t - rows[k - w].t;
    const double d[3] = {rows[k].x - rows[k - w].x, rows[k].y - rows[k - w].y, rows[k].z - rows[k - w].z};
    for (int a = 0; a < 3; ++a) {
      const double v = std::abs(d[a]) / dt;
      if (a == 0) peak_x = std::max(peak_x, v);
      if (v > vmax[a] + 0.002 / dt) {
        ADD_FAILURE() << "axis " << a << " at " << v << " mm/s, row " << k;
        return peak_x;
      }
    }
  }
  return peak_x;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
}

// A Linux file name is bytes, not always UTF-8: the JSON report of a
// program named so still prints (the bad byte as U+FFFD) — it used to end
// the process in an uncaught exception from the JSON library.
TEST(LasercncRun, AProgramWhoseNameIsNotUtf8StillGetsItsJsonReport) {
  const fs::path prog = write_file("part_\xff.ngc", "G21 G90 G64 P0.01\nG1 X2 Y1 F600\nM2\n");
  const CmdResult r = lasercnc("run '" + prog.string() + "' --json --no-progress --fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NE(j["program"].get<std::string>().find("part_\xEF\xBF\xBD.ngc"), std::string::npos) << j["program"];
  EXPECT_TRUE(j["steps_match"].get<bool>());
}

TEST(LasercncRun, SampleJobRunsWithExactStepsAndAnHonestReport) {
  const fs::path trace = temp_dir() / "trace.csv";
  const CmdResult r = lasercnc("run " + kShare +
                               "/examples/bracket.ngc --json --no-progress --fast --trace " + trace.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["steps_match"].get<bool>());
  for (const auto& [name, ax] : j["axes"].items()) {
    EXPECT_EQ(ax["steps_sent"].get<long long>(), ax["steps_commanded"].get<long long>()) << name;
  }
  // the program ends at X0 Y0 Z25 (machine: G55 X500 Y0)
  EXPECT_EQ(j["axes"]["X"]["steps_sent"].get<long long>(), 500000);
  EXPECT_EQ(j["axes"]["Z"]["steps_sent"].get<long long>(), 25000);
  EXPECT_EQ(j["underruns"].get<long long>(), 0);
  EXPECT_EQ(j["bad_frames"].get<long long>(), 0);
  // on the simulated clock nothing is lost or late, on any computer, under
  // any load or sanitizer: the kernel waits for the planner and the trace's
  // reader instead
  EXPECT_EQ(j["clock"], "simulated");
  EXPECT_EQ(j["trace_drops"].get<long long>(), 0);
  EXPECT_EQ(j["starvations"].get<long long>(), 0);
  // G64 P0.01: the executed path stays within P of the programmed one
  EXPECT_LE(j["max_deviation_mm"].get<double>(), 0.01);
  const double period = j["period_s"].get<double>();
  EXPECT_NEAR(period, 75e-6, 1e-12);
  // at 100 % every period lasts T
  EXPECT_EQ(j["feed_override"].get<double>(), 1.0);
  EXPECT_NEAR(j["cycle_time_s"].get<double>(), j["periods"].get<double>() * period, 1e-9);
  // cutting 480+ mm at ≤ 100 mm/s takes longer than 4.8 s
  EXPECT_GT(j["feed_length_mm"].get<double>(), 480.0);
  EXPECT_GT(j["cycle_time_s"].get<double>(), j["feed_length_mm"].get<double>() / 100.0);
  EXPECT_GT(j["laser_on_s"].get<double>(), 4.0);
  EXPECT_LE(j["axes"]["X"]["peak_velocity"].get<double>(), 500.0 + 1e-6);
  EXPECT_LE(j["axes"]["X"]["peak_acceleration"].get<double>(), 5000.0 * (1 + 1e-6));

  // The trace: one row per RT period, header as documented, and its motion
  // within the axis limits.
  const std::vector<TraceRow> rows = read_trace(trace);
  ASSERT_EQ(rows.size(), j["periods"].get<std::size_t>());
  // each row one period later
  for (std::size_t k = 0; k < rows.size(); ++k)
    ASSERT_NEAR(rows[k].t, static_cast<double>(k + 1) * period, 1e-9) << "row " << k;
  EXPECT_NEAR(rows.back().t, j["cycle_time_s"].get<double>(), 1e-9);
  expect_within_velocity_limits(rows);
  EXPECT_NEAR(rows.back().x, 500.0, 1e-9);
  EXPECT_NEAR(rows.back().z, 25.0, 1e-9);
  // the power column follows the laser: on while cutting, off at the end
  std::size_t lit = 0;
  for (const TraceRow& r : rows) lit += r.power > 0.0;
  EXPECT_NEAR(static_cast<double>(lit) * period, j["laser_on_s"].get<double>(), 1e-6);
  EXPECT_EQ(rows.back().power, 0.0);
}

// Feed override for the whole run. Below 100 % every period lasts T/K: the
// cycle time scales by 1/K while the steps stay exact. Above it the planner
// plans the feed moves at K·F within the limits: the cuts take 1/K of the
// time, the rapids (already at the axes' speed) as long as at 100 %, and
// the steps are the same.
TEST(LasercncRun, FeedOverrideScalesTheCycleTimeAndKeepsEveryStep) {
  const fs::path prog = write_file("override.ngc",
                                   "G21 G90 G61\nG0 X10 Y10 Z5\nG0 X400 Y200\n"
                                   "G1 X450 F6000 S80 M3\nG1 Y300\nM5\nM2\n");
  std::map<int, nlohmann::json> runs;
  std::map<int, std::vector<TraceRow>> traces;
  for (int pct : {100, 150, 50}) {
    const fs::path trace = temp_dir() / ("trace" + std::to_string(pct) + ".csv");
    const CmdResult r = lasercnc("run " + prog.string() + " --json --no-progress --fast --feed-override " +
                                 std::to_string(pct) + " --trace " + trace.string());
    ASSERT_EQ(r.exit_code, 0) << pct << "\n" << r.err;
    runs[pct] = nlohmann::json::parse(r.out);
    traces[pct] = read_trace(trace);
  }
  const double T = runs[100]["period_s"].get<double>();
  const double c100 = runs[100]["cycle_time_s"].get<double>();
  EXPECT_GT(c100, 1.0);
  // on the simulated clock the planner is never late (the kernel waits for
  // it): the timing below is exact on any computer
  for (int pct : {100, 150, 50}) {
    const nlohmann::json& j = runs[pct];
    EXPECT_EQ(j["starvations"].get<long long>(), 0) << pct;
    EXPECT_EQ(j["feed_override"].get<double>(), pct / 100.0);
    EXPECT_TRUE(j["steps_match"].get<bool>()) << pct;
    EXPECT_EQ(j["underruns"].get<long long>(), 0) << pct;
    EXPECT_EQ(j["bad_frames"].get<long long>(), 0) << pct;
    for (const auto& [name, ax] : j["axes"].items()) {
      EXPECT_EQ(ax["steps_sent"].get<long long>(), ax["steps_commanded"].get<long long>()) << name;
      EXPECT_EQ(ax["steps_sent"].get<long long>(), runs[100]["axes"][name]["steps_sent"].get<long long>());
    }
    // every period lasted T/K, K = min(1, override); the last row ends the cycle
    const double nominal = j["periods"].get<double>() * T / std::min(1.0, pct / 100.0);
    EXPECT_NEAR(j["cycle_time_s"].get<double>(), nominal, 1e-9) << pct;
    const std::vector<TraceRow>& rows = traces[pct];
    ASSERT_EQ(rows.size(), j["periods"].get<std::size_t>());
    EXPECT_NEAR(rows.back().t, j["cycle_time_s"].get<double>(), 1e-9);
    EXPECT_NEAR(rows.front().t, T / std::min(1.0, pct / 100.0), 1e-9);
    // never past a limit, measured from the trace against its own time
    expect_within_velocity_limits(rows);
    EXPECT_LE(j["axes"]["X"]["peak_velocity"].get<double>(), 500.0 + 1e-6);
    EXPECT_LE(j["axes"]["X"]["peak_acceleration"].get<double>(), 5000.0 * (1 + 1e-6));
  }
  // 50 %: the same periods, each T/0.5 — the cycle doubles
  EXPECT_EQ(runs[50]["periods"].get<long long>(), runs[100]["periods"].get<long long>());
  EXPECT_NEAR(runs[50]["cycle_time_s"].get<double>(), 2 * c100, 3 * T);
  EXPECT_NEAR(runs[50]["laser_on_s"].get<double>(), 2 * runs[100]["laser_on_s"].get<double>(), 3 * T);
  EXPECT_NEAR(runs[50]["axes"]["X"]["peak_velocity"].get<double>(),
              runs[100]["axes"]["X"]["peak_velocity"].get<double>() * 0.5, 1e-6);
  // 150 %: the 150 mm of cut at 150 mm/s instead of 100 (plus 10 ms more of
  // speeding up and slowing down per cut), the rapids as fast as at 100 %
  const double on100 = runs[100]["laser_on_s"].get<double>();
  const double on150 = runs[150]["laser_on_s"].get<double>();
  EXPECT_LT(runs[150]["periods"].get<long long>(), runs[100]["periods"].get<long long>());
  EXPECT_NEAR(on100, 1.5 + 2 * 0.02, 0.01);
  EXPECT_NEAR(on150, 1.0 + 2 * 0.03, 0.01);
  EXPECT_NEAR(runs[150]["cycle_time_s"].get<double>(), c100 - (on100 - on150), 3 * T);
  // at 100 % the rapids reach the X limit already: the plan is at the limits
  EXPECT_GT(expect_within_velocity_limits(traces[100]), 0.95 * 500.0);
  EXPECT_NEAR(runs[100]["axes"]["X"]["peak_velocity"].get<double>(), 500.0, 1e-6);
}

// A zig-zag of 20° turns at F6000, with no path mode of its own.
std::string zigzag_body() {
  std::string body = "G0 X100 Y100 Z5\nG1 F6000\n";
  for (int k = 0; k < 20; ++k)
    body += "G1 X" + std::to_string(105 + 5 * k) + " Y" + (k % 2 ? "100" : "100.88") + "\n";
  return body + "M2\n";
}

TEST(LasercncRun, BlendingCutsCornersWithinPAndSavesTime) {
  const std::string body = zigzag_body();
  const fs::path blend = write_file("blend.ngc", "G21 G90 G64 P0.02\n" + body);
  const fs::path stop = write_file("stop.ngc", "G21 G90 G61\n" + body);
  const CmdResult rb = lasercnc("run " + blend.string() + " --json --no-progress --fast");
  const CmdResult rs = lasercnc("run " + stop.string() + " --json --no-progress --fast");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  ASSERT_EQ(rs.exit_code, 0) << rs.err;
  const auto jb = nlohmann::json::parse(rb.out), js = nlohmann::json::parse(rs.out);
  EXPECT_LE(jb["max_deviation_mm"].get<double>(), 0.02);
  EXPECT_GT(jb["max_deviation_mm"].get<double>(), 0.005);  // corners really are rounded
  EXPECT_LE(js["max_deviation_mm"].get<double>(), 0.001);
  EXPECT_LT(jb["cycle_time_s"].get<double>(), 0.9 * js["cycle_time_s"].get<double>());
  EXPECT_TRUE(jb["steps_match"].get<bool>());
}

// The shipped machine starts every program in G64 (its startup_code): a
// CAM file that never writes G64 blends within the machine's tolerance, and
// `--tolerance` sets that tolerance. It used to start in G61 and stop at
// every chord.
TEST(LasercncRun, AProgramWithoutG64BlendsWithinTheMachinesTolerance) {
  const std::string body = zigzag_body();
  const fs::path cam = write_file("cam.ngc", "G21 G90\n" + body);
  const fs::path stop = write_file("stop.ngc", "G21 G90 G61\n" + body);
  const CmdResult rc = lasercnc("run " + cam.string() + " --json --no-progress --fast --tolerance 0.02");
  const CmdResult rs = lasercnc("run " + stop.string() + " --json --no-progress --fast --tolerance 0.02");
  ASSERT_EQ(rc.exit_code, 0) << rc.err;
  ASSERT_EQ(rs.exit_code, 0) << rs.err;
  const auto jc = nlohmann::json::parse(rc.out), js = nlohmann::json::parse(rs.out);
  EXPECT_LE(jc["max_deviation_mm"].get<double>(), 0.02);
  EXPECT_GT(jc["max_deviation_mm"].get<double>(), 0.011);  // --tolerance, not the config's 0.01
  EXPECT_LT(jc["cycle_time_s"].get<double>(), 0.9 * js["cycle_time_s"].get<double>());
}

// IJK arcs whose two radii differ within LinuxCNC's tolerance (a post's
// rounding) run as spirals: the job ends on the programmed end with every
// step, within the axes' limits (the run's own check, and the trace
// measured here), and without a jump at the arcs' ends.
TEST(LasercncRun, ArcsWhoseRadiiDifferRunAsSpiralsWithinTheLimits) {
  const fs::path prog = write_file("spirals.ngc",
                                   "G21 G90 G64 P0.01 F9000\nG0 X10 Y10 Z5\nG1 X20\n"
                                   "G3 X30.028 Y10 I5 J0\nG2 X40 Y10 I4.986 J0\n"
                                   "G2 X50 Y19.98 I0 J10\nG1 X60\nM2\n");
  const fs::path trace = temp_dir() / "spirals.csv";
  const CmdResult r =
      lasercnc("run " + prog.string() + " --json --no-progress --fast --trace " + trace.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["steps_match"].get<bool>());
  EXPECT_EQ(j["axes"]["X"]["steps_sent"].get<long long>(), 60000);
  EXPECT_EQ(j["axes"]["Y"]["steps_sent"].get<long long>(), 19980);
  EXPECT_LE(j["max_deviation_mm"].get<double>(), 0.01);
  const std::vector<TraceRow> rows = read_trace(trace);
  ASSERT_FALSE(rows.empty());
  expect_within_velocity_limits(rows);
  // no period moves further than the fastest axis allows (500 mm/s) and a
  // step: a jump onto an arc's end would
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double dt = rows[k].t - rows[k - 1].t;
    ASSERT_LE(std::hypot(rows[k].x - rows[k - 1].x, rows[k].y - rows[k - 1].y), 500.0 * dt + 0.0015)
        << "row " << k;
  }
}

// The simulated machine's inputs from the command line: an M66 wait for
// input 3 high times out without `--input 3` (a fault, exit 3) and goes on
// at once with it; `--adaptive-feed 0.5` halves the feed after M52 P1.
TEST(LasercncRun, TheSimulatedInputsAreSetFromTheCommandLine) {
  const fs::path prog = write_file("inputs.ngc",
                                   "G21 G90\nG0 X10 Y10 Z20\nM66 P3 L3 Q0.3\nM52 P1\n"
                                   "G1 X60 F3000\nM2\n");
  const CmdResult none = lasercnc("run " + prog.string() + " --no-progress --fast");
  EXPECT_EQ(none.exit_code, 3);
  EXPECT_NE(none.out.find("M66 wait for an input timed out at line 3"), std::string::npos) << none.out;
  const CmdResult high = lasercnc("run " + prog.string() + " --json --no-progress --fast --input 3");
  ASSERT_EQ(high.exit_code, 0) << high.err;
  const CmdResult half =
      lasercnc("run " + prog.string() + " --json --no-progress --fast --input 3 --adaptive-feed 0.5");
  ASSERT_EQ(half.exit_code, 0) << half.err;
  const double t1 = nlohmann::json::parse(high.out)["cycle_time_s"].get<double>();
  const double t2 = nlohmann::json::parse(half.out)["cycle_time_s"].get<double>();
  // the 50 mm cut at 50 mm/s takes 1 s, at half 2 s; the rapids the same
  // (the simulated clock: exact on any computer)
  EXPECT_GT(t2 - t1, 0.9) << t1 << " " << t2;
  EXPECT_LT(t2 - t1, 1.5) << t1 << " " << t2;
  EXPECT_EQ(lasercnc("run " + prog.string() + " --input 8").exit_code, 2);
  EXPECT_EQ(lasercnc("run " + prog.string() + " --adaptive-feed 1.5").exit_code, 2);
}

TEST(LasercncRun, TextReportNamesEveryFigure) {
  const fs::path prog = write_file("square.ngc", "G21 G90 G61\nG0 X10 Y10 Z5\nG1 X20 F1200\nG1 Y20\nM2\n");
  const CmdResult r = lasercnc("run " + prog.string() + " --no-progress");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"feed override", "cycle time", "path length", "max deviation", "peak velocity",
                          "steps sent", "underruns", "RT latency", "p50", "p99"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
  EXPECT_NE(r.out.find("sent = commanded on every axis"), std::string::npos) << r.out;
}

TEST(LasercncRun, LimitsFromTheCommandLineOverrideTheConfig) {
  const fs::path prog = write_file("line.ngc", "G0 X100 Y10 Z5\nM2\n");
  const CmdResult r =
      lasercnc("run " + prog.string() + " --json --no-progress --fast --vmax 100 --amax 1000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // planned at the limits given: 100 mm at 100 mm/s with a = 1000: 1 s + 0.1 s
  EXPECT_NEAR(j["axes"]["X"]["peak_velocity"].get<double>(), 100.0, 1e-6);
  EXPECT_LE(j["axes"]["X"]["peak_acceleration"].get<double>(), 1000.0 * (1 + 1e-6));
  EXPECT_NEAR(j["cycle_time_s"].get<double>(), 1.1, 0.01);
}

TEST(LasercncRun, BadProgramIsRejectedBeforeAnythingMoves) {
  std::string text = "G21 G90\nG0 X10 Y10 Z5\n";
  for (int i = 0; i < 200; ++i) text += "G1 X" + std::to_string(10 + i % 7) + " F600\n";
  text += "G1 X20 Y20 Q7\n";  // line 203: a word outside the subset
  const fs::path prog = write_file("bad.ngc", text);
  const fs::path trace = temp_dir() / "never.csv";
  const CmdResult r = lasercnc("run " + prog.string() + " --no-progress --fast --trace " + trace.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(prog.string() + ":203:"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(fs::exists(trace));  // nothing ran
}

TEST(LasercncRun, MoveBeyondTravelAndMissingFeedNameTheirLines) {
  const fs::path p1 = write_file("travel.ngc", "G0 X10 Y10\nG0 Y500\n");
  CmdResult r = lasercnc("run " + p1.string() + " --no-progress --fast");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("travel.ngc:2:"), std::string::npos) << r.err;
  const fs::path p2 = write_file("nofeed.ngc", "G0 X10 Y10\nG1 X20\n");
  r = lasercnc("run " + p2.string() + " --no-progress --fast");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("nofeed.ngc:2:"), std::string::npos) << r.err;
}

// A job's work offsets outlive it: the machine's parameter file keeps them
// for the next `lasercnc run` (a new process), and `check` leaves it alone.
TEST(LasercncRun, WorkOffsetsSetByAJobAreThereForTheNextJob) {
  std::string cfg = slurp(kShare + "/machines/default.toml");
  cfg.replace(cfg.find("[machine]\n"), 10, "[machine]\nparameter_file = \"jobs.var\"\n");
  const fs::path m = write_file("kept.toml", cfg);
  const fs::path var = temp_dir() / "jobs.var";
  fs::remove(var);
  const fs::path setter = write_file("setter.ngc", "G21 G90\nG10 L2 P1 X5 Y2\nG0 X1\nM2\n");
  const fs::path user = write_file("user.ngc", "G21 G90\nG0 X1\nM2\n");
  CmdResult r = lasercnc("check " + setter.string() + " --machine " + m.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(var)) << "a check writes nothing";
  r = lasercnc("run " + setter.string() + " --json --no-progress --fast --machine " + m.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(var));
  EXPECT_NE(slurp(var.string()).find("5221\t5\n"), std::string::npos) << slurp(var.string());
  // G54 is X5 now: X1 is machine X6, 6 mm from the simulated machine's 0
  // (without the kept offset, 1 mm)
  r = lasercnc("run " + user.string() + " --json --no-progress --fast --machine " + m.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["path_length_mm"].get<double>(), 6.0, 1e-9);
  // a malformed file stops the next job before it moves, naming the line
  std::ofstream(var) << "5221 five\n";
  r = lasercnc("run " + user.string() + " --no-progress --fast --machine " + m.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("jobs.var:1:6"), std::string::npos) << r.err;
}

// A job that moves and then sets a work offset passes its own check: the
// check reads the program from the offsets the job started from, not from
// the parameter file the job rewrites at its end (read after, it held the
// moves before the G10 to the new offset: 0.32 mm off, a failed run).
TEST(LasercncRun, AJobThatSetsAWorkOffsetAfterItsMovesPassesItsOwnCheck) {
  std::string cfg = slurp(kShare + "/machines/default.toml");
  cfg.replace(cfg.find("[machine]\n"), 10, "[machine]\nparameter_file = \"moved.var\"\n");
  const fs::path m = write_file("moved.toml", cfg);
  const fs::path var = temp_dir() / "moved.var";
  const fs::path prog =
      write_file("moves_then_g10.ngc", "G21 G90\nG1 X2 Y1 F1200\nG1 X0 Y0\nG10 L2 P1 X1\nM30\n");
  for (int run = 0; run < 2; ++run) {  // with no parameter file yet, then with the one it wrote
    const CmdResult r =
        lasercnc("run " + prog.string() + " --json --no-progress --fast --machine " + m.string());
    ASSERT_EQ(r.exit_code, 0) << "run " << run << "\n" << r.out << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["check"]["passed"].get<bool>()) << j["check"].dump();
    EXPECT_LT(j["max_deviation_mm"].get<double>(), 0.01) << j.dump();
    EXPECT_NE(slurp(var.string()).find("5221\t1\n"), std::string::npos);
  }
}

// `check` and `run` always end: an endless loop that moves runs into the
// reading's work budget (a week of machine time, 200 million segments), one
// of G4 P0 or M0 into the limit on passes without anything that takes time —
// an error at the loop's line, with the shipped machine's limits.
TEST(LasercncRun, CheckAndRunEndOnEveryEndlessLoop) {
  const std::vector<std::pair<std::string, std::string>> loops{
      {"G21 G90 F6000\no1 while [1]\nG1 X10\nG1 X0\no1 endwhile\nM2\n", "E314"},
      {"G21 G90 F6000\nG0 Y20\no1 repeat [1000000000000]\nG2 X10 I5\nG2 X0 I-5\no1 endrepeat\nM2\n", "E314"},
      {"G21 G90\no1 do\nG4 P0\no1 while [1]\nM2\n", "E310"},
      {"G21 G90\no1 while [1]\nM0\no1 endwhile\nM2\n", "E310"},
  };
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const fs::path p = write_file("endless_" + std::to_string(k) + ".ngc", loops[k].first);
    for (const std::string cmd : {"check ", "run "}) {
      const CmdResult r = lasercnc(cmd + p.string() + " --no-progress --fast");
      EXPECT_EQ(r.exit_code, 1) << cmd << k << "\n" << r.out << r.err;
      EXPECT_NE(r.err.find(loops[k].second), std::string::npos) << cmd << k << "\n" << r.err;
      EXPECT_NE(r.err.find("endless_" + std::to_string(k) + ".ngc:"), std::string::npos) << r.err;
    }
  }
}

// Unattended, `lasercnc run` resumes each M0/M1 after --pause seconds: the
// cycle is that much longer, every step and limit as without them.
TEST(LasercncRun, ProgramPausesAreResumedAfterThePauseOption) {
  const fs::path plain = write_file("plain.ngc", "G21 G90 G64 P0.01\nG1 X10 F600\nG1 X20\nG1 Y5\nM2\n");
  const fs::path paused =
      write_file("paused.ngc", "G21 G90 G64 P0.01\nG1 X10 F600\nM0\nG1 X20\nM1\nG1 Y5\nM2\n");
  CmdResult r = lasercnc("run " + plain.string() + " --json --no-progress --fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double base = nlohmann::json::parse(r.out)["cycle_time_s"].get<double>();
  r = lasercnc("run " + paused.string() + " --json --no-progress --fast --pause 0.4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["program_pauses"], 2);
  EXPECT_TRUE(j["steps_match"].get<bool>());
  EXPECT_TRUE(j["check"]["passed"].get<bool>()) << j.dump();
  // two pauses of 0.4 s at least; the stops they make cost a little more
  EXPECT_GE(j["cycle_time_s"].get<double>(), base + 0.8);
  EXPECT_LT(j["cycle_time_s"].get<double>(), base + 0.8 + 1.0);
  EXPECT_EQ(lasercnc("run " + paused.string() + " --pause -1").exit_code, 2);
}

TEST(LasercncRun, BadMachineConfigIsRejectedWithTheKey) {
  std::string cfg = slurp(kShare + "/machines/default.toml");
  cfg.replace(cfg.find("max_velocity = 500.0"), 20, "max_velocity = 5000.0");
  const fs::path m = write_file("fast.toml", cfg);
  const fs::path prog = write_file("p.ngc", "G0 X1\n");
  const CmdResult r = lasercnc("run " + prog.string() + " --machine " + m.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("axes.X.max_velocity"), std::string::npos) << r.err;
  // --vmax beyond the DDA preset is refused the same way
  const CmdResult r2 = lasercnc("run " + prog.string() + " --vmax 4000");
  EXPECT_EQ(r2.exit_code, 1);
  EXPECT_NE(r2.err.find("max_velocity"), std::string::npos) << r2.err;
}

// --fast runs the machine on the simulated clock; the Modbus devices keep
// wall time, so the two are not combined: a usage error naming why.
TEST(LasercncCli, FastIsRefusedWithDevicesThatKeepWallTime) {
  const fs::path prog = write_file("p.ngc", "G0 X1\nM2\n");
  for (const std::string devices :
       {"--devices", "--laser tcp:127.0.0.1:1", "--power-meter tcp:127.0.0.1:1"}) {
    const CmdResult r = lasercnc("run " + prog.string() + " --fast " + devices);
    EXPECT_EQ(r.exit_code, 2) << devices;
    EXPECT_NE(r.err.find("keep wall time"), std::string::npos) << r.err;
  }
  const CmdResult d = lasercnc("drill " + kShare + "/examples/holes.csv --fast --devices");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("keep wall time"), std::string::npos) << d.err;
}

TEST(LasercncCli, FeedOverrideOutsideItsRangeIsAUsageError) {
  // 1e-300 % would make a period last 10^297 s: the run never ends
  for (const char* pct : {"0", "200", "-10", "150.5", "1e-300", "0.99"}) {
    const CmdResult r = lasercnc(std::string("run x.ngc --no-progress --feed-override ") + pct);
    EXPECT_EQ(r.exit_code, 2) << pct;
    EXPECT_NE(r.err.find("1 <= PCT <= 150"), std::string::npos) << pct << "\n" << r.err;
    EXPECT_NE(r.err.find("usage:"), std::string::npos);
    EXPECT_TRUE(r.out.empty());
  }
  EXPECT_EQ(lasercnc("run x.ngc --feed-override fast").exit_code, 2);
  // not a number, as every option's number reads (app/cli_values.h)
  const CmdResult nan = lasercnc("run x.ngc --feed-override nan");
  EXPECT_EQ(nan.exit_code, 2);
  EXPECT_NE(nan.err.find("--feed-override needs a number"), std::string::npos) << nan.err;
  EXPECT_EQ(lasercnc("run x.ngc --feed-override").exit_code, 2);
  // the range follows the machine's max_feed_override
  std::string cfg = slurp(kShare + "/machines/default.toml");
  cfg.replace(cfg.find("max_feed_override = 1.5"), 23, "max_feed_override = 1.2");
  const fs::path m = write_file("k12.toml", cfg);
  const fs::path prog = write_file("p.ngc", "G0 X1\n");
  const CmdResult r = lasercnc("run " + prog.string() + " --no-progress --fast --machine " + m.string() +
                               " --feed-override 130");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("1 <= PCT <= 120"), std::string::npos) << r.err;
  EXPECT_EQ(lasercnc("run " + prog.string() + " --no-progress --fast --machine " + m.string() +
                     " --feed-override 120")
                .exit_code,
            0);
}

TEST(LasercncCli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(lasercnc("").exit_code, 2);
  EXPECT_EQ(lasercnc("fly").exit_code, 2);
  EXPECT_EQ(lasercnc("run").exit_code, 2);
  EXPECT_EQ(lasercnc("run x.ngc --vmax fast").exit_code, 2);
  const CmdResult r = lasercnc("run x.ngc --bogus");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--bogus"), std::string::npos);
}

TEST(LasercncCli, CheckReadsTheWholeProgram) {
  const CmdResult r = lasercnc("check " + kShare + "/examples/bracket.ngc");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("OK"), std::string::npos);
  const CmdResult missing = lasercnc("check /nonexistent.ngc");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("/nonexistent.ngc"), std::string::npos);
}

}  // namespace

namespace {

TEST(LasercncRun, ProgressBarReachesOneHundredPercent) {
  const fs::path prog = write_file("p.ngc", "G0 X50 Y10 Z5\nG1 X60 F3000\nM2\n");
  const CmdResult r = lasercnc("run " + prog.string() + " --progress --fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("100.0 %"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[####"), std::string::npos) << r.err;
}

}  // namespace
