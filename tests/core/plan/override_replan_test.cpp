// The feed override raised and lowered at random periods while a program of
// random arcs and lines, laser on and off, is planned: every period's
// increment stays within the increment guard (no axis past its velocity or
// acceleration limit in one period). The program is the one a soak of
// random jobs under random overrides stopped on (2026-12-03): two raises in
// a row while the look-ahead's window was empty started the next segment
// from the speed of an earlier release, 72 mm/s, after a stop — X jumped by
// 53 mm/s in one period. The schedule below (seed 1) hits it in its 15th
// trial.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "common/share_path.h"
#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "plan/coarse_interpolator.h"
#include "plan/increment_guard.h"
#include "plan/planner.h"
#include "plan/program_source.h"

namespace lcnc {
namespace {

TEST(OverrideReplan, RandomRaisesAndDropsKeepEveryIncrementWithinTheGuard) {
  Result<MachineConfig> m = load_machine_config(share_path("machines/default.toml"));
  ASSERT_TRUE(static_cast<bool>(m)) << m.error().to_string();
  std::ifstream in(std::string(LCNC_SOURCE_DIR) + "/tests/core/plan/data/override_soak.ngc");
  std::stringstream text;
  text << in.rdbuf();
  ASSERT_GT(text.str().size(), 10'000u);
  std::mt19937 rng(1);
  // the overrides an operator sets; the planner plans for those above 100 %
  // (as the daemon's planner thread does: a raise, or a drop from above 100 %)
  const double choices[] = {0.0, 0.1, 0.5, 0.8, 1.0, 1.2, 1.5};
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE(trial);
    ReaderOptions o;
    auto reader = ProgramReader::from_string(text.str(), "override_soak.ngc", *m, o);
    ASSERT_TRUE(reader);
    Planner planner(*m, reader_source(*reader));
    StepQuantizer q(*m, o.start);
    std::array<std::int64_t, kAxisCount> start{};
    for (int i = 0; i < kAxisCount; ++i) start[i] = q.commanded(i);
    IncrementGuard guard(*m, start);
    PeriodSample s;
    std::uint64_t n = 0, next_change = rng() % 3000, changes = 0;
    while (planner.next(s) == SourceStatus::Item) {
      ASSERT_TRUE(guard.admit(q.quantize(s))) << "period " << n << ": " << guard.error().to_string();
      if (++n == next_change) {
        const double asked = choices[rng() % 7];
        if (asked > planner.feed_scale() || (asked < planner.feed_scale() && planner.feed_scale() > 1.0)) {
          planner.set_feed_scale(asked);
          ++changes;
        }
        next_change = n + 1 + rng() % 3000;
      }
    }
    EXPECT_GT(changes, 50u);
  }
}

}  // namespace
}  // namespace lcnc
