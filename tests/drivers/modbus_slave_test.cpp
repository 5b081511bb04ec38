// The TCP slave's service to several clients over real loopback sockets
// (127.0.0.1, a free port): a slow or idle client never keeps the others
// out, idle connections are closed, and the MBAP header is checked before a
// frame is taken (protocol id, length exactly the function's PDU, unit id).
// Every exchange is bounded in count and time.
#include "drivers/modbus/modbus_slave.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include "modbus_test_support.h"

namespace lcnc::drivers {
namespace {

using namespace testing;
using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;

constexpr std::uint8_t kCncUnit = 1;             // the shipped map's cnc device
constexpr std::uint16_t kOverrideRegister = 25;  // feed_override_set_pct, holding, u16

// An MBAP frame: transaction id, protocol id, length (unit + PDU), unit, PDU.
Bytes mbap(std::uint16_t tid, std::uint8_t unit, const Bytes& pdu, std::uint16_t protocol = 0) {
  const auto n = static_cast<std::uint16_t>(pdu.size() + 1);
  Bytes f;
  f.reserve(7 + pdu.size());
  for (std::uint16_t w : {tid, protocol, n}) {
    f.push_back(static_cast<std::uint8_t>(w >> 8));
    f.push_back(static_cast<std::uint8_t>(w));
  }
  f.push_back(unit);
  for (std::uint8_t b : pdu) f.push_back(b);
  return f;
}

const Bytes kReadOverride = {3, 0, kOverrideRegister, 0, 1};
Bytes write_override(std::uint8_t v) { return {6, 0, kOverrideRegister, 0, v}; }

// A raw Modbus TCP client on a blocking socket, every wait bounded by poll.
class Client {
 public:
  explicit Client(std::uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(port);
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa) == 0;
  }
  ~Client() { ::close(fd_); }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  [[nodiscard]] bool connected() const { return connected_; }

  bool send(const Bytes& b) {
    return ::send(fd_, b.data(), b.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(b.size());
  }

  // The next whole answer with transaction id `tid` (others, late answers
  // to earlier requests, are skipped), or empty after `limit` or on close.
  Bytes answer(std::uint16_t tid, std::chrono::milliseconds limit) {
    const auto end = Clock::now() + limit;
    for (;;) {
      while (pending_.size() >= 6) {
        const std::size_t size = 6 + ((pending_[4] << 8) | pending_[5]);
        if (pending_.size() < size) break;
        Bytes f(pending_.begin(), pending_.begin() + static_cast<long>(size));
        pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(size));
        if (((f[0] << 8) | f[1]) == tid) return f;
      }
      if (!fill(end)) return {};
    }
  }

  // True when the slave closed the connection within `limit` (bytes that
  // arrive meanwhile are kept for answer()).
  bool closed_within(std::chrono::milliseconds limit) {
    const auto end = Clock::now() + limit;
    while (!closed_)
      if (!fill(end) && !closed_) return false;
    return true;
  }

 private:
  // Reads what arrives before `end`; false on time-out or close.
  bool fill(Clock::time_point end) {
    if (closed_) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
    std::uint8_t buf[512];
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    if (n <= 0) {
      closed_ = true;  // orderly close or reset
      return false;
    }
    pending_.insert(pending_.end(), buf, buf + n);
    return true;
  }

  int fd_ = -1;
  bool connected_ = false;
  bool closed_ = false;
  Bytes pending_;
};

struct Served {
  std::unique_ptr<ModbusSlave> slave;
  explicit Served(SlaveConfig sc = {}) {
    slave = std::make_unique<ModbusSlave>(shipped("cnc"), sc);
    const Status s = slave->start();
    EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
    EXPECT_TRUE(slave->set("feed_override_set_pct", 120).ok());
  }
  std::uint16_t port() const { return slave->port(); }
  double override_pct() const { return slave->get("feed_override_set_pct").value(); }
};

// One client sends half a request, a byte at a time, and then nothing more
// while another polls 20 times: every poll is answered while the first
// request is still incomplete (a slave that waited for it would answer
// none). Then the rest of the trickled request arrives and is answered too.
// Ordered by events, not by time, so a loaded computer cannot change the
// verdict: the slave's frame timeouts are set out of the way (their own
// test is AFrameLeftUnfinishedClosesItsConnection) and each wait's limit
// only bounds a failure.
TEST(ModbusSlaveService, ATricklingClientDoesNotStopAnotherClientsPolls) {
  SlaveConfig sc;
  sc.byte_timeout = 60s;
  sc.frame_timeout = 60s;
  Served s(sc);
  Client poller(s.port()), trickler(s.port());
  ASSERT_TRUE(poller.connected() && trickler.connected());
  const Bytes trickled = mbap(1, kCncUnit, kReadOverride);
  const std::size_t half = trickled.size() / 2;
  for (std::size_t i = 0; i < half; ++i) ASSERT_TRUE(trickler.send({trickled[i]}));
  constexpr int kPolls = 20;
  int answered = 0;
  for (int i = 0; i < kPolls; ++i) {
    const auto tid = static_cast<std::uint16_t>(1000 + i);
    const Bytes want = {static_cast<std::uint8_t>(tid >> 8),
                        static_cast<std::uint8_t>(tid),
                        0,
                        0,
                        0,
                        5,
                        kCncUnit,
                        3,
                        2,
                        0,
                        120};
    ASSERT_TRUE(poller.send(mbap(tid, kCncUnit, kReadOverride)));
    if (poller.answer(tid, 5s) == want) ++answered;
  }
  EXPECT_EQ(answered, kPolls);
  // the rest of the trickled request: answered as well
  ASSERT_TRUE(trickler.send(Bytes(trickled.begin() + static_cast<std::ptrdiff_t>(half), trickled.end())));
  EXPECT_FALSE(trickler.answer(1, 5s).empty());
}

// The limit's worth of connections that never send a byte, then one more
// client: it is served, and the connection idle the longest (the first)
// is the one dropped to make room.
TEST(ModbusSlaveService, IdleConnectionsAtTheLimitDoNotLockOutANewClient) {
  SlaveConfig sc;
  sc.max_clients = 8;
  Served s(sc);
  std::vector<std::unique_ptr<Client>> idle;
  for (int i = 0; i < sc.max_clients; ++i) {
    idle.push_back(std::make_unique<Client>(s.port()));
    ASSERT_TRUE(idle.back()->connected());
    ASSERT_TRUE(eventually([&] { return s.slave->counters().connections == idle.size(); }, 1000ms));
  }
  Client late(s.port());
  ASSERT_TRUE(late.connected());
  ASSERT_TRUE(late.send(mbap(7, kCncUnit, kReadOverride)));
  const Bytes a = late.answer(7, 5000ms);
  std::printf("[ figures  ] a new client after %d idle connections: %s\n", sc.max_clients,
              a.empty() ? "not served" : "served");
  EXPECT_EQ(a, (Bytes{0, 7, 0, 0, 0, 5, kCncUnit, 3, 2, 0, 120}));
  EXPECT_TRUE(idle.front()->closed_within(5000ms));
  for (std::size_t i = 1; i < idle.size(); ++i) EXPECT_FALSE(idle[i]->closed_within(0ms)) << i;
  EXPECT_EQ(s.slave->counters().evicted, 1u);
}

// A connection silent for the idle timeout is closed; one that keeps
// polling through the same time is not. The timeout is long beside the polls'
// gaps (100 ms against 1.5 s), so a loaded computer that delays a poll does
// not close the busy one; each wait's limit only bounds a failure.
TEST(ModbusSlaveService, AnIdleConnectionIsClosedAfterTheIdleTimeout) {
  SlaveConfig sc;
  sc.idle_timeout = 1500ms;
  Served s(sc);
  const auto start = Clock::now();
  Client quiet(s.port()), busy(s.port());
  std::uint16_t tid = 0;
  while (!quiet.closed_within(100ms) && Clock::now() - start < 20s) {
    ++tid;
    ASSERT_TRUE(busy.send(mbap(tid, kCncUnit, kReadOverride)));
    ASSERT_FALSE(busy.answer(tid, 5000ms).empty()) << "poll " << tid;
  }
  EXPECT_TRUE(quiet.closed_within(0ms));
  EXPECT_GE(Clock::now() - start, sc.idle_timeout);  // not before its time
  EXPECT_GE(tid, 10);                                // the busy one polled through it, and is still served
  ASSERT_TRUE(busy.send(mbap(++tid, kCncUnit, kReadOverride)));
  EXPECT_FALSE(busy.answer(tid, 5000ms).empty());
  EXPECT_EQ(s.slave->counters().idle_closed, 1u);
}

// A frame begun and never finished does not hold its connection: it is
// closed after the inter-byte timeout.
TEST(ModbusSlaveService, AFrameLeftUnfinishedClosesItsConnection) {
  Served s;
  Client c(s.port());
  const Bytes f = mbap(1, kCncUnit, write_override(77));
  ASSERT_TRUE(c.send(Bytes(f.begin(), f.begin() + 5)));
  EXPECT_TRUE(c.closed_within(10000ms));  // bounds a failure only
  EXPECT_EQ(s.override_pct(), 120.0);
  EXPECT_EQ(s.slave->counters().frame_timeouts, 1u);
}

// One MBAP frame whose length covers a read and, after it, a whole second
// frame writing a register: the function's PDU is 5 bytes, the frame holds
// 17, so the length is wrong — exception 03 for the frame, nothing of the
// hidden write done, and the connection still in step.
TEST(ModbusSlaveService, AReadWithAWriteHiddenInItsLengthExecutesNothingHidden) {
  Served s;
  Client c(s.port());
  Bytes pdu = kReadOverride;
  const Bytes hidden = mbap(2, kCncUnit, write_override(77));
  pdu.insert(pdu.end(), hidden.begin(), hidden.end());
  ASSERT_TRUE(c.send(mbap(1, kCncUnit, pdu)));
  EXPECT_EQ(c.answer(1, 300ms), (Bytes{0, 1, 0, 0, 0, 3, kCncUnit, 0x83, 3}));
  EXPECT_TRUE(c.answer(2, 100ms).empty());  // the hidden one is not a request
  ASSERT_TRUE(c.send(mbap(3, kCncUnit, kReadOverride)));
  EXPECT_EQ(c.answer(3, 300ms), (Bytes{0, 3, 0, 0, 0, 5, kCncUnit, 3, 2, 0, 120}));
  EXPECT_EQ(s.override_pct(), 120.0);
  EXPECT_EQ(s.slave->counters().malformed, 1u);
}

// A length short of the function's PDU is exception 03 at once (the frame
// ends where its header says), not a wait for bytes that belong to no frame.
TEST(ModbusSlaveService, ALengthShortOfThePduIsException03) {
  Served s;
  Client c(s.port());
  ASSERT_TRUE(c.send(mbap(4, kCncUnit, {6, 0, kOverrideRegister})));
  EXPECT_EQ(c.answer(4, 300ms), (Bytes{0, 4, 0, 0, 0, 3, kCncUnit, 0x86, 3}));
  EXPECT_EQ(s.override_pct(), 120.0);
  EXPECT_EQ(s.slave->counters().malformed, 1u);
}

// A protocol id other than 0 (Modbus) is not taken: no answer, no write;
// the length still delimits the frame, so the next one is served.
TEST(ModbusSlaveService, AProtocolIdOtherThanModbusIsDropped) {
  Served s;
  Client c(s.port());
  ASSERT_TRUE(c.send(mbap(1, kCncUnit, write_override(77), /*protocol=*/1)));
  EXPECT_TRUE(c.answer(1, 200ms).empty());
  ASSERT_TRUE(c.send(mbap(2, kCncUnit, kReadOverride)));
  EXPECT_EQ(c.answer(2, 300ms), (Bytes{0, 2, 0, 0, 0, 5, kCncUnit, 3, 2, 0, 120}));
  EXPECT_EQ(s.override_pct(), 120.0);
  EXPECT_EQ(s.slave->counters().malformed, 1u);
}

// A length beyond the largest ADU (unit + 253-byte PDU) cannot be a Modbus
// frame, and the stream has no other boundary to find: the connection is
// closed without an answer.
TEST(ModbusSlaveService, ALengthBeyondTheLargestAduClosesTheConnection) {
  Served s;
  Client c(s.port());
  Bytes f = mbap(1, kCncUnit, kReadOverride);
  f[4] = 0x01;  // length 256 + 6
  ASSERT_TRUE(c.send(f));
  EXPECT_TRUE(c.closed_within(500ms));
  EXPECT_TRUE(c.answer(1, 0ms).empty());
  EXPECT_EQ(s.slave->counters().malformed, 1u);
}

// The unit id: the slave's own, or 0 / 255 (the Modbus TCP "this server");
// a frame for any other unit is ignored, as on a serial line.
TEST(ModbusSlaveService, AFrameForAnotherUnitIsIgnored) {
  Served s;
  Client c(s.port());
  ASSERT_TRUE(c.send(mbap(1, 9, write_override(77))));
  EXPECT_TRUE(c.answer(1, 200ms).empty());
  EXPECT_EQ(s.override_pct(), 120.0);
  for (std::uint8_t unit : {std::uint8_t{0}, std::uint8_t{255}, kCncUnit}) {
    ASSERT_TRUE(c.send(mbap(unit, unit, kReadOverride)));
    EXPECT_EQ(c.answer(unit, 300ms), (Bytes{0, unit, 0, 0, 0, 5, unit, 3, 2, 0, 120})) << int(unit);
  }
}

}  // namespace
}  // namespace lcnc::drivers
