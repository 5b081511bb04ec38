// The 3D probe's RS-232 line protocol: checksums as NMEA computes them,
// every malformed line rejected with its column and what was expected, and
// the client against the simulated probe over a real pty — including a
// corrupted answer that must be rejected and asked for again.
#include "drivers/serial/probe_protocol.h"

#include <gtest/gtest.h>

#include "drivers/devices/probe_3d_sim.h"
#include "drivers/serial/probe_client.h"
#include "modbus_test_support.h"

namespace lcnc::drivers {
namespace {

using namespace probe;

TEST(ProbeProtocol, ChecksumIsTheXorOfTheBodyAsInNmea) {
  // A textbook NMEA 0183 sentence and its published checksum.
  EXPECT_EQ(checksum("GPGLL,5300.97914,N,00259.98174,E,125926,A"), 0x28);
  EXPECT_EQ(frame("MEAS,7"), "$MEAS,7*01\r\n");
  EXPECT_EQ(encode(PointReply{7, 512.25, 100.5, 20.0131}), "$POS,7,512.2500,100.5000,20.0131*51\r\n");
}

TEST(ProbeProtocol, EveryMessageRoundTrips) {
  const std::vector<Message> all = {MeasureRequest{65535}, PingRequest{}, PointReply{3, -1.5, 0, 499.9999},
                                    ErrorReply{4, ProbeError::NoSurface, "no surface in range"},
                                    PongReply{"M", "2.1"}};
  for (const Message& m : all) {
    auto back = decode(encode(m));
    ASSERT_TRUE(back.ok()) << encode(m) << ": " << back.error().to_string();
    EXPECT_EQ(back->index(), m.index());
    EXPECT_EQ(encode(back.value()), encode(m));
  }
  EXPECT_TRUE(decode("$ERR,8,2,busy*7e\r\n").ok());  // lower-case hex is accepted
}

struct BadLine {
  const char* line;
  ErrorCode code;
  std::uint32_t col;
  const char* expect;
};

class ProbeProtocolRejects : public ::testing::TestWithParam<BadLine> {};

TEST_P(ProbeProtocolRejects, WithColumnAndReason) {
  const BadLine& c = GetParam();
  auto m = decode(c.line, "/dev/ttyS1");
  ASSERT_FALSE(m.ok()) << c.line;
  EXPECT_EQ(m.error().code, c.code) << m.error().to_string();
  EXPECT_EQ(m.error().file, "/dev/ttyS1");
  EXPECT_EQ(m.error().col, c.col) << m.error().to_string();
  EXPECT_NE(m.error().message.find(c.expect), std::string::npos) << m.error().to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ProbeProtocolRejects,
    ::testing::Values(
        BadLine{"$MEAS,7*02\r\n", ErrorCode::SerialChecksum, 9, "checksum *02 does not match the body's *01"},
        BadLine{"MEAS,7*01\r\n", ErrorCode::SerialSyntax, 1, "does not start with '$'"},
        BadLine{"$MEAS,7\r\n", ErrorCode::SerialSyntax, 8, "does not end in '*HH'"},
        BadLine{"$MEAS,7*0G\r\n", ErrorCode::SerialSyntax, 9, "is not two hex digits"},
        BadLine{"$MEAS,7*01", ErrorCode::SerialSyntax, 11, "does not end in CR LF"},
        BadLine{"$ME\x07S,7*41\r\n", ErrorCode::SerialSyntax, 4, "byte '\\x07' not allowed"},
        BadLine{"$MEAS,0*06\r\n", ErrorCode::SerialSyntax, 2, "$MEAS: id '0' is not an integer 1 … 65535"},
        BadLine{"$POS,1,2,3*50\r\n", ErrorCode::SerialSyntax, 2, "expected 4 fields (id, x, y, z), found 3"},
        BadLine{"$POS,1,2,y,4*02\r\n", ErrorCode::SerialSyntax, 2, "y 'y' is not a number"},
        BadLine{"$FOO*46\r\n", ErrorCode::SerialSyntax, 2, "unknown sentence type"}));

TEST(ProbeProtocol, OverlongLineIsRejected) {
  const std::string body = "ERR,1,3," + std::string(80, 'x');
  auto m = decode(frame(body));
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("at most 82"), std::string::npos);
}

// The client and the simulated probe over a pty.
class ProbeOverPty : public ::testing::Test {
 protected:
  void SetUp() override {
    Probe3dParams p;
    p.latency = std::chrono::milliseconds(1);
    auto sim = Probe3dSim::create(testing::shipped("probe_3d"), {}, p);
    ASSERT_TRUE(sim.ok()) << sim.error().to_string();
    sim_ = std::move(sim.value());
    ASSERT_TRUE(sim_->start().ok());
    ProbeClientConfig c;
    c.device = sim_->serial_path();
    c.timeout = std::chrono::milliseconds(200);
    client_ = std::make_unique<ProbeClient>(testing::shipped("probe_3d"), c);
    const Status s = client_->open();
    ASSERT_TRUE(s.ok()) << s.error().to_string();
  }
  std::unique_ptr<Probe3dSim> sim_;
  std::unique_ptr<ProbeClient> client_;
};

TEST_F(ProbeOverPty, MeasuresThePointOnTheSurface) {
  const double x = 250, y = 120;
  const double z = sim_->surface().z_at(x, y);
  sim_->set_position(x, y, z + 3);
  auto p = client_->measure();
  ASSERT_TRUE(p.ok()) << p.error().to_string();
  EXPECT_EQ(p->x_mm, x);
  EXPECT_EQ(p->y_mm, y);
  EXPECT_NEAR(p->z_mm, z, 0.006);  // σ = 1 µm noise, 4-decimal transport
  auto pong = client_->ping();
  ASSERT_TRUE(pong.ok()) << pong.error().to_string();
  EXPECT_EQ(pong->model, "LCNC-SIM-PROBE3D");
  auto async = client_->measure_async().get();
  EXPECT_TRUE(async.ok());
}

TEST_F(ProbeOverPty, NoSurfaceInReachIsADeviceError) {
  sim_->set_position(10, 10, sim_->surface().z_at(10, 10) + 50);
  auto p = client_->measure();
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::PeripheralException);
  EXPECT_NE(p.error().message.find("no surface in range (code 1"), std::string::npos) << p.error().message;
  EXPECT_EQ(client_->counters().device_errors, 1u);
}

TEST_F(ProbeOverPty, CorruptedAnswerIsRejectedAndAskedAgain) {
  sim_->corrupt_next_answer();
  auto p = client_->measure();
  ASSERT_TRUE(p.ok()) << p.error().to_string();
  const ProbeCounters c = client_->counters();
  EXPECT_EQ(c.checksum_errors, 1u);
  EXPECT_EQ(c.requests, 2u);
  EXPECT_EQ(sim_->serial_requests(), 2u);
}

TEST_F(ProbeOverPty, ProbeAnswersABadRequestInsteadOfStayingSilent) {
  SerialPort raw;
  ASSERT_TRUE(raw.open(sim_->serial_path(), 115200).ok());
  ASSERT_TRUE(raw.write_all("$MEAS,7*00\r\n").ok());
  auto line = raw.read_line(std::chrono::milliseconds(500));
  ASSERT_TRUE(line.ok()) << line.error().to_string();
  auto m = decode(line.value());
  ASSERT_TRUE(m.ok());
  const auto* e = std::get_if<ErrorReply>(&m.value());
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->code, ProbeError::BadRequest);
  EXPECT_EQ(e->text, "bad checksum");
}

TEST(ProbeClient, SilentPortTimesOutWithinItsBound) {
  auto pty = open_pty();
  ASSERT_TRUE(pty.ok());
  ProbeClientConfig c;
  c.device = pty->path;
  c.timeout = std::chrono::milliseconds(50);
  c.retries = 1;
  ProbeClient client(testing::shipped("probe_3d"), c);
  ASSERT_TRUE(client.open().ok());
  const auto t0 = std::chrono::steady_clock::now();
  auto p = client.measure();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(400));
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::PeripheralTimeout);
  EXPECT_NE(p.error().message.find("no answer within 50 ms (2 attempts)"), std::string::npos)
      << p.error().message;
  close_pty(pty.value());
}

}  // namespace
}  // namespace lcnc::drivers
