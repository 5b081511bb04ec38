#include "plan/planner.h"

namespace lcnc {

Planner::Planner(const MachineConfig& machine, SegmentSource source)
    : blender_(machine, std::move(source)),
      lookahead_(machine, [this](IndexedSegment& s) { return blender_.next(s); }),
      interp_(machine, [this](PlannedSegment& p) {
        const SourceStatus st = lookahead_.next(p);
        if (st == SourceStatus::Item && on_planned_) on_planned_(p);
        return st;
      }) {}

SourceStatus Planner::next(PeriodSample& out) { return interp_.next(out); }

}  // namespace lcnc
