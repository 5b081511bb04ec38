// G64 Q, the naive-CAM detector (as LinuxCNC): consecutive feed lines whose
// inner points all lie within q of the straight line from the run's first
// point to its last are merged into that one line, q = min(Q, P)/2 (the other
// half of P is left to the corner blends that follow, plan/path_blender.h).
// A run is at most kMaxMergeRun lines with the same feed, laser and gas, in
// G64, without rotary motion, never reversing.
//
// The first stage of the planner: program segments in, indexed segments out
// (a merged line carries the index of the last program segment it covers).
// Streaming: holds one run back; constant memory. A segment that cannot
// start a run (every one without G64 Q) passes straight through when no run
// is held.
#pragma once

#include <array>
#include <cstdint>

#include "path/segment_geometry.h"
#include "plan/planned_segment.h"

namespace lcnc {

struct IndexedSegment {
  Segment seg;
  std::uint32_t index = 0;  // index of the program segment this piece belongs to
  // Set by the blender on what it hands out: the geometry (the look-ahead's
  // too), and whether the segment starts along the previous one's end
  // tangent by construction (a blend arc and the line after it).
  SegmentGeometry geo{Segment{}};
  bool tangent_in = false;
};
// The blender's output, handed out by reference: valid until the source is
// asked again.
using IndexedSource = std::function<SourceStatus(const IndexedSegment*&)>;

// Merge tolerance q of a G64 block: half of min(Q, P); 0 turns merging off.
[[nodiscard]] double merge_tolerance(const Segment& s) noexcept;

class LineMerger {
 public:
  static constexpr std::size_t kMaxMergeRun = 16;

  explicit LineMerger(SegmentSource source) : source_(std::move(source)) {}
  [[nodiscard]] SourceStatus next(IndexedSegment& out);

 private:
  [[nodiscard]] bool extends_run(const Segment& next) const;

  SegmentSource source_;
  bool have_run_ = false;
  IndexedSegment run_;                      // the run so far, as one line
  std::array<Vec3, kMaxMergeRun> inner_{};  // its inner points
  std::size_t inner_count_ = 0;
  IndexedSegment read_;  // the segment read while a run is held
  std::uint32_t count_ = 0;
  SourceStatus end_status_ = SourceStatus::Item;
};

}  // namespace lcnc
