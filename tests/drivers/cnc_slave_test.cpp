// The CNC's slave as a PLC or MES sees it: published status, commands by
// coil (accepted, refused), the hole parameter block handed to the owner
// whole, and refusals that store nothing.
#include "drivers/modbus/cnc_slave.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <vector>

#include "modbus_test_support.h"

namespace lcnc::drivers {
namespace {

using namespace testing;

class CncSlaveTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto made = CncSlave::create(shipped("cnc"));
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    cnc_ = std::move(made.value());
    cnc_->on_command([this](CncCommand c, double v) -> Status {
      std::lock_guard lock(mutex_);
      commands_.emplace_back(c, v);
      if (c == CncCommand::Start && refuse_start_)
        return make_error(ErrorCode::RtRefused, "start refused: no job loaded");
      return {};
    });
    cnc_->on_parameters([this](const HoleParameters& p) -> Status {
      std::lock_guard lock(mutex_);
      blocks_.push_back(p);
      if (p.hole_number == 9999) return make_error(ErrorCode::RtRefused, "hole 9999 is locked");
      return {};
    });
    ASSERT_TRUE(cnc_->start().ok());
    master_ = std::make_unique<ModbusMaster>(shipped("cnc"), quick_master(cnc_->endpoint()));
    ASSERT_TRUE(master_->start().ok());
  }
  std::unique_ptr<CncSlave> cnc_;
  std::unique_ptr<ModbusMaster> master_;
  std::mutex mutex_;
  std::vector<std::pair<CncCommand, double>> commands_;
  std::vector<HoleParameters> blocks_;
  std::atomic<bool> refuse_start_{false};  // test thread → slave thread
};

TEST_F(CncSlaveTest, PublishesStatusWhole) {
  CncStatusSnapshot s;
  s.state = 1;
  s.position = {512.25, 100.5, 20, -45.5, 359.999};
  s.feed_override_pct = 120;
  s.job_line = 1234567;
  s.homed = true;
  s.laser_on = true;
  ASSERT_TRUE(cnc_->publish(s).ok());
  auto v = master_
               ->read_block({"state", "fault_code", "x_mm", "y_mm", "z_mm", "a_deg", "c_deg",
                             "feed_override_pct", "job_line"})
               .get();
  ASSERT_TRUE(v.ok()) << v.error().to_string();
  EXPECT_EQ(v.value(), (std::vector<double>{1, 0, 512.25, 100.5, 20, -45.5, 359.999, 120, 1234567}));
  auto bits = master_->read_block({"estop", "homed", "laser_on", "fault"}).get();
  ASSERT_TRUE(bits.ok());
  EXPECT_EQ(bits.value(), (std::vector<double>{0, 1, 1, 0}));

  CncStatusSnapshot bad = s;
  bad.state = 2;
  bad.position[0] = 20000;  // beyond the map's ±10000 mm
  const Status st = cnc_->publish(bad);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("x_mm = 20000 outside"), std::string::npos) << st.error().message;
  EXPECT_EQ(master_->read("state").get().value(), 1.0);  // nothing of it published
}

TEST_F(CncSlaveTest, CommandsReachTheOwnerAndRefusalsAreException04) {
  ASSERT_TRUE(master_->write("cmd_hold", 1).get().ok());
  ASSERT_TRUE(master_->write("feed_override_set_pct", 80).get().ok());
  refuse_start_ = true;
  const Status s = master_->write("cmd_start", 1).get();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("exception 04"), std::string::npos) << s.error().message;
  EXPECT_EQ(master_->read("cmd_start").get().value(), 0.0);
  {
    std::lock_guard lock(mutex_);
    ASSERT_EQ(commands_.size(), 3u);
    EXPECT_EQ(commands_[0].first, CncCommand::Hold);
    EXPECT_EQ(commands_[1], std::make_pair(CncCommand::SetOverride, 80.0));
    EXPECT_EQ(commands_[2].first, CncCommand::Start);
  }
  // An accepted command's coil is cleared once taken.
  EXPECT_TRUE(eventually([&] { return master_->read("cmd_hold").get().value() == 0.0; }));
}

TEST_F(CncSlaveTest, ParameterBlockIsHandedOverWhole) {
  ASSERT_TRUE(
      master_->write_block({{"hole_number", 12}, {"hole_x_mm", 100}, {"hole_y_mm", 200}, {"hole_z_mm", 30}})
          .get()
          .ok());
  ASSERT_TRUE(master_->write("laser_power_pct", 55.5).get().ok());  // a partial write
  {
    std::lock_guard lock(mutex_);
    ASSERT_EQ(blocks_.size(), 2u);
    const HoleParameters& p = blocks_.back();
    EXPECT_EQ(p.hole_number, 12u);  // merged with what was stored
    EXPECT_EQ(p.position[1], 200.0);
    EXPECT_EQ(p.power_pct, 55.5);
    EXPECT_EQ(p.head.radius_turns, 1u);
  }
  // The owner refuses: exception 04, nothing stored.
  const Status s = master_->write_block({{"hole_number", 9999}, {"hole_x_mm", 1}}).get();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("exception 04"), std::string::npos);
  const HoleParameters now = cnc_->parameters();
  EXPECT_EQ(now.hole_number, 12u);
  EXPECT_EQ(now.position[0], 100.0);
  EXPECT_EQ(now.power_pct, 55.5);
}

TEST(CncSlave, NeedsTheCncMap) {
  auto made = CncSlave::create(shipped("laser_source"));
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.error().message.find("map of device 'laser_source'"), std::string::npos);
}

}  // namespace
}  // namespace lcnc::drivers
