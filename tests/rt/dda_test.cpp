#include "rt/dda.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace lcnc::rt {
namespace {

std::array<std::int32_t, kAxisCount> one_axis(std::int32_t n) {
  std::array<std::int32_t, kAxisCount> s{};
  s[0] = n;
  return s;
}

// The closed form in Dda::run_period equals the tick-by-tick definition for
// every magnitude, over many periods (accumulator carried), for several
// presets: tabulated (≤ kTabulatedMaxPulses) and computed per period (12 bits).
TEST(Dda, ClosedFormMatchesTickLoopForEveryMagnitude) {
  static_assert(Dda::kTabulatedMaxPulses < 4095);
  const DdaConfig presets[] = {{4, 30}, {8, 300}, {6, 64}, {3, 7}, {10, 1100}, {12, 5000}};
  std::mt19937 rng(7);
  for (const DdaConfig& cfg : presets) {
    Dda dda(cfg);
    std::uint32_t ref_acc = cfg.capacity / 2;
    PulseFrame frame;
    for (int period = 0; period < 2000; ++period) {
      const auto n = static_cast<std::int32_t>(rng() % (cfg.max_pulses() + 1));
      const std::int32_t s = (rng() & 1) ? n : -n;
      dda.run_period(one_axis(s), frame);
      std::vector<std::uint32_t> ref;
      Dda::reference_period(cfg.capacity, ref_acc, static_cast<std::uint32_t>(n), ref);
      ASSERT_EQ(frame.axes[0].count, ref.size()) << "N=" << cfg.capacity << " n=" << n;
      for (std::size_t j = 0; j < ref.size(); ++j)
        ASSERT_EQ(frame.axes[0].ticks[j], ref[j]) << "N=" << cfg.capacity << " n=" << n;
      EXPECT_EQ(frame.axes[0].negative, s < 0);
      EXPECT_EQ(dda.accumulator(), ref_acc);  // the reference ends where it began
    }
  }
}

TEST(Dda, SeedPresetSpreadsFifteenPulsesEvenly) {
  Dda dda(DdaConfig{4, 30});
  PulseFrame frame;
  dda.run_period(one_axis(15), frame);
  ASSERT_EQ(frame.axes[0].count, 15u);
  // preset N/2 = 15: the first pulse on tick 0, then every second tick
  for (std::uint32_t j = 0; j < 15; ++j) EXPECT_EQ(frame.axes[0].ticks[j], 2 * j);
  dda.run_period(one_axis(1), frame);
  ASSERT_EQ(frame.axes[0].count, 1u);
  EXPECT_EQ(frame.axes[0].ticks[0], 14u);  // half-way through the period
}

TEST(Dda, EveryPeriodEmitsExactlyItsMagnitude) {
  Dda dda(DdaConfig{8, 300});
  PulseFrame frame;
  std::mt19937 rng(11);
  for (int k = 0; k < 10000; ++k) {
    std::array<std::int32_t, kAxisCount> s{};
    for (auto& v : s) v = static_cast<std::int32_t>(rng() % 511) - 255;
    dda.run_period(s, frame);
    for (int a = 0; a < kAxisCount; ++a) {
      EXPECT_EQ(frame.axes[a].count, static_cast<std::uint32_t>(std::abs(s[a])));
      for (std::uint32_t j = 0; j < frame.axes[a].count; ++j) {
        EXPECT_LT(frame.axes[a].ticks[j], 300u);
        if (j > 0) {
          EXPECT_GT(frame.axes[a].ticks[j], frame.axes[a].ticks[j - 1]);
        }
      }
    }
  }
}

}  // namespace
}  // namespace lcnc::rt
