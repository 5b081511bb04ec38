// End to end: a program run under tool-centre-point control ([kinematics]
// tcp = true) — checked on the joints, planned and executed on the simulated
// machine with every step sent; the same program without TCP runs the
// programmed coordinates as joints.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "e2e_support.h"

namespace {

using namespace e2e;

fs::path tcp_machine(const std::string& orientation) {
  const fs::path p = temp_dir() / ("tcp_" + orientation + ".toml");
  std::string text = slurp(kShare + "/machines/default.toml");
  const auto set = [&](const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  set("tcp = false", "tcp = true");
  set("orientation = \"pole_smoothed\"", "orientation = \"" + orientation + "\"");
  std::ofstream(p) << text;
  return p;
}

TEST(LasercncTcp, TiltingCutRunsWithEveryStepSent) {
  // a short bevel (share/examples/tcp_bevel.ngc is the long one): tilt and
  // turn while cutting, then back upright through A = 0
  const fs::path prog = temp_dir() / "bevel.ngc";
  std::ofstream(prog) << "G21 G90 G64 P0.01\nG0 X100 Y100 Z20 A0 C0\nM3 S80\n"
                         "G1 X120 A10 F3000\nG1 Y110 C45\nG1 X100 A0\nM5\nM2\n";
  const CmdResult r = lasercnc("run " + prog.string() + " --machine " +
                               tcp_machine("pole_smoothed").string() + " --json --fast");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_TRUE(j["steps_match"].get<bool>());
  EXPECT_EQ(j["underruns"], 0);
  EXPECT_EQ(j["fault"], "");
  EXPECT_GT(j["axes"]["A"]["peak_velocity"].get<double>(), 0.0);
  EXPECT_GT(j["axes"]["C"]["peak_velocity"].get<double>(), 0.0);
  // the tool tip (forward kinematics of the joints) against the program
  EXPECT_LE(j["max_deviation_mm"].get<double>(), 0.01);
  EXPECT_GT(j["segments"].get<int>(), 6);  // the tilting lines were split into pieces
  // the head's reference point, not the tip, is what the X Y Z joints carry:
  // 200 mm above the tip at A = 0 on the default head
  EXPECT_NEAR(j["axes"]["Z"]["steps_commanded"].get<double>(), 220000.0, 1.0);
}

// C stepping by 37° and wrapping past 360 while A tilts through 0: every
// move of C is the shorter turn, with and without TCP (C once turned from
// 333 to 10 the long way, −323°). Under TCP the rapid to the first pose once
// never finished (its pieces became feed moves of feed 0); the tool tip is
// held to the program as written.
nlohmann::json run_json(const fs::path& prog, const std::string& machine_args) {
  const CmdResult r = lasercnc("run " + prog.string() + machine_args + " --json --fast");
  EXPECT_EQ(r.exit_code, 0) << prog << ": " << r.err << r.out;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  EXPECT_TRUE(j.is_object()) << r.out;
  return j;
}

TEST(LasercncTcp, AWrappingSwingTakesEveryShorterTurnAndKeepsTheTip) {
  const fs::path prog = temp_dir() / "swing.ngc";
  {
    std::ofstream p(prog);
    p << "G21 G90 G64 P0.05\nG0 X100 Y100 Z20 A-30 C0\nF3000\n";
    for (int k = 0; k <= 12; ++k)
      p << "G1 X" << 100 + 10 * k << " Y" << 100 + 5 * (k % 3) << " A" << -30 + 5 * k << " C"
        << (37 * k) % 360 << "\n";
    p << "M30\n";
  }
  nlohmann::json j = run_json(prog, "");
  ASSERT_TRUE(j.is_object());
  EXPECT_TRUE(j["succeeded"].get<bool>());
  EXPECT_NEAR(j["axes"]["C"]["steps_commanded"].get<double>(), 444000.0, 1.0);  // 12 × 37°

  // under TCP (Z is the tip's, 200 mm below the head at A = 0): C from 333
  // to 10 to 47 turns 74° in all, not 360 more
  const fs::path tcp_prog = temp_dir() / "swing_tcp.ngc";
  std::ofstream(tcp_prog) << "G21 G90 G64 P0.05\nG0 X100 Y100 Z-180 A15 C333\nF3000\n"
                             "G1 X110 Y105 A20 C10\nG1 X120 Y100 A25 C47\nM30\n";
  const fs::path trace = temp_dir() / "swing_tcp.csv";
  j = run_json(tcp_prog,
               " --machine " + tcp_machine("pole_smoothed").string() + " --trace " + trace.string());
  ASSERT_TRUE(j.is_object());
  EXPECT_TRUE(j["succeeded"].get<bool>());
  EXPECT_LE(j["axes"]["C"]["peak_velocity"].get<double>(), 360.0);
  EXPECT_LE(j["max_deviation_mm"].get<double>(), 0.05 + 0.005);  // the tip's
  const std::vector<TraceRow> rows = read_trace(trace);
  ASSERT_FALSE(rows.empty());
  double c_travel = 0.0;
  for (std::size_t i = 1; i < rows.size(); ++i) c_travel += std::abs(rows[i].c - rows[i - 1].c);
  // the G0 from C 0 to 333 is 27° the short way; then 74° on
  EXPECT_NEAR(c_travel, 27.0 + 74.0, 0.5);
  EXPECT_NEAR(rows.back().c - rows.front().c, 47.0, 0.5);
}

TEST(LasercncTcp, CheckSaysWhereTheJointsLeaveTheTravel) {
  const fs::path prog = temp_dir() / "high.ngc";
  std::ofstream(prog) << "G21 G90\nG1 X100 Y100 Z250 F600\nG1 Z320\nM2\n";
  const CmdResult r = lasercnc("check " + prog.string() + " --machine " + tcp_machine("vector").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("high.ngc:3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("axis Z"), std::string::npos) << r.err;
  // without TCP X Y Z are joints: within the travel
  EXPECT_EQ(lasercnc("check " + prog.string()).exit_code, 0);
}

}  // namespace
