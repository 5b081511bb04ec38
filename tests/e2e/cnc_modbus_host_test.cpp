// The daemon's Modbus host in pieces: the --modbus endpoint, the status as
// the map publishes it, and the hole block's whole-block check.
#include "app/cnc_modbus_host.h"

#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

#include <spdlog/spdlog.h>

#include "drivers/modbus/endpoint_spec.h"
#include "drivers/modbus/modbus_master.h"
#include "drivers/modbus/register_map.h"
#include "rt/rt_kernel.h"

namespace lcnc::app {
namespace {

TEST(ModbusEndpoint, TcpAndRtuFormsAndTheirErrors) {
  Result<drivers::Endpoint> e = drivers::parse_endpoint("tcp:127.0.0.1:1502");
  ASSERT_TRUE(static_cast<bool>(e));
  EXPECT_EQ(e->transport, drivers::Transport::Tcp);
  EXPECT_EQ(e->host, "127.0.0.1");
  EXPECT_EQ(e->port, 1502);
  e = drivers::parse_endpoint("rtu:/dev/ttyUSB0:19200:E");
  ASSERT_TRUE(static_cast<bool>(e));
  EXPECT_EQ(e->transport, drivers::Transport::Rtu);
  EXPECT_EQ(e->device, "/dev/ttyUSB0");
  EXPECT_EQ(e->baud, 19200);
  EXPECT_EQ(e->parity, 'E');
  e = drivers::parse_endpoint("rtu:/dev/pts/3");
  ASSERT_TRUE(static_cast<bool>(e));
  EXPECT_EQ(e->baud, 115200);
  EXPECT_EQ(e->parity, 'N');
  for (const char* bad : {"tcp:1502", "tcp:127.0.0.1:70000", "tcp:host:x", "rtu:", "rtu:/dev/x:0",
                          "rtu:/dev/x:9600:Q", "udp:1:2", ""}) {
    const Result<drivers::Endpoint> r = drivers::parse_endpoint(bad);
    ASSERT_FALSE(static_cast<bool>(r)) << bad;
    EXPECT_EQ(r.error().code, ErrorCode::Usage) << bad;
    EXPECT_NE(r.error().message.find("expected tcp:HOST:PORT"), std::string::npos) << bad;
  }
}

TEST(ModbusSnapshot, MapsTheKernelStatus) {
  shm::Status st;
  st.state = shm::MachineState::FeedHold;
  st.pos = {100.5, 20.25, 3, -45, 7, 359.5};
  st.axes_mask = 0b101111;
  st.homed_mask = 0b001111;  // C not homed
  st.feed_override = 1.2;
  st.line = 42;
  st.buffer_fill = static_cast<std::uint32_t>(rt::kPositionBufferCapacity / 4);
  st.power_pct = 0.0f;
  drivers::CncStatusSnapshot s = to_snapshot(st, st.axes_mask);
  EXPECT_EQ(s.state, 2);
  EXPECT_EQ(s.position[0], 100.5);
  EXPECT_EQ(s.position[3], -45.0);  // A
  EXPECT_EQ(s.position[4], 359.5);  // C, not B
  EXPECT_DOUBLE_EQ(s.feed_override_pct, 120.0);
  EXPECT_EQ(s.job_line, 42u);
  EXPECT_DOUBLE_EQ(s.buffer_fill_pct, 25.0);
  EXPECT_FALSE(s.homed);
  EXPECT_FALSE(s.laser_on);
  EXPECT_FALSE(s.estop);
  st.homed_mask = 0b111111;  // B's bit does not matter: the machine has no B
  st.power_pct = 40.0f;
  st.state = shm::MachineState::EStop;
  st.fault = 402;
  s = to_snapshot(st, st.axes_mask);
  EXPECT_TRUE(s.homed);
  EXPECT_TRUE(s.laser_on);
  EXPECT_TRUE(s.estop);
  EXPECT_TRUE(s.fault);
  EXPECT_EQ(s.fault_code, 402);
}

// The record's defaults (feed 600 mm/min, layer feed 0.1 mm, 3000 rpm, no
// beam offset, helix) with a hole of its own.
drivers::HoleParameters good_block() {
  drivers::HoleParameters p;
  p.hole_number = 3;
  p.position << 100, 50, 20, 0, 0, 0;
  p.layer_count = 5;
  p.total_depth_mm = 0.5;
  p.power_pct = 60;
  p.head.start_radius_mm = p.head.end_radius_mm = 0.4;
  p.head.radius_turns = 2;
  p.head.scan_speed_mm_s = 100;
  return p;
}

TEST(HoleBlock, CheckedAsTheHoleProcessesNeedIt) {
  drivers::HoleParameters p = good_block();
  EXPECT_TRUE(check_hole_block(p).ok());
  p.total_depth_mm = 0.6;
  const Status s = check_hole_block(p);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("hole 3: field 10"), std::string::npos) << s.error().message;
  // a free shape's polygon comes from the process DB: the rest is checked
  p = good_block();
  p.process = HoleProcessId::FreeShape;
  EXPECT_TRUE(check_hole_block(p).ok());
  p.layer_feed_mm = 0.0;
  EXPECT_FALSE(check_hole_block(p).ok());
}

}  // namespace
}  // namespace lcnc::app

namespace lcnc::app {
namespace {

// A master's command waits in the slave's write hook for the control thread
// (drain()); the control thread's publish must not wait for the slave in
// turn — or both wait until the hook gives up and the command is refused.
TEST(CncModbusHost, PublishingNeverWaitsForACommandInFlight) {
  drivers::Endpoint ep;  // TCP 127.0.0.1, a free port
  Result<std::unique_ptr<CncModbusHost>> host = CncModbusHost::start(ep, spdlog::default_logger());
  ASSERT_TRUE(static_cast<bool>(host)) << host.error().to_string();
  auto map = drivers::shipped_device("cnc");
  ASSERT_TRUE(static_cast<bool>(map));
  drivers::MasterConfig mc;
  mc.endpoint = (*host)->endpoint();
  mc.response_timeout = std::chrono::milliseconds(3000);
  drivers::ModbusMaster plc(*map, mc);
  ASSERT_TRUE(plc.start().ok());
  std::future<Status> hold = plc.write("cmd_hold", 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the command now waits in the hook
  shm::Status st;
  const auto t0 = std::chrono::steady_clock::now();
  const bool published = (*host)->publish(st);
  // a publish that waited would return when the hook gives up (kCommandWait,
  // ~900 ms from here); the bound leaves room for a loaded machine's scheduling
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(400));
  EXPECT_FALSE(published);  // busy: try again later
  int taken = 0;
  (*host)->drain([&](const shm::Command& c) {
    EXPECT_EQ(c.type, shm::CommandType::Hold);
    ++taken;
    return Ack{true, ErrorCode::Internal, "hold"};
  });
  EXPECT_EQ(taken, 1);
  EXPECT_TRUE(hold.get().ok());
  // the slave lets go of its bank once it has answered (it may still be
  // finishing the reply as the master reads it): publishing succeeds then
  bool later = false;
  for (int i = 0; i < 200 && !later; ++i) {
    later = (*host)->publish(st);
    if (!later) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(later);
  plc.stop();
}

}  // namespace
}  // namespace lcnc::app
