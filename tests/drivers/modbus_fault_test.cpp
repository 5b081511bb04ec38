// Faults on the Modbus link (docs/design.md §8): corrupted bytes on the RTU line (a
// PtyLink flips a bit in the next frame), a pulled cable, a device gone and
// back, a device that accepts and never answers, exception answers. Each must
// be reported with a clear message, recovered from automatically, and never
// hang the caller.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <future>
#include <random>

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
  EXPECT_NE(r.error().message.find("read input 40: exception 02 (illegal data address)"), std::string::npos)
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
  EXPECT_GE(refused.load(), 3);         // beyond the queue's capacity: refused at once
  p->master->stop();                    // the queued ones fail with PeripheralStopped
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

namespace lcnc::drivers {
namespace {

using namespace testing;

// Waits for a request's answer, failing (never hanging) past `limit`.
template <typename T>
T answer(std::future<T> f, std::chrono::milliseconds limit = 3000ms) {
  if (f.wait_for(limit) != std::future_status::ready) {
    ADD_FAILURE() << "a request hung past " << limit.count() << " ms";
    std::abort();  // the master would outlive the test: nothing sane to go on with
  }
  return f.get();
}

// The soak: LCNC_SOAK_FAULTS faults (CI: 40; RELIABILITY.md: 1,000) drawn
// at random from five kinds, on an RTU link (a pty pair through a PtyLink)
// and a TCP link (loopback): a corrupted answer, a corrupted request, a
// pulled cable, an exception answer, the TCP device switched off and on.
// After each: the fault showed as its kind (error code, counters moved as
// that kind moves them), nothing hung, the link answers again. At the end
// the master's counters add up.
TEST(ModbusFaults, SoakOfInjectedFaultsEveryLinkRecoversAndTheCountersAddUp) {
  const char* env = std::getenv("LCNC_SOAK_FAULTS");
  const int faults = env != nullptr ? std::atoi(env) : 40;
  auto fast = [](MasterConfig& c) {
    c.response_timeout = 300ms;  // far above a loaded ASan run's answer times
    c.retries = 1;
  };
  auto rtu = Pair::make(Transport::Rtu, shipped("laser_source"), {}, fast);
  const DeviceMap meter = shipped("power_meter");
  auto tcp_slave = std::make_unique<ModbusSlave>(meter, SlaveConfig{});
  ASSERT_TRUE(tcp_slave->start().ok());
  const std::uint16_t port = tcp_slave->port();
  Endpoint ep;
  ep.port = port;
  MasterConfig mc = quick_master(ep);
  fast(mc);
  ModbusMaster tcp(meter, mc);
  ASSERT_TRUE(tcp.start().ok());
  ASSERT_TRUE(answer(tcp.read("wavelength_nm")).ok());

  std::mt19937 rng(2026);
  int kinds[5] = {};
  const auto t0 = Clock::now();
  for (int i = 0; i < faults; ++i) {
    const int kind = static_cast<int>(rng() % 5);
    ++kinds[kind];
    SCOPED_TRACE("fault " + std::to_string(i) + " of kind " + std::to_string(kind));
    const MasterCounters r0 = rtu->master->counters(), t0c = tcp.counters();
    const SlaveCounters s0 = rtu->slave->counters();
    switch (kind) {
      case 0: {  // a corrupted answer: the CRC check catches it, the retry gets it
        rtu->link->corrupt_next(LinkDirection::BtoA);
        ASSERT_TRUE(answer(rtu->master->read("power_setpoint_pct")).ok());
        const MasterCounters r = rtu->master->counters();
        EXPECT_EQ(r.crc_errors - r0.crc_errors, 1u);
        EXPECT_EQ(r.retries - r0.retries, 1u);
        break;
      }
      case 1: {  // a corrupted request: the slave drops it, the master times out and retries
        rtu->link->corrupt_next(LinkDirection::AtoB);
        const double v = static_cast<double>(rng() % 100);
        ASSERT_TRUE(answer(rtu->master->write("power_setpoint_pct", v)).ok());
        EXPECT_EQ(rtu->slave->counters().crc_errors - s0.crc_errors, 1u);
        EXPECT_EQ(rtu->master->counters().timeouts - r0.timeouts, 1u);
        EXPECT_EQ(rtu->slave->get("power_setpoint_pct").value(), v);
        break;
      }
      case 2: {  // the cable pulled for one request, then plugged in again
        rtu->link->set_connected(false);
        const Result<double> gone = answer(rtu->master->read("status"));
        ASSERT_FALSE(gone.ok());
        EXPECT_EQ(gone.error().code, ErrorCode::PeripheralTimeout);
        EXPECT_EQ(rtu->master->counters().timeouts - r0.timeouts, 2u);  // both attempts
        rtu->link->set_connected(true);
        ASSERT_TRUE(eventually([&] { return answer(rtu->master->read("status")).ok(); }));
        break;
      }
      case 3: {  // an exception answer: final, no retry
        const auto r = answer(tcp.request({Function::ReadInputRegisters, 40, 1, {}, "read input 40"}));
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().code, ErrorCode::PeripheralException);
        const MasterCounters t = tcp.counters();
        EXPECT_EQ(t.exceptions - t0c.exceptions, 1u);
        EXPECT_EQ(t.retries - t0c.retries, 0u);
        break;
      }
      case 4: {  // the TCP device switched off, then on again at the same address
        tcp_slave.reset();
        const Result<double> gone = answer(tcp.read("wavelength_nm"));
        ASSERT_FALSE(gone.ok());
        EXPECT_EQ(gone.error().code, ErrorCode::PeripheralDisconnected);
        SlaveConfig back;
        back.endpoint.port = port;
        tcp_slave = std::make_unique<ModbusSlave>(meter, back);
        ASSERT_TRUE(tcp_slave->start().ok());
        ASSERT_TRUE(eventually([&] { return answer(tcp.read("wavelength_nm")).ok(); }));
        EXPECT_EQ(tcp.counters().reconnects - t0c.reconnects, 1u);
        break;
      }
    }
    // whatever came before, both links answer now
    ASSERT_TRUE(answer(rtu->master->read("power_setpoint_pct")).ok());
    ASSERT_TRUE(answer(tcp.read("wavelength_nm")).ok());
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  for (const MasterCounters& c : {rtu->master->counters(), tcp.counters()}) {
    EXPECT_EQ(c.requests, c.ok + c.failed);
    EXPECT_EQ(c.refused, 0u);
  }
  const MasterCounters r = rtu->master->counters(), t = tcp.counters();
  std::printf(
      "modbus soak: %d faults (answer corrupted %d, request corrupted %d, cable pulled %d, "
      "exception %d, device off/on %d) in %.1f s; 0 hangs; RTU master %llu requests, %llu ok, "
      "%llu crc errors, %llu timeouts, %llu retries; TCP master %llu requests, %llu ok, "
      "%llu exceptions, %llu link errors, %llu reconnects\n",
      faults, kinds[0], kinds[1], kinds[2], kinds[3], kinds[4], seconds,
      static_cast<unsigned long long>(r.requests), static_cast<unsigned long long>(r.ok),
      static_cast<unsigned long long>(r.crc_errors), static_cast<unsigned long long>(r.timeouts),
      static_cast<unsigned long long>(r.retries), static_cast<unsigned long long>(t.requests),
      static_cast<unsigned long long>(t.ok), static_cast<unsigned long long>(t.exceptions),
      static_cast<unsigned long long>(t.link_errors), static_cast<unsigned long long>(t.reconnects));
  EXPECT_EQ(rtu->link->corruptions(), static_cast<std::uint64_t>(kinds[0] + kinds[1]));
  EXPECT_GE(r.crc_errors, static_cast<std::uint64_t>(kinds[0]));
  EXPECT_EQ(t.exceptions, static_cast<std::uint64_t>(kinds[3]));
  EXPECT_EQ(t.reconnects, static_cast<std::uint64_t>(kinds[4]));
}

}  // namespace
}  // namespace lcnc::drivers
