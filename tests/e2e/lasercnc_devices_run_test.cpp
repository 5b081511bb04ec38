// End to end: `lasercnc run` with the laser source and power meter on
// Modbus — the in-process simulators (--devices), and a device at an
// endpoint (--laser) that is in alarm or not there: the run is refused
// before anything moves.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/laser_link.h"
#include "drivers/devices/laser_source_sim.h"
#include "drivers/modbus/modbus_master.h"
#include "drivers/modbus/register_map.h"
#include "e2e_support.h"

namespace {

using namespace e2e;

fs::path job(const std::string& text) {
  const fs::path p = temp_dir() / "job.ngc";
  std::ofstream(p) << text;
  return p;
}

// 1.5 s of cutting at 60 % (30 W of the simulator's 50 W): long enough for
// the thermopile (τ 0.3 s) to settle.
const char* kCut = "G21 G90\nG0 X10 Y10\nM3 S60\nG1 X160 F6000\nG1 Y20\nG1 X10\nM5\nG0 X0 Y0\nM2\n";

TEST(LasercncRunDevices, SetpointFollowsTheJobAndTheMeterSeesTheBeam) {
  const CmdResult r = lasercnc("run " + job(kCut).string() + " --devices --json --no-realtime");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  ASSERT_TRUE(j.contains("peripherals")) << r.out;
  const nlohmann::json& p = j["peripherals"];
  EXPECT_TRUE(p["simulated"].get<bool>());
  EXPECT_NE(p["laser"].get<std::string>().find("laser_source (unit 2, tcp 127.0.0.1:"), std::string::npos);
  EXPECT_EQ(p["rated_power_w"].get<double>(), 50.0);
  EXPECT_GE(p["setpoint_writes"].get<int>(), 2);  // on at 60 %, off at M5
  EXPECT_EQ(p["modbus_failed"].get<int>(), 0) << p["error"];
  EXPECT_EQ(p["alarm"], "");
  EXPECT_NEAR(p["commanded_mean_lasing_w"].get<double>(), 30.0, 1e-9);
  // the beam reached the meter: after the lag, near the commanded 30 W
  EXPECT_GT(p["meter_samples"].get<int>(), 10);
  EXPECT_NEAR(p["meter_peak_w"].get<double>(), 30.0, 1.5);
  EXPECT_GT(p["meter_mean_lasing_w"].get<double>(), 15.0);
  EXPECT_LE(p["meter_mean_lasing_w"].get<double>(), 31.0);
  EXPECT_TRUE(j["steps_match"].get<bool>());
}

TEST(LasercncRunDevices, TextReportNamesTheDevices) {
  const CmdResult r = lasercnc("run " + job(kCut).string() + " --devices --no-realtime --no-progress");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("laser source     laser_source (unit 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(simulator)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("power meter      power_meter (unit 3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 failed"), std::string::npos) << r.out;
}

TEST(LasercncRunDevices, ALaserInAlarmRefusesTheRunBeforeAnythingMoves) {
  auto map = lcnc::drivers::shipped_device("laser_source");
  ASSERT_TRUE(static_cast<bool>(map));
  lcnc::drivers::LaserSourceParams hot;
  hot.alarm_c = 20.0;  // below the ambient 25 °C: the over-temperature alarm latches at once
  hot.reset_below_c = 15.0;
  auto laser = lcnc::drivers::LaserSourceSim::create(*map, {}, hot);
  ASSERT_TRUE(static_cast<bool>(laser)) << laser.error().to_string();
  ASSERT_TRUE((*laser)->start().ok());
  const auto ep = (*laser)->endpoint();
  {  // the alarm latches at the simulator's first tick: wait for it
    lcnc::drivers::MasterConfig mc;
    mc.endpoint = ep;
    lcnc::drivers::ModbusMaster m(*map, mc);
    ASSERT_TRUE(m.start().ok());
    bool alarmed = false;
    for (int i = 0; i < 200 && !alarmed; ++i) {
      auto a = m.read("alarm").get();
      alarmed = a.ok() && *a == 1.0;
      if (!alarmed) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(alarmed);
  }
  const fs::path trace = temp_dir() / "trace.csv";
  const CmdResult r =
      lasercnc("run " + job(kCut).string() + " --laser tcp:127.0.0.1:" + std::to_string(ep.port) +
               " --trace " + trace.string() + " --no-realtime");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.err.find("laser_source (unit 2, tcp 127.0.0.1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("exception 04"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");                                          // no report: nothing ran
  EXPECT_TRUE(!fs::exists(trace) || fs::file_size(trace) < 64);  // at most the CSV header
  (*laser)->stop();
}

TEST(LasercncRunDevices, NoDeviceAtTheEndpointIsAClearErrorWithinTheTimeouts) {
  const auto t0 = std::chrono::steady_clock::now();
  const CmdResult r = lasercnc("run " + job(kCut).string() + " --laser tcp:127.0.0.1:1 --no-realtime");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("laser_source"), std::string::npos) << r.err;
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(10));
  EXPECT_EQ(lasercnc("run " + job(kCut).string() + " --laser udp:1").exit_code, 2);
}

// About 6.5 s of cutting at 60 %: time for the source to fail in the middle.
const char* kLongCut = "G21 G90\nG0 X10 Y10\nM3 S60\nG1 X160 F3000\nG1 Y20\nG1 X10\nM5\nG0 X0 Y0\nM2\n";
constexpr double kLongCutS = 6.3;  // at least, without a fault

// Runs kLongCut against `laser` (a source this test holds) while `fail`
// breaks it 0.8 s in; the report and the trace's laser column after.
struct FailedRun {
  CmdResult r;
  nlohmann::json j;
  double last_lasing_t = -1.0;  // the last period with laser output, s
  double last_moving_t = 0.0;   // the last period whose position changed, s
  double end_t = 0.0;           // the trace's last period, s
};
template <typename Fail>
FailedRun run_while_failing(lcnc::drivers::LaserSourceSim& laser, Fail fail) {
  FailedRun out;
  const fs::path trace = temp_dir() / "fail_trace.csv";
  std::thread breaker([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    fail();
  });
  out.r = lasercnc("run " + job(kLongCut).string() +
                   " --laser tcp:127.0.0.1:" + std::to_string(laser.endpoint().port) + " --trace " +
                   trace.string() + " --json --no-realtime");
  breaker.join();
  out.j = nlohmann::json::parse(out.r.out, nullptr, false);
  std::ifstream csv(trace);
  std::string row;
  std::getline(csv, row);  // header
  std::string last_pos;
  while (std::getline(csv, row)) {
    const double t = std::stod(row);
    const std::size_t power_at = row.rfind(',');
    const double power = std::stod(row.substr(power_at + 1));
    const std::string pos = row.substr(row.find(',') + 1, power_at - row.find(','));
    if (power > 0.0) out.last_lasing_t = t;
    if (pos != last_pos) out.last_moving_t = t;
    last_pos = pos;
    out.end_t = t;
  }
  return out;
}

// A source that goes silent mid-job (its server gone): a controlled stop
// along the path with the beam off, and the run fails naming it.
TEST(LasercncRunDevices, ALaserSourceLostMidJobStopsTheJobWithTheBeamOff) {
  auto map = lcnc::drivers::shipped_device("laser_source");
  ASSERT_TRUE(static_cast<bool>(map));
  auto laser = lcnc::drivers::LaserSourceSim::create(*map);
  ASSERT_TRUE(static_cast<bool>(laser));
  ASSERT_TRUE((*laser)->start().ok());
  const FailedRun f = run_while_failing(**laser, [&] { (*laser)->stop(); });
  EXPECT_EQ(f.r.exit_code, 3) << f.r.err << f.r.out;
  ASSERT_TRUE(f.j.is_object()) << f.r.out;
  const std::string fault = f.j["fault"].get<std::string>();
  EXPECT_NE(fault.find("laser source: laser_source (unit 2"), std::string::npos) << fault;
  EXPECT_NE(fault.find("lost"), std::string::npos) << fault;
  EXPECT_FALSE(f.j["succeeded"].get<bool>());
  EXPECT_LT(f.end_t, kLongCutS - 2.0);  // stopped well short of the end
  EXPECT_GT(f.last_lasing_t, 0.5);      // it was cutting …
  // … and the beam went off at the fault, while the axes still braked
  // along the path (without the RT's inhibit it would follow the job's
  // power to rest)
  EXPECT_LT(f.last_lasing_t, f.last_moving_t - 0.002);
  EXPECT_TRUE(f.j["check"]["passed"].get<bool>()) << f.j["check"];  // a controlled stop
}

// The source latches its over-temperature alarm mid-job.
TEST(LasercncRunDevices, ALaserAlarmMidJobStopsTheJobWithTheBeamOff) {
  auto map = lcnc::drivers::shipped_device("laser_source");
  ASSERT_TRUE(static_cast<bool>(map));
  lcnc::drivers::LaserSourceParams p;
  p.thermal_tau_s = 0.5;  // heats fast: 60 % of 30 °C rise trips 35 °C within a second
  p.alarm_c = 35.0;
  p.reset_below_c = 30.0;
  auto laser = lcnc::drivers::LaserSourceSim::create(*map, {}, p);
  ASSERT_TRUE(static_cast<bool>(laser));
  ASSERT_TRUE((*laser)->start().ok());
  const FailedRun f = run_while_failing(**laser, [] {});
  (*laser)->stop();
  EXPECT_EQ(f.r.exit_code, 3) << f.r.err << f.r.out;
  ASSERT_TRUE(f.j.is_object()) << f.r.out;
  EXPECT_NE(f.j["fault"].get<std::string>().find("alarm: over-temperature"), std::string::npos)
      << f.j["fault"];
  EXPECT_LT(f.end_t, kLongCutS - 2.0);
  EXPECT_LT(f.last_lasing_t, f.last_moving_t - 0.002);
}

// A sensor that reads the register's end (3276.7 °C) is no temperature.
TEST(LasercncRunDevices, AnImplausibleTemperatureStopsTheJob) {
  auto shipped = lcnc::drivers::shipped_device("laser_source");
  ASSERT_TRUE(static_cast<bool>(shipped));
  lcnc::drivers::DeviceMap map = *shipped;  // the simulator may report the i16's end
  for (auto& reg : map.registers)
    if (reg.name == "temperature_c") reg.max = 3276.7;
  lcnc::drivers::LaserSourceParams p;
  p.ambient_c = 3276.7;
  p.alarm_c = 1e6;
  p.reset_below_c = 1e5;
  auto laser = lcnc::drivers::LaserSourceSim::create(map, {}, p);
  ASSERT_TRUE(static_cast<bool>(laser)) << laser.error().to_string();
  ASSERT_TRUE((*laser)->start().ok());
  const FailedRun f = run_while_failing(**laser, [] {});
  (*laser)->stop();
  EXPECT_EQ(f.r.exit_code, 3) << f.r.err << f.r.out;
  ASSERT_TRUE(f.j.is_object()) << f.r.out;
  EXPECT_NE(f.j["fault"].get<std::string>().find("temperature_c: device reported 3276.7 outside"),
            std::string::npos)
      << f.j["fault"];
}

}  // namespace

namespace {

// A link dropped on an error path, without finish(): emission is off all the
// same (the laser is never left enabled).
TEST(LaserLink, DroppedWithoutFinishStillSwitchesEmissionOff) {
  auto map = lcnc::drivers::shipped_device("laser_source");
  ASSERT_TRUE(static_cast<bool>(map));
  auto laser = lcnc::drivers::LaserSourceSim::create(*map);
  ASSERT_TRUE(static_cast<bool>(laser));
  ASSERT_TRUE((*laser)->start().ok());
  lcnc::drivers::MasterConfig mc;
  mc.endpoint = (*laser)->endpoint();
  lcnc::drivers::ModbusMaster watch(*map, mc);
  ASSERT_TRUE(watch.start().ok());
  {
    auto link = lcnc::app::LaserLink::connect((*laser)->endpoint(), std::nullopt);
    ASSERT_TRUE(static_cast<bool>(link)) << link.error().to_string();
    ASSERT_TRUE((*link)->enable().ok());
    EXPECT_EQ(*watch.read("enable").get(), 1.0);
    (*link)->follow(70.0);  // the setpoint follows a cut …
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }  // … and the link goes away without finish()
  EXPECT_EQ(*watch.read("enable").get(), 0.0);
  EXPECT_EQ(*watch.read("power_setpoint_pct").get(), 0.0);
  watch.stop();
  (*laser)->stop();
}

}  // namespace
