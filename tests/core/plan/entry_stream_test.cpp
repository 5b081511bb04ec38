#include "plan/entry_stream.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/plan/test_machine.h"

namespace lcnc {
namespace {

Segment line_to(Pose& at, double x, double y) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.feed_mm_s = 80.0;
  s.path_mode = PathMode::ExactStop;
  s.start = at;
  at[0] = x;
  at[1] = y;
  s.end = at;
  return s;
}

SegmentSource over(const std::vector<Segment>& segs, std::size_t& i, bool fail_at_end = false) {
  return [&segs, &i, fail_at_end](Segment& out) {
    if (i == segs.size()) return fail_at_end ? SourceStatus::Error : SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  };
}

struct Drained {
  std::vector<PeriodIncrement> entries;
  EntryStream::Next end = EntryStream::Next::Entry;
  std::array<std::int64_t, kAxisCount> sum{};
};

Drained drain(EntryStream& stream) {
  Drained d;
  PeriodIncrement inc;
  while ((d.end = stream.next(inc)) == EntryStream::Next::Entry) {
    d.entries.push_back(inc);
    for (int i = 0; i < kAxisCount; ++i) d.sum[i] += inc.steps[i];
  }
  return d;
}

// The entries of a plan add up to where it ends, in whole steps, and each
// carries the ramp room the RT's override ramp needs (a moving entry's is
// bounded, a hand-built one's is not).
TEST(EntryStream, EntriesSumToTheCommandedPositionAndCarryTheirRampRoom) {
  const MachineConfig m = testing::test_machine(100.0, 2000.0);
  Pose at = Pose::Zero();
  at << 10, 10, 5, 0, 0, 0;
  const Pose start = at;
  std::vector<Segment> segs = {line_to(at, 30.0012345, 10), line_to(at, 30.0012345, 22.5432109)};
  std::size_t i = 0;
  Planner planner(m, over(segs, i));
  EntryStream stream(m, planner, start);
  const Drained d = drain(stream);
  ASSERT_EQ(d.end, EntryStream::Next::End);
  EXPECT_EQ(stream.entries(), d.entries.size());
  for (int a = 0; a < kAxisCount; ++a) {
    EXPECT_EQ(d.sum[a], stream.commanded(a) - stream.start_steps(a)) << a;
    if (m.axes[a].present) {
      EXPECT_EQ(stream.commanded(a), std::llround(at[a] * m.axes[a].steps_per_unit)) << a;
    }
  }
  bool bounded = false;
  for (const PeriodIncrement& e : d.entries) bounded = bounded || e.ramp.r0 < 1e30f;
  EXPECT_TRUE(bounded);
  PeriodIncrement more;
  EXPECT_EQ(stream.next(more), EntryStream::Next::End);  // and stays ended
}

// A plan with no motion still ends the job in a controlled way: one entry,
// at rest, laser off, marked as the end.
TEST(EntryStream, APlanWithoutMotionGivesOneEndEntry) {
  const MachineConfig m = testing::test_machine();
  std::vector<Segment> none;
  std::size_t i = 0;
  Planner planner(m, over(none, i));
  EntryStream stream(m, planner, Pose::Zero());
  const Drained d = drain(stream);
  ASSERT_EQ(d.entries.size(), 1u);
  EXPECT_TRUE(d.entries[0].end_of_program);
  EXPECT_EQ(d.entries[0].power_pct, 0.0f);
  for (int a = 0; a < kAxisCount; ++a) EXPECT_EQ(d.entries[0].steps[a], 0);
  EXPECT_EQ(d.end, EntryStream::Next::End);
}

// A source that fails mid-way: the motion before it ends at rest, its steps
// all paid, and then the stream says Error.
TEST(EntryStream, ASourceErrorEndsTheMotionBeforeItThenSaysSo) {
  const MachineConfig m = testing::test_machine(100.0, 2000.0);
  Pose at = Pose::Zero();
  at << 10, 10, 5, 0, 0, 0;
  const Pose start = at;
  std::vector<Segment> segs = {line_to(at, 40.0000004, 10)};
  std::size_t i = 0;
  Planner planner(m, over(segs, i, true));
  EntryStream stream(m, planner, start);
  const Drained d = drain(stream);
  EXPECT_EQ(d.end, EntryStream::Next::Error);
  EXPECT_EQ(d.sum[0], std::llround(30.0000004 * 1000.0));
}

// The guard is part of the chain: a segment built in code that leaves the
// travel is refused before its first step beyond it, and nothing more is
// handed out.
TEST(EntryStream, AnEntryBeyondTheTravelIsRefusedAndTheStreamStops) {
  const MachineConfig m = testing::test_machine(100.0, 2000.0);  // X 0 … 1000
  Pose at = Pose::Zero();
  at << 990, 10, 5, 0, 0, 0;
  const Pose start = at;
  std::vector<Segment> segs = {line_to(at, 1010, 10)};
  std::size_t i = 0;
  Planner planner(m, over(segs, i));
  EntryStream stream(m, planner, start);
  const Drained d = drain(stream);
  ASSERT_EQ(d.end, EntryStream::Next::Limit);
  EXPECT_EQ(stream.limit_error().code, ErrorCode::RtSoftLimit) << stream.limit_error().to_string();
  EXPECT_LE(990000 + d.sum[0], 1000000);
  EXPECT_GT(990000 + d.sum[0], 999000);  // it got there, and no further
  PeriodIncrement more;
  EXPECT_EQ(stream.next(more), EntryStream::Next::Limit);
}

}  // namespace
}  // namespace lcnc
