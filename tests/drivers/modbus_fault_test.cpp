// Faults on the Modbus link (DESIGN §8): corrupted bytes on the RTU line (a
// PtyLink flips a bit in the next frame), a pulled cable, a device gone and
// back, a device that accepts and never answers, exception answers. Each must
// be reported with a clear message, recovered from automatically, and never
// hang the caller.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "modbus_test_support.h"

namespace lcnc::drivers {
namespace {

using namespace testing;
using Clock = std::chrono::steady_clock;

std::unique_ptr<Pair> rtu_pair(std::function<void(MasterConfig&)> tune = {}) {
  auto p = Pair::make(Transport::Rtu, shipped("laser_source"), {}, std::move(tune));
  EXPECT_TRUE(p->slave->set("power_setpoint_pct", 12.5).ok());
  return p;
}

TEST(ModbusFaults, RtuCorruptedAnswerIsCountedAndRetried) {
  auto p = rtu_pair();
  p->link->corrupt_next(LinkDirection::BtoA);  // byte 3 of the next answer
  auto v = p->master->read("power_setpoint_pct").get();
  ASSERT_TRUE(v.ok()) << v.error().to_string();
  EXPECT_EQ(v.value(), 12.5);
  EXPECT_EQ(p->link->corruptions(), 1u);
  const MasterCounters c = p->master->counters();
  EXPECT_EQ(c.crc_errors, 1u);
  EXPECT_EQ(c.retries, 1u);
  EXPECT_EQ(c.ok, 1u);
}

TEST(ModbusFaults, RtuCorruptedAnswerWithoutRetriesIsAClearError) {
  auto p = rtu_pair([](MasterConfig& c) { c.retries = 0; });
  p->link->corrupt_next(LinkDirection::BtoA);
  auto v = p->master->read("power_setpoint_pct").get();
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.error().code, ErrorCode::PeripheralCorrupted);
  EXPECT_NE(v.error().message.find("laser_source (unit 2, rtu /dev/pts/"), std::string::npos)
      << v.error().message;
  EXPECT_NE(v.error().message.find("read power_setpoint_pct: answer with a bad CRC (1 attempt)"),
            std::string::npos)
      << v.error().message;
  EXPECT_EQ(p->master->last_error(), v.error().message);
  // The line is flushed: the next request goes through.
  EXPECT_TRUE(p->master->read("power_setpoint_pct").get().ok());
}

TEST(ModbusFaults, RtuCorruptedRequestIsDroppedByTheSlaveAndRetried) {
  auto p = rtu_pair();
  p->link->corrupt_next(LinkDirection::AtoB);
  const Status s = p->master->write("power_setpoint_pct", 50).get();
  ASSERT_TRUE(s.ok()) << s.error().to_string();
  EXPECT_EQ(p->slave->counters().crc_errors, 1u);
  EXPECT_EQ(p->master->counters().timeouts, 1u);  // the slave stayed silent
  EXPECT_EQ(p->slave->get("power_setpoint_pct").value(), 50.0);
}

TEST(ModbusFaults, RtuPulledCableTimesOutThenRecovers) {
  auto p = rtu_pair([](MasterConfig& c) { c.retries = 0; });
  p->link->set_connected(false);
  for (int i = 0; i < 3; ++i) {  // rtu_reopen_after = 3: the port is reopened
    const auto t0 = Clock::now();
    auto v = p->master->read("status").get();
    ASSERT_FALSE(v.ok());
    EXPECT_EQ(v.error().code, ErrorCode::PeripheralTimeout);
    EXPECT_NE(v.error().message.find("read status: no answer within 150 ms"), std::string::npos)
        << v.error().message;
    EXPECT_LT(Clock::now() - t0, 600ms);  // bounded by the timeout, never a hang
  }
  p->link->set_connected(true);
  ASSERT_TRUE(eventually([&] { return p->master->read("status").get().ok(); }));
  const MasterCounters c = p->master->counters();
  EXPECT_EQ(c.timeouts, 3u);
  EXPECT_EQ(c.reconnects, 1u);  // the port was closed and reopened
}

// The device on the serial line is switched off and on again.
TEST(ModbusFaults, RtuDeviceGoneAndBack) {
  auto p = rtu_pair([](MasterConfig& c) { c.retries = 0; });
  ASSERT_TRUE(p->master->read("status").get().ok());
  p->slave.reset();  // off
  auto gone = p->master->read("status").get();
  ASSERT_FALSE(gone.ok());
  EXPECT_EQ(gone.error().code, ErrorCode::PeripheralTimeout);
  SlaveConfig sc;
  sc.endpoint.transport = Transport::Rtu;
  sc.endpoint.device = p->link->b_path();
  p->slave = std::make_unique<ModbusSlave>(shipped("laser_source"), sc);  // on again
  ASSERT_TRUE(p->slave->start().ok());
  ASSERT_TRUE(p->slave->set("power_setpoint_pct", 77).ok());
  ASSERT_TRUE(eventually([&] {
    auto v = p->master->read("power_setpoint_pct").get();
    return v.ok() && v.value() == 77.0;
  }));
}

TEST(ModbusFaults, TcpDeviceGoneAndBack) {
  const DeviceMap map = shipped("power_meter");
  auto slave = std::make_unique<ModbusSlave>(map, SlaveConfig{});
  ASSERT_TRUE(slave->start().ok());
  const std::uint16_t port = slave->port();
  Endpoint ep;
  ep.port = port;
  ModbusMaster master(map, quick_master(ep));
  ASSERT_TRUE(master.start().ok());
  ASSERT_TRUE(master.write("wavelength_nm", 1030).get().ok());
  EXPECT_TRUE(master.connected());

  slave.reset();  // switched off
  const auto t0 = Clock::now();
  auto gone = master.read("wavelength_nm").get();
  ASSERT_FALSE(gone.ok());
  EXPECT_LT(Clock::now() - t0, 500ms);
  EXPECT_EQ(gone.error().code, ErrorCode::PeripheralDisconnected);
  EXPECT_NE(gone.error().message.find("power_meter (unit 3, tcp 127.0.0.1:" + std::to_string(port)),
            std::string::npos)
      << gone.error().message;
  EXPECT_NE(gone.error().message.find("cannot connect: Connection refused"), std::string::npos)
      << gone.error().message;
  EXPECT_FALSE(master.connected());
  // While it stays away, requests fail at once instead of queueing.
  auto fast = master.read("wavelength_nm").get();
  EXPECT_FALSE(fast.ok());

  SlaveConfig back;
  back.endpoint.port = port;  // switched on again, same address
  slave = std::make_unique<ModbusSlave>(map, back);
  ASSERT_TRUE(slave->start().ok());
  ASSERT_TRUE(slave->set("wavelength_nm", 515).ok());
  ASSERT_TRUE(eventually([&] {
    auto v = master.read("wavelength_nm").get();
    return v.ok() && v.value() == 515.0;
  }));
  EXPECT_TRUE(master.connected());
  EXPECT_EQ(master.counters().reconnects, 1u);
  EXPECT_GE(master.counters().link_errors, 1u);
}

// A device that accepts the connection and never answers.
TEST(ModbusFaults, TcpSilentDeviceTimesOutAfterItsRetries) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(fd, 4), 0);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  Endpoint ep;
  ep.port = ntohs(a.sin_port);
  ModbusMaster master(shipped("scan_head"), quick_master(ep));
  ASSERT_TRUE(master.start().ok());
  const auto t0 = Clock::now();
  auto v = master.read("status").get();
  const auto took = Clock::now() - t0;
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.error().code, ErrorCode::PeripheralTimeout);
  EXPECT_NE(v.error().message.find("no answer within 150 ms (3 attempts)"), std::string::npos)
      << v.error().message;
  EXPECT_GE(took, 400ms);
  EXPECT_LT(took, 1000ms);
  EXPECT_EQ(master.counters().timeouts, 3u);
  ::close(fd);
}

TEST(ModbusFaults, ExceptionIsFinalAndNamed) {
  auto p = Pair::make(Transport::Tcp, shipped("laser_source"));
  auto r = p->master->request({Function::ReadInputRegisters, 40, 1, {}, "read input 40"}).get();
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::PeripheralException);
  EXPECT_NE(r.error().message.find("read input 40: exception 02 (illegal data address)"),
            std::string::npos)
      << r.error().message;
  EXPECT_EQ(p->master->counters().retries, 0u);  // the device has spoken: no retry
  EXPECT_TRUE(p->master->read("status").get().ok());
}

TEST(ModbusFaults, CallerNeverBlocksWhileTheLinkIsDown) {
  auto p = rtu_pair([](MasterConfig& c) {
    c.retries = 0;
    c.queue_capacity = 4;
  });
  p->link->set_connected(false);
  std::atomic<int> answered{0}, refused{0};
  const auto t0 = Clock::now();
  for (int i = 0; i < 8; ++i)
    p->master->read_async("status", [&](Result<double> v) {
      (v.ok() ? answered : (v.error().code == ErrorCode::PeripheralStopped ? refused : answered))++;
    });
  EXPECT_LT(Clock::now() - t0, 100ms);  // eight submissions, no wait on the wire (8 × 150 ms)
  EXPECT_GE(refused.load(), 3);        // beyond the queue's capacity: refused at once
  p->master->stop();                   // the queued ones fail with PeripheralStopped
  EXPECT_EQ(answered.load() + refused.load(), 8);
  auto after = p->master->read("status").get();
  ASSERT_FALSE(after.ok());
  EXPECT_NE(after.error().message.find("master stopped"), std::string::npos);
}

TEST(ModbusFaults, NoDeviceAtAllIsAClearErrorAtOnce) {
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);  // find a free port, then free it
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  Endpoint ep;
  ep.port = ntohs(a.sin_port);
  ModbusMaster master(shipped("laser_source"), quick_master(ep));
  ASSERT_TRUE(master.start().ok());
  const Status s = master.write("enable", 1).get();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::PeripheralDisconnected);
  EXPECT_NE(s.error().message.find("write enable = 1"), std::string::npos) << s.error().message;

  Endpoint rtu;
  rtu.transport = Transport::Rtu;
  rtu.device = "/dev/nonexistent-tty";
  ModbusMaster serial(shipped("laser_source"), quick_master(rtu));
  ASSERT_TRUE(serial.start().ok());
  auto v = serial.read("status").get();
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.error().message.find("rtu /dev/nonexistent-tty"), std::string::npos);
  EXPECT_NE(v.error().message.find("cannot connect"), std::string::npos) << v.error().message;
}

}  // namespace
}  // namespace lcnc::drivers
