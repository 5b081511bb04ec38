#include "machine/feed_override_percent.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace lcnc {
namespace {

// One rule for every entry point: a live controller takes 0 (a hold), a run
// from start to end at least 1 %; both at most 100 × max_feed_override.
TEST(OverrideFromPercent, OneRuleWithEachUsesLowestValue) {
  EXPECT_DOUBLE_EQ(*override_from_percent(0.0, kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override"),
                   0.0);
  EXPECT_DOUBLE_EQ(*override_from_percent(150.0, kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override"),
                   1.5);
  EXPECT_DOUBLE_EQ(*override_from_percent(1.0, kMinRunOverridePct, 1.5, ErrorCode::Usage, "--feed-override"),
                   0.01);
  const Result<double> zero_run =
      override_from_percent(0.0, kMinRunOverridePct, 1.5, ErrorCode::Usage, "--feed-override");
  ASSERT_FALSE(zero_run);
  EXPECT_EQ(zero_run.error().code, ErrorCode::Usage);
  EXPECT_NE(zero_run.error().message.find("--feed-override 0 refused: allowed 1 <= PCT <= 150"),
            std::string::npos)
      << zero_run.error().message;
  for (const double bad : {150.001, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const Result<double> k =
        override_from_percent(bad, kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override");
    ASSERT_FALSE(k) << bad;
    EXPECT_EQ(k.error().code, ErrorCode::RtRefused);
    EXPECT_NE(k.error().message.find("allowed 0 <= PCT <= 150"), std::string::npos) << k.error().message;
  }
  // every K a live controller may hold passes back through its percent
  for (const double k : {0.0, 0.01, 0.1, 0.7, 1.0, 1.1, 1.2}) {
    const Result<double> again =
        override_from_percent(k * 100.0, kMinLiveOverridePct, 1.2, ErrorCode::RtRefused, "o");
    ASSERT_TRUE(again) << k;
  }
}

// The fraction on the wire (the shm command) by the same rule, its message in
// percent as a person reads it.
TEST(CheckOverride, TakesTheFractionAndNamesTheRangeInPercent) {
  EXPECT_DOUBLE_EQ(*check_override(1.5, kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override"), 1.5);
  EXPECT_DOUBLE_EQ(*check_override(0.0, kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override"), 0.0);
  const Result<double> high = check_override(2.0, kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override");
  ASSERT_FALSE(high);
  EXPECT_NE(high.error().message.find("override 200 refused: allowed 0 <= PCT <= 150"), std::string::npos)
      << high.error().message;
  EXPECT_FALSE(check_override(0.005, kMinRunOverridePct, 1.5, ErrorCode::Usage, "run"));
  EXPECT_FALSE(check_override(std::nan(""), kMinLiveOverridePct, 1.5, ErrorCode::RtRefused, "override"));
}

}  // namespace
}  // namespace lcnc
