#include "plan/planner.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/plan/test_machine.h"

namespace lcnc {
namespace {

// The facade chains every stage: G64 corners come out blended, G61 ones
// stopped, and every planned segment is observable.
TEST(Planner, ChainsMergerBlenderLookaheadAndInterpolator) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::vector<Segment> segs(2);
  for (int k = 0; k < 2; ++k) {
    segs[k].kind = MotionKind::Linear;
    segs[k].feed_mm_s = 50.0;
    segs[k].path_mode = PathMode::Blend;
    segs[k].blend_tolerance_mm = 0.01;
  }
  segs[0].start << 10, 10, 5, 0, 0, 0;
  segs[0].end << 20, 10, 5, 0, 0, 0;
  segs[1].start = segs[0].end;
  segs[1].end << 20, 20, 5, 0, 0, 0;
  std::size_t i = 0;
  Planner planner(m, [&](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  });
  std::vector<MotionKind> kinds;
  planner.on_planned([&](const PlannedSegment& p) { kinds.push_back(p.seg.kind); });
  PeriodSample s;
  PeriodSample last;
  while (planner.next(s) == SourceStatus::Item) last = s;
  EXPECT_TRUE(last.end_of_program);
  EXPECT_EQ(last.pose, segs[1].end);
  ASSERT_EQ(kinds.size(), 3u);  // line, blend arc, line
  EXPECT_EQ(kinds[1], MotionKind::Arc);
  EXPECT_EQ(planner.periods(), static_cast<std::uint64_t>(std::llround(last.t_s / m.period_s())));
}

}  // namespace
}  // namespace lcnc
