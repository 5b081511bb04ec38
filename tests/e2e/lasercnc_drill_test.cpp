// End to end: `lasercnc drill` runs a process-database table on the simulated
// machine — the holes in order, the scanning head's block written while the
// machine stands at each hole, every step sent — and refuses bad tables and
// holes beyond the travel before anything moves.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "e2e_support.h"

namespace {

using namespace e2e;

const std::string kHeader =
    "hole,x_mm,y_mm,z_mm,a_deg,c_deg,feed_mm_min,layer_feed_mm,layer_count,total_depth_mm,"
    "power_pct,start_radius_mm,end_radius_mm,radius_turns,scan_speed_mm_s,wedge_speed_rpm,"
    "beam_offset_mm,process,shape\n";

fs::path table(const std::string& rows) {
  const fs::path p = temp_dir() / "holes.csv";
  std::ofstream(p) << kHeader << rows;
  return p;
}

TEST(LasercncDrill, RunsTheHolesInOrderAndWritesEachHeadBlockAtItsHole) {
  const fs::path t = table(
      "11,100,100,20,0,0,2000,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n"
      "12,120,100,20,-20,90,2000,0.1,2,0.2,60,0.3,0.6,2,150,6000,0,circle,\n");
  const CmdResult r = lasercnc("drill " + t.string() + " --devices --json --no-realtime --settle 0.1");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_TRUE(j["steps_match"].get<bool>());
  EXPECT_EQ(j["underruns"], 0);
  EXPECT_EQ(j["fault"], "");
  EXPECT_EQ(j["lines"], 2);
  EXPECT_EQ(j["line_unit"], "holes");
  const nlohmann::json& holes = j["holes"];
  ASSERT_EQ(holes.size(), 2u);
  EXPECT_EQ(holes[0]["hole"], 11);
  EXPECT_EQ(holes[0]["process"], "helix");
  EXPECT_EQ(holes[1]["hole"], 12);
  EXPECT_EQ(holes[1]["process"], "circle");
  double t_prev = -1.0, total = 0.0;
  for (const nlohmann::json& h : holes) {
    EXPECT_TRUE(h["head_written"].get<bool>()) << h;
    EXPECT_EQ(h["head_error"], "") << h;
    EXPECT_GT(h["start_s"].get<double>(), t_prev);
    EXPECT_GT(h["time_s"].get<double>(), 0.1);  // at least the settle dwell
    t_prev = h["start_s"].get<double>();
    total += h["time_s"].get<double>();
  }
  EXPECT_NEAR(total, j["cycle_time_s"].get<double>(), 0.01);
  EXPECT_GE(j["scan_head"]["requests"].get<int>(), 7);  // per hole run 0, block, run 1; run 0 after
  EXPECT_EQ(j["scan_head"]["failed"], 0);
  EXPECT_EQ(j["peripherals"]["modbus_failed"], 0);
  EXPECT_GT(j["laser_on_s"].get<double>(), 0.2);
  // the tilted hole turned A and C: peak speeds on both
  EXPECT_GT(j["axes"]["A"]["peak_velocity"].get<double>(), 0.0);
  EXPECT_GT(j["axes"]["C"]["peak_velocity"].get<double>(), 0.0);
}

TEST(LasercncDrill, BadTableIsRefusedWithItsLineAndColumn) {
  const fs::path t = table("11,1O0,100,20,0,0,2000,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n");
  const CmdResult r = lasercnc("drill " + t.string() + " --fast");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("holes.csv:2:4: error E701"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(LasercncDrill, HoleBeyondTheTravelIsRefusedBeforeAnythingMoves) {
  // Z 499: its clearance point (5 mm above, plus the head's pivot) leaves the travel
  const fs::path t = table(
      "11,100,100,20,0,0,2000,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n"
      "12,120,100,499,0,0,2000,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n");
  const CmdResult r = lasercnc("drill " + t.string() + " --fast");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("holes.csv:3:1:"), std::string::npos) << r.err;  // the row of hole 12
  EXPECT_NE(r.err.find("hole 12: axis Z"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(LasercncDrill, UsageErrors) {
  EXPECT_EQ(lasercnc("drill").exit_code, 2);
  EXPECT_EQ(lasercnc("drill a.csv --clearance -1").exit_code, 2);
  EXPECT_EQ(lasercnc("drill a.csv --bogus").exit_code, 2);
  EXPECT_EQ(lasercnc("drill " + temp_dir().string() + "/missing.csv").exit_code, 1);
}

}  // namespace
