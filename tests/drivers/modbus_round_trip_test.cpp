// Round trips of every function code over RTU (pty pair, real libmodbus RTU
// framing and CRC) and TCP (loopback), and the slave's refusals: bad
// addresses (02), out-of-range values (03), read-only registers, half of a
// 32-bit register, the owner's veto — each leaving the values untouched.
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include <cerrno>

#include "modbus_test_support.h"

namespace lcnc::drivers {
namespace {

using namespace testing;

class ModbusRoundTrip : public ::testing::TestWithParam<Transport> {
 protected:
  void SetUp() override { pair_ = Pair::make(GetParam(), shipped("cnc")); }
  ModbusSlave& slave() { return *pair_->slave; }
  ModbusMaster& master() { return *pair_->master; }
  Result<RawReply> raw(Function fc, std::uint16_t addr, std::uint16_t count,
                       std::vector<std::uint16_t> data = {}) {
    return master().request(RawRequest{fc, addr, count, std::move(data), "test"}).get();
  }
  std::unique_ptr<Pair> pair_;
};

TEST_P(ModbusRoundTrip, Fc3ReadsHoldingRegisters) {
  ASSERT_TRUE(slave().set("hole_number", 42).ok());
  ASSERT_TRUE(slave().set("hole_x_mm", 123.456).ok());
  auto r = raw(Function::ReadHoldingRegisters, 0, 3);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  EXPECT_EQ(r.value(), (RawReply{42, 0x0001, 0xE240}));  // 123456 = 0x0001E240, high word first
  auto v = master().read("hole_x_mm").get();
  ASSERT_TRUE(v.ok());
  EXPECT_DOUBLE_EQ(v.value(), 123.456);
}

TEST_P(ModbusRoundTrip, Fc4ReadsInputRegistersPublishedByTheOwner) {
  slave().with_bank([](RegisterBank& b) {
    ASSERT_TRUE(b.set("state", 1).ok());
    ASSERT_TRUE(b.set("x_mm", -12.5).ok());
    ASSERT_TRUE(b.set("job_line", 3000000000.0).ok());
  });
  auto v = master().read_block({"state", "fault_code", "x_mm"}).get();
  ASSERT_TRUE(v.ok()) << v.error().to_string();
  EXPECT_EQ(v.value(), (std::vector<double>{1, 0, -12.5}));
  auto line = master().read("job_line").get();
  ASSERT_TRUE(line.ok());
  EXPECT_EQ(line.value(), 3000000000.0);
}

TEST_P(ModbusRoundTrip, Fc1AndFc2ReadBits) {
  ASSERT_TRUE(slave().set("cmd_hold", 1).ok());
  ASSERT_TRUE(slave().set("homed", 1).ok());
  ASSERT_TRUE(slave().set("fault", 1).ok());
  auto coils = raw(Function::ReadCoils, 0, 5);
  ASSERT_TRUE(coils.ok()) << coils.error().to_string();
  EXPECT_EQ(coils.value(), (RawReply{0, 1, 0, 0, 0}));
  auto inputs = raw(Function::ReadDiscreteInputs, 0, 4);
  ASSERT_TRUE(inputs.ok());
  EXPECT_EQ(inputs.value(), (RawReply{0, 1, 0, 1}));
  EXPECT_EQ(master().read("homed").get().value(), 1.0);
}

TEST_P(ModbusRoundTrip, Fc5WritesOneCoil) {
  ASSERT_TRUE(master().write("cmd_start", 1).get().ok());
  EXPECT_EQ(slave().get("cmd_start").value(), 1.0);
  ASSERT_TRUE(master().write("cmd_start", 0).get().ok());
  EXPECT_EQ(slave().get("cmd_start").value(), 0.0);
}

TEST_P(ModbusRoundTrip, Fc6WritesOneRegisterScaled) {
  const Status s = master().write("laser_power_pct", 37.25).get();
  ASSERT_TRUE(s.ok()) << s.error().to_string();
  EXPECT_DOUBLE_EQ(slave().get("laser_power_pct").value(), 37.25);
  auto raw16 = raw(Function::ReadHoldingRegisters, 16, 1);
  ASSERT_TRUE(raw16.ok());
  EXPECT_EQ(raw16.value()[0], 3725);                               // scale 100
  ASSERT_TRUE(master().write("beam_offset_mm", -1.5).get().ok());  // i16, negative
  EXPECT_DOUBLE_EQ(master().read("beam_offset_mm").get().value(), -1.5);
}

TEST_P(ModbusRoundTrip, Fc15WritesCoils) {
  auto r = raw(Function::WriteMultipleCoils, 1, 3, {1, 0, 1});
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  EXPECT_EQ(slave().get("cmd_hold").value(), 1.0);
  EXPECT_EQ(slave().get("cmd_resume").value(), 0.0);
  EXPECT_EQ(slave().get("cmd_stop").value(), 1.0);
  ASSERT_TRUE(master().write_block({{"cmd_reset", 1}, {"cmd_stop", 0}}).get().ok());
  EXPECT_EQ(slave().get("cmd_reset").value(), 1.0);
  EXPECT_EQ(slave().get("cmd_stop").value(), 0.0);
}

// The hole parameter block of docs/design.md §6, written at once (Shao 2022: FC16).
TEST_P(ModbusRoundTrip, Fc16WritesTheHoleParameterBlock) {
  const std::vector<std::pair<std::string, double>> block = {
      {"hole_number", 17},         {"hole_x_mm", 512.25},     {"hole_y_mm", 100.5},
      {"hole_z_mm", 20},           {"hole_a_deg", -45.5},     {"hole_c_deg", 359.999},
      {"feed_mm_min", 1500},       {"layer_feed_mm", 0.05},   {"layer_count", 20},
      {"total_depth_mm", 1},       {"laser_power_pct", 80},   {"scan_start_radius_mm", 0.2},
      {"scan_end_radius_mm", 0.4}, {"scan_radius_turns", 10}, {"scan_speed_mm_s", 2500.5},
      {"wedge_speed_rpm", 12000},  {"beam_offset_mm", 0.125}, {"process_id", 1}};
  const Status s = master().write_block(block).get();
  ASSERT_TRUE(s.ok()) << s.error().to_string();
  std::vector<std::string> names;
  for (const auto& [n, v] : block) names.push_back(n);
  auto back = master().read_block(names).get();
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  for (std::size_t i = 0; i < block.size(); ++i)
    EXPECT_NEAR(back.value()[i], block[i].second, 1e-9) << block[i].first;
}

TEST_P(ModbusRoundTrip, BadAddressGetsException02) {
  auto r = raw(Function::ReadHoldingRegisters, 26, 1);  // one past feed_override_set_pct
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::PeripheralException);
  EXPECT_NE(r.error().message.find("exception 02 (illegal data address)"), std::string::npos)
      << r.error().message;
  EXPECT_NE(r.error().message.find("cnc (unit 1"), std::string::npos) << r.error().message;
  EXPECT_FALSE(raw(Function::ReadInputRegisters, 18, 1).ok());  // past underruns
  EXPECT_FALSE(raw(Function::ReadCoils, 0, 6).ok());            // one past cmd_reset
  EXPECT_FALSE(raw(Function::WriteSingleCoil, 9, 1, {1}).ok());
  EXPECT_EQ(master().counters().exceptions, 4u);
}

// One bad value in a block: exception 03, and every register keeps its value.
TEST_P(ModbusRoundTrip, OutOfRangeBlockGetsException03AndChangesNothing) {
  ASSERT_TRUE(master().write_block({{"hole_number", 5}, {"hole_x_mm", 10}, {"hole_y_mm", 20}}).get().ok());
  // hole_y_mm = 451 mm (raw 451000) is beyond 450: the raw request bypasses
  // the master's own range check so that the slave's is tested.
  auto r =
      raw(Function::WriteMultipleRegisters, 0, 5, {6, 0x0000, 0x4E20 /*20 mm*/, 0x0006, 0xE1B8 /*451 mm*/});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("exception 03 (illegal data value)"), std::string::npos)
      << r.error().message;
  EXPECT_EQ(slave().get("hole_number").value(), 5.0);
  EXPECT_EQ(slave().get("hole_x_mm").value(), 10.0);
  EXPECT_EQ(slave().get("hole_y_mm").value(), 20.0);
  auto r6 = raw(Function::WriteSingleRegister, 24, 1, {3});  // process_id 3: 0…2
  ASSERT_FALSE(r6.ok());
  EXPECT_EQ(slave().get("process_id").value(), 0.0);
  EXPECT_EQ(slave().counters().refused_writes, 2u);
}

TEST_P(ModbusRoundTrip, MasterRefusesOutOfRangeBeforeTheWire) {
  const auto before = slave().counters().requests;
  const Status s = master().write("hole_a_deg", 96).get();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::PeripheralValueOutOfRange);
  EXPECT_NE(s.error().message.find("hole_a_deg = 96 deg is outside -95 … 95 deg"), std::string::npos)
      << s.error().message;
  const Status b = master().write_block({{"hole_number", 1}, {"hole_x_mm", 2000}}).get();
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().message.find("nothing sent"), std::string::npos);
  EXPECT_FALSE(master().write("state", 1).get().ok());  // input register: read-only
  EXPECT_FALSE(master().read("no_such_register").get().ok());
  EXPECT_EQ(slave().counters().requests, before);
}

TEST_P(ModbusRoundTrip, HalfOfA32BitRegisterOrAGapIsRefused) {
  ASSERT_TRUE(slave().set("hole_x_mm", 1).ok());
  EXPECT_FALSE(raw(Function::WriteSingleRegister, 1, 1, {0}).ok());        // high word of hole_x_mm
  EXPECT_FALSE(raw(Function::WriteMultipleRegisters, 2, 2, {0, 0}).ok());  // low word + next high
  EXPECT_EQ(slave().get("hole_x_mm").value(), 1.0);
}

TEST_P(ModbusRoundTrip, OwnersWriteHookCanVeto) {
  pair_.reset();
  pair_ = Pair::make(GetParam(), shipped("cnc"), [](ModbusSlave& s) {
    s.set_write_hook([](std::span<const RegisterWrite> w, RegisterBank&) {
      for (const RegisterWrite& x : w)
        if (x.reg->name == "cmd_start" && x.value != 0) return ModbusException::DeviceBusy;
      return ModbusException::None;
    });
  });
  const Status s = master().write("cmd_start", 1).get();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("exception 06 (server device busy)"), std::string::npos)
      << s.error().message;
  EXPECT_EQ(slave().get("cmd_start").value(), 0.0);
  EXPECT_TRUE(master().write("cmd_hold", 1).get().ok());
}

INSTANTIATE_TEST_SUITE_P(Transports, ModbusRoundTrip, ::testing::Values(Transport::Rtu, Transport::Tcp),
                         transport_name);

// Function codes outside 1–6, 15, 16 (here 22 and 23, sent with plain
// libmodbus) get exception 01 and change nothing.
TEST(ModbusSlave, OtherFunctionCodesGetException01) {
  ModbusSlave slave(shipped("cnc"), {});
  ASSERT_TRUE(slave.start().ok());
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", slave.port());
  ASSERT_NE(ctx, nullptr);
  ASSERT_EQ(modbus_connect(ctx), 0);
  std::uint16_t v = 7, back = 0;
  EXPECT_EQ(modbus_write_and_read_registers(ctx, 0, 1, &v, 0, 1, &back), -1);
  EXPECT_EQ(errno, EMBXILFUN);
  EXPECT_EQ(modbus_mask_write_register(ctx, 0, 0, 7), -1);
  EXPECT_EQ(errno, EMBXILFUN);
  modbus_close(ctx);
  modbus_free(ctx);
  EXPECT_EQ(slave.get("hole_number").value(), 1.0);
  EXPECT_EQ(slave.counters().exceptions, 2u);
}

// On a serial line the slave answers only its own unit id.
TEST(ModbusSlave, RtuIgnoresOtherUnits) {
  auto p = Pair::make(Transport::Rtu, shipped("cnc"), {}, [](MasterConfig& c) {
    c.unit_id = 9;
    c.retries = 0;
  });
  auto v = p->master->read("state").get();
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.error().code, ErrorCode::PeripheralTimeout);
  EXPECT_NE(v.error().message.find("cnc (unit 9, rtu"), std::string::npos) << v.error().message;
}

TEST(ModbusSlave, TcpBindsLoopbackOnAFreePort) {
  ModbusSlave a(shipped("power_meter"), {});
  ModbusSlave b(shipped("power_meter"), {});
  ASSERT_TRUE(a.start().ok());
  ASSERT_TRUE(b.start().ok());
  EXPECT_NE(a.port(), 0);
  EXPECT_NE(a.port(), b.port());
  EXPECT_EQ(a.endpoint().host, "127.0.0.1");
}

TEST(ModbusSlave, StopIsPrompt) {
  ModbusSlave s(shipped("power_meter"), {});
  ASSERT_TRUE(s.start().ok());
  std::this_thread::sleep_for(20ms);
  const auto t0 = std::chrono::steady_clock::now();
  s.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 100ms);
  EXPECT_FALSE(s.running());
}

TEST(ModbusSlave, BusyPortIsAClearError) {
  ModbusSlave a(shipped("power_meter"), {});
  ASSERT_TRUE(a.start().ok());
  SlaveConfig c;
  c.endpoint.port = a.port();
  ModbusSlave b(shipped("power_meter"), c);
  const Status s = b.start();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::PeripheralSetup);
  EXPECT_NE(s.error().message.find("cannot listen"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace lcnc::drivers
