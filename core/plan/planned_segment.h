// A segment with its geometry and its speed profile: the planner's output and
// the coarse interpolator's input.
#pragma once

#include <cstdint>
#include <functional>

#include "path/segment.h"
#include "path/segment_geometry.h"
#include "path/segment_source.h"
#include "plan/trapezoid.h"

namespace lcnc {

struct PlannedSegment {
  Segment seg;
  SegmentGeometry geo{Segment{}};
  Trapezoid profile;
  double programmed_speed = 0.0;  // F (or L/duration) the segment was asked to run at, × k_plan
  // The feed override it is planned at: programmed_speed is the program's
  // F times this (1 for rapids and dwells), within the axes' limits.
  double k_plan = 1.0;
  double v_limit = 0.0;     // the highest speed its axes allow (SegmentLimits::v_max)
  std::uint32_t index = 0;  // position in the program's segment stream
};

// Planned segments are handed out by reference (some 600 bytes each, not
// copied): the one handed out stays valid until the source is asked again.
using PlannedSource = std::function<SourceStatus(const PlannedSegment*&)>;

}  // namespace lcnc
