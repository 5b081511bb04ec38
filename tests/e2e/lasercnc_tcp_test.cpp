// End to end: a program run under tool-centre-point control ([kinematics]
// tcp = true) — checked on the joints, planned and executed on the simulated
// machine with every step sent; the same program without TCP runs the
// programmed coordinates as joints.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "e2e_support.h"

namespace {

using namespace e2e;

const std::string kShare = std::string(LCNC_SOURCE_DIR) + "/share";

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
  const CmdResult r = lasercnc("run " + prog.string() + " --machine " + tcp_machine("pole_smoothed").string() +
                               " --json --no-realtime");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_TRUE(j["steps_match"].get<bool>());
  EXPECT_EQ(j["underruns"], 0);
  EXPECT_EQ(j["fault"], "");
  EXPECT_GT(j["axes"]["A"]["peak_velocity"].get<double>(), 0.0);
  EXPECT_GT(j["axes"]["C"]["peak_velocity"].get<double>(), 0.0);
  // measured against the joint path the program became
  EXPECT_LE(j["max_deviation_mm"].get<double>(), 0.01);
  EXPECT_GT(j["segments"].get<int>(), 6);  // the tilting lines were split into pieces
  // the head's reference point, not the tip, is what the X Y Z joints carry:
  // 200 mm above the tip at A = 0 on the default head
  EXPECT_NEAR(j["axes"]["Z"]["steps_commanded"].get<double>(), 220000.0, 1.0);
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
