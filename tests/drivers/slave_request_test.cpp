// The slave's request handling fed raw frames (RawFrameLoop: libmodbus's
// receive and reply over a socket pair), the way the fuzz target feeds it;
// and where a TCP slave listens.
#include "drivers/modbus/slave_request.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <vector>

#include "drivers/modbus/modbus_slave.h"

namespace lcnc::drivers {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes tcp(std::uint16_t tid, Bytes pdu) {
  const auto n = static_cast<std::uint16_t>(pdu.size() + 1);
  pdu.insert(pdu.begin(), {static_cast<std::uint8_t>(tid >> 8), static_cast<std::uint8_t>(tid), 0, 0,
                           static_cast<std::uint8_t>(n >> 8), static_cast<std::uint8_t>(n), 1});
  return pdu;
}

struct Loop {
  SlaveRequestHandler handler{*shipped_device("cnc")};
  std::unique_ptr<RawFrameLoop> tcp_loop = std::move(RawFrameLoop::open(Transport::Tcp, 1)).value();
  std::unique_ptr<RawFrameLoop> rtu_loop = std::move(RawFrameLoop::open(Transport::Rtu, 1)).value();
  double get(const char* name) { return *handler.bank().get(name); }
};

TEST(SlaveRequest, AReadOfHoldingRegistersAnswersTheirValues) {
  Loop l;
  ASSERT_TRUE(l.handler.bank().set("feed_override_set_pct", 120).ok());
  const auto x = l.tcp_loop->deliver(l.handler, tcp(7, {3, 0, 25, 0, 1}));
  EXPECT_EQ(x.received.kind, Received::Kind::Answered);
  EXPECT_EQ(x.received.exception, ModbusException::None);
  // MBAP echoing transaction 7, fc 3, 2 bytes, the value 120
  EXPECT_EQ(x.reply, (Bytes{0, 7, 0, 0, 0, 5, 1, 3, 2, 0, 120}));
}

TEST(SlaveRequest, ABlockWithOneValueOutOfRangeIsRefusedWhole) {
  Loop l;
  const double number = l.get("hole_number"), x_mm = l.get("hole_x_mm");
  // hole_number 3 (ok), hole_x_mm 2000.000 mm (max 1000): exception 03
  const auto x = l.tcp_loop->deliver(l.handler, tcp(1, {16, 0, 0, 0, 3, 6, 0, 3, 0x00, 0x1E, 0x84, 0x80}));
  EXPECT_EQ(x.received.exception, ModbusException::IllegalDataValue);
  EXPECT_TRUE(x.received.write);
  EXPECT_EQ(x.reply, (Bytes{0, 1, 0, 0, 0, 3, 1, 0x90, 3}));
  EXPECT_EQ(l.get("hole_number"), number);  // untouched
  EXPECT_EQ(l.get("hole_x_mm"), x_mm);
  EXPECT_NE(number, 3.0);
}

// Found by the fuzz target: a request whose function code has the exception
// bit set (0x83) was answered by libmodbus as fc 0x83 + 0x80 = 0x03 (mod 256)
// — "03 03", which a master reads as a normal answer of function 3. It is
// not a request: no answer.
TEST(SlaveRequest, AFunctionCodeWithTheExceptionBitGetsNoAnswer) {
  Loop l;
  const auto x = l.tcp_loop->deliver(l.handler, tcp(1, {0x83, 0, 0, 0, 1}));
  EXPECT_EQ(x.received.kind, Received::Kind::NotARequest);
  EXPECT_TRUE(x.reply.empty());
  // and an unknown function below 0x80 still gets exception 01
  const auto y = l.tcp_loop->deliver(l.handler, tcp(2, {0x2B, 0x0E, 1, 0}));
  EXPECT_EQ(y.received.exception, ModbusException::IllegalFunction);
  EXPECT_EQ(y.reply, (Bytes{0, 2, 0, 0, 0, 3, 1, 0xAB, 1}));
}

TEST(SlaveRequest, RtuFramesAreCrcCheckedAndAddressed) {
  Loop l;
  const Bytes pdu = {6, 0, 25, 0, 90};  // feed_override_set_pct ← 90
  Bytes good = RawFrameLoop::rtu_frame(1, pdu);
  const auto x = l.rtu_loop->deliver(l.handler, good);
  EXPECT_EQ(x.received.exception, ModbusException::None);
  EXPECT_EQ(x.reply, good);  // fc 6 answers with the request itself
  EXPECT_EQ(l.get("feed_override_set_pct"), 90.0);

  Bytes bad = RawFrameLoop::rtu_frame(1, Bytes{6, 0, 25, 0, 50});
  bad.back() ^= 0x01;
  EXPECT_EQ(l.rtu_loop->deliver(l.handler, bad).received.kind, Received::Kind::BadCrc);
  EXPECT_EQ(l.rtu_loop->deliver(l.handler, RawFrameLoop::rtu_frame(2, Bytes{6, 0, 25, 0, 50})).received.kind,
            Received::Kind::OtherUnit);
  EXPECT_EQ(l.get("feed_override_set_pct"), 90.0);
}

TEST(SlaveRequest, AFrameCutShortChangesNothingAndGetsNoAnswer) {
  Loop l;
  Bytes f = tcp(1, {6, 0, 25, 0, 77});
  f.pop_back();
  const auto x = l.tcp_loop->deliver(l.handler, f);
  EXPECT_EQ(x.received.kind, Received::Kind::Broken);
  EXPECT_TRUE(x.reply.empty());
  EXPECT_EQ(l.get("feed_override_set_pct"), 0.0);
}

// The MBAP length delimits a TCP frame; what the function needs is
// checked against it when the frame is answered.
TEST(SlaveRequest, ATcpFrameIsCutWhereItsMbapLengthSays) {
  using K = TcpFrameCut::Kind;
  const Bytes read = tcp(1, {3, 0, 25, 0, 1});
  EXPECT_EQ(cut_tcp_frame(Bytes(read.begin(), read.end() - 1)).kind, K::NeedMore);
  Bytes two = read;
  two.insert(two.end(), read.begin(), read.end());
  EXPECT_EQ(cut_tcp_frame(two).kind, K::Frame);
  EXPECT_EQ(cut_tcp_frame(two).size, read.size());
  Bytes foreign = read;
  foreign[3] = 1;  // protocol id 1
  EXPECT_EQ(cut_tcp_frame(foreign).kind, K::Foreign);
  EXPECT_EQ(cut_tcp_frame(foreign).size, read.size());
  EXPECT_EQ(cut_tcp_frame(Bytes{0, 1, 0, 0, 0, 1, 1}).kind, K::Foreign);  // no function code
  EXPECT_EQ(cut_tcp_frame(Bytes{0, 1, 0, 0, 0, 255}).kind, K::Unframeable);
  EXPECT_EQ(request_pdu_length(Bytes{3, 0, 25, 0, 1}), 5u);
  EXPECT_EQ(request_pdu_length(Bytes{16, 0, 0, 0, 2, 4, 0, 1, 0, 2}), 10u);
  EXPECT_EQ(request_pdu_length(Bytes{16, 0, 0}), 6u);
  EXPECT_EQ(request_pdu_length(Bytes{0x2B, 0x0E}), 0u);  // not implemented: 01 needs no length
}

// Through the frame loop (the fuzz target's path): a read whose length
// hides a write behind it is exception 03, and the write is not done.
TEST(SlaveRequest, AReadWithTrailingBytesIsException03) {
  Loop l;
  Bytes pdu = {3, 0, 25, 0, 1};
  const Bytes hidden = tcp(2, {6, 0, 25, 0, 77});
  pdu.insert(pdu.end(), hidden.begin(), hidden.end());
  const auto x = l.tcp_loop->deliver(l.handler, tcp(1, pdu));
  EXPECT_EQ(x.received.exception, ModbusException::IllegalDataValue);
  EXPECT_EQ(x.reply, (Bytes{0, 1, 0, 0, 0, 3, 1, 0x83, 3}));
  EXPECT_EQ(l.get("feed_override_set_pct"), 0.0);
  EXPECT_EQ(l.handler.counts().malformed, 1u);
}

// A slave configured with nothing but a port listens on the loopback
// interface only: from this host's own outside address nothing answers.
TEST(SlaveSecurity, ATcpSlaveListensOnLoopbackUnlessConfigured) {
  ModbusSlave slave(*shipped_device("cnc"), SlaveConfig{});
  ASSERT_TRUE(slave.start().ok());
  EXPECT_EQ(slave.endpoint().host, "127.0.0.1");
  auto connects = [&](in_addr a) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(slave.port());
    sa.sin_addr = a;
    const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&sa), sizeof sa) == 0;
    ::close(fd);
    return ok;
  };
  in_addr lo{};
  lo.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_TRUE(connects(lo));
  ifaddrs* ifs = nullptr;
  ASSERT_EQ(::getifaddrs(&ifs), 0);
  int outside = 0;
  for (ifaddrs* i = ifs; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET) continue;
    const in_addr a = reinterpret_cast<sockaddr_in*>(i->ifa_addr)->sin_addr;
    if ((ntohl(a.s_addr) >> 24) == 127) continue;
    ++outside;
    EXPECT_FALSE(connects(a)) << "reachable on " << i->ifa_name;
  }
  ::freeifaddrs(ifs);
  if (outside == 0) GTEST_SKIP() << "this host has no address but loopback to try from";
}

}  // namespace
}  // namespace lcnc::drivers
