// End to end: lasercncd serving the register map's cnc device to a PLC or
// MES (lasercncd --modbus): a real libmodbus master over loopback TCP reads
// the status, starts, holds, resumes and overrides a job by coil and
// register, and writes the hole parameter block — refusals are exceptions
// that change nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <regex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "daemon_status.h"
#include "drivers/modbus/modbus_master.h"
#include "drivers/modbus/register_map.h"
#include "e2e_support.h"

namespace {

using namespace e2e;
using namespace std::chrono_literals;
using lcnc::drivers::ModbusMaster;

// The port the daemon says it bound (it logs "… on tcp 127.0.0.1:PORT").
int bound_port(const Daemon& d) {
  const std::regex re("Modbus slave \\(device cnc, unit 1\\) on tcp 127\\.0\\.0\\.1:([0-9]+)");
  for (int i = 0; i < 500; ++i) {
    std::smatch m;
    const std::string log = d.log();
    if (std::regex_search(log, m, re)) return std::stoi(m[1]);
    std::this_thread::sleep_for(10ms);
  }
  return -1;
}

std::unique_ptr<ModbusMaster> master_for(int port) {
  auto map = lcnc::drivers::shipped_device("cnc");
  EXPECT_TRUE(static_cast<bool>(map));
  lcnc::drivers::MasterConfig c;
  c.endpoint.host = "127.0.0.1";
  c.endpoint.port = static_cast<std::uint16_t>(port);
  c.response_timeout = 2000ms;  // a command waits for the daemon's control thread
  auto m = std::make_unique<ModbusMaster>(*map, c);
  EXPECT_TRUE(m->start().ok());
  return m;
}

double read(ModbusMaster& m, const std::string& name) {
  auto r = m.read(name).get();
  EXPECT_TRUE(r.ok()) << name << ": " << (r.ok() ? "" : r.error().to_string());
  return r.ok() ? *r : -1.0;
}

bool wait_for(ModbusMaster& m, const std::string& name, double value, std::chrono::milliseconds t = 5000ms) {
  const auto until = std::chrono::steady_clock::now() + t;
  while (std::chrono::steady_clock::now() < until) {
    if (read(m, name) == value) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

TEST(LasercncdModbus, APlcRunsHoldsResumesAndOverridesAJob) {
  const std::string shm = shm_name("/lcnc_e2e_mb_");
  Daemon d(shm, {"--modbus", "tcp:127.0.0.1:0"});
  ASSERT_TRUE(d.ready()) << d.log();
  const int port = bound_port(d);
  ASSERT_GT(port, 0) << d.log();
  auto plc = master_for(port);
  EXPECT_EQ(read(*plc, "state"), 0.0);  // idle
  EXPECT_EQ(read(*plc, "x_mm"), 0.0);
  // start with nothing loaded: refused (exception 04), the coil stays 0
  lcnc::Status s = plc->write("cmd_start", 1).get();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("exception 04"), std::string::npos) << s.error().message;
  EXPECT_EQ(read(*plc, "cmd_start"), 0.0);
  EXPECT_NE(d.log().find("modbus: start refused: no program loaded"), std::string::npos) << d.log();

  const fs::path prog = temp_dir() / "long.ngc";
  std::ofstream(prog) << "G21 G90\nG0 X10 Y10\nM3 S50\nG1 X200 F1200\nG1 Y100\nM5\nM2\n";
  ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm).exit_code, 0);
  ASSERT_TRUE(plc->write("cmd_start", 1).get().ok());
  ASSERT_TRUE(wait_for(*plc, "state", 1.0));  // running
  EXPECT_TRUE(wait_for(*plc, "laser_on", 1.0));
  EXPECT_EQ(status(shm)["state"], "running");
  // a second start while running: refused, the job goes on
  EXPECT_FALSE(plc->write("cmd_start", 1).get().ok());
  // override by register: the kernel ramps to it
  ASSERT_TRUE(plc->write("feed_override_set_pct", 120).get().ok());
  EXPECT_TRUE(wait_for(*plc, "feed_override_pct", 120.0));
  // hold and resume by coil
  ASSERT_TRUE(plc->write("cmd_hold", 1).get().ok());
  ASSERT_TRUE(wait_for(*plc, "state", 2.0));  // feed hold
  ASSERT_TRUE(wait_machine_time(shm, 0.4));   // the ramp is over: at rest
  const double x_held = read(*plc, "x_mm");
  EXPECT_GT(x_held, 10.0);
  ASSERT_TRUE(wait_machine_time(shm, 0.1));
  EXPECT_EQ(read(*plc, "x_mm"), x_held);
  EXPECT_EQ(read(*plc, "laser_on"), 0.0);  // dark during a hold
  // the status agrees with the shm status, to the map's resolution (1 µm)
  EXPECT_NEAR(status(shm)["position"][0].get<double>(), x_held, 0.0005);
  ASSERT_TRUE(plc->write("cmd_resume", 1).get().ok());
  ASSERT_TRUE(wait_for(*plc, "state", 1.0));
  ASSERT_TRUE(plc->write("cmd_stop", 1).get().ok());
  ASSERT_TRUE(wait_for(*plc, "state", 0.0));
  EXPECT_EQ(status(shm)["job_active"], false);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

TEST(LasercncdModbus, HoleParameterBlockIsCheckedWholeAndRefusalsStoreNothing) {
  const std::string shm = shm_name("/lcnc_e2e_mb_");
  Daemon d(shm, {"--modbus", "tcp:127.0.0.1:0"});
  ASSERT_TRUE(d.ready()) << d.log();
  const int port = bound_port(d);
  ASSERT_GT(port, 0) << d.log();
  auto plc = master_for(port);
  std::vector<std::pair<std::string, double>> block = {
      {"hole_number", 7},          {"hole_x_mm", 120.5},     {"hole_y_mm", 80.25},
      {"hole_z_mm", 30},           {"hole_a_deg", -20},      {"hole_c_deg", 90},
      {"feed_mm_min", 600},        {"layer_feed_mm", 0.1},   {"layer_count", 10},
      {"total_depth_mm", 1.0},     {"laser_power_pct", 80},  {"scan_start_radius_mm", 0.5},
      {"scan_end_radius_mm", 0.3}, {"scan_radius_turns", 3}, {"scan_speed_mm_s", 200},
      {"wedge_speed_rpm", 3000},   {"beam_offset_mm", 0},    {"process_id", 0}};
  ASSERT_TRUE(plc->write_block(block).get().ok());
  EXPECT_EQ(read(*plc, "hole_number"), 7.0);
  EXPECT_EQ(read(*plc, "total_depth_mm"), 1.0);
  // depth ≠ layers × layer feed: the whole block refused, nothing stored
  block[0].second = 8;
  block[9].second = 1.2;
  const lcnc::Status s = plc->write_block(block).get();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("exception 04"), std::string::npos) << s.error().message;
  EXPECT_EQ(read(*plc, "hole_number"), 7.0);
  EXPECT_EQ(read(*plc, "total_depth_mm"), 1.0);
  EXPECT_NE(d.log().find("field 10 total depth"), std::string::npos) << d.log();
  // out of the map's range: exception 03 from the map itself
  EXPECT_FALSE(plc->write("hole_a_deg", 120).get().ok());
  EXPECT_EQ(read(*plc, "hole_a_deg"), -20.0);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

TEST(LasercncdModbus, BadEndpointIsAUsageError) {
  const std::string shm = shm_name("/lcnc_e2e_mb_");
  Daemon d(shm, {"--modbus", "udp:1502"});
  EXPECT_EQ(d.wait_exit(), 2);
  EXPECT_NE(d.log().find("expected tcp:HOST:PORT"), std::string::npos) << d.log();
}

}  // namespace
