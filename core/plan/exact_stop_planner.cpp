#include "plan/exact_stop_planner.h"

#include "plan/segment_limits.h"

namespace lcnc {

PlannedSegment plan_rest_to_rest(const Segment& seg, const MachineConfig& machine,
                                 std::uint32_t index) {
  PlannedSegment p{seg, SegmentGeometry(seg), {}, 0.0, index};
  if (seg.kind == MotionKind::Dwell) {
    p.profile = Trapezoid::hold(seg.dwell_s);
    return p;
  }
  const SegmentLimits lim = segment_limits(seg, p.geo, machine);
  p.programmed_speed = target_speed(seg, p.geo, lim);
  p.profile = Trapezoid::plan(p.geo.length(), lim.a_max, 0.0, p.programmed_speed, 0.0);
  return p;
}

ExactStopPlanner::ExactStopPlanner(const MachineConfig& machine, SegmentSource source)
    : machine_(machine), source_(std::move(source)) {}

SourceStatus ExactStopPlanner::next(PlannedSegment& out) {
  Segment seg;
  const SourceStatus st = source_(seg);
  if (st != SourceStatus::Item) return st;
  out = plan_rest_to_rest(seg, machine_, count_++);
  return SourceStatus::Item;
}

}  // namespace lcnc
