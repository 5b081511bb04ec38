// Exact-stop planning (G61 semantics): every segment starts and ends at rest,
// with a trapezoid at the segment's own path limits (plan/segment_limits.h).
// Blending and look-ahead replace this for G64 (planner issue); exact stop
// stays what G61/G61.1 mean.
#pragma once

#include "machine/machine_config.h"
#include "plan/planned_segment.h"

namespace lcnc {

class ExactStopPlanner {
 public:
  ExactStopPlanner(const MachineConfig& machine, SegmentSource source);
  [[nodiscard]] SourceStatus next(PlannedSegment& out);

 private:
  const MachineConfig& machine_;
  SegmentSource source_;
  std::uint32_t count_ = 0;
};

// Plans one segment from rest to rest.
[[nodiscard]] PlannedSegment plan_rest_to_rest(const Segment& seg, const MachineConfig& machine,
                                               std::uint32_t index);

}  // namespace lcnc
