#include "plan/planner.h"

namespace lcnc {

Planner::Planner(const MachineConfig& machine, SegmentSource source)
    : jerk_(lcnc::jerk_limit(machine)),
      budget_(lcnc::tolerance_budget(machine, jerk_.error_mm)),
      planned_(planned_machine(machine, jerk_)),
      blender_(machine, std::move(source), budget_),
      lookahead_(planned_, [this](const IndexedSegment*& s) { return blender_.next(s); }),
      holds_([this](const PlannedSegment*& p) { return planned(p); }, jerk_, machine.period_s()),
      interp_(machine, [this](const PlannedSegment*& p) { return holds_.next(p); }),
      filter_(jerk_.taps) {}

SourceStatus Planner::planned(const PlannedSegment*& out) {
  const SourceStatus st = lookahead_.next(out);
  if (st == SourceStatus::Item && on_planned_) on_planned_(*out);
  return st;
}

SourceStatus Planner::next_filtered(PeriodSample& out) {
  const SourceStatus st = interp_.next(out);
  if (st == SourceStatus::Item) out = filter_.filter(out);
  return st;
}

}  // namespace lcnc
