#include "plan/line_merger.h"

#include <algorithm>

#include "path/segment_geometry.h"
#include "plan/tolerances.h"

namespace lcnc {
namespace {

bool mergeable(const Segment& s) {
  return s.kind == MotionKind::Linear && !s.curve && s.path_mode == PathMode::Blend &&
         merge_tolerance(s) > 0.0 && (s.end - s.start).tail<3>().norm() == 0.0 &&
         (s.end.head<3>() - s.start.head<3>()).norm() > plan::kMinSegmentLength;
}

}  // namespace

double merge_tolerance(const Segment& s) noexcept {
  return 0.5 * std::min(s.naive_cam_tolerance_mm, s.blend_tolerance_mm);
}

bool LineMerger::extends_run(const Segment& next) const {
  const Segment& a = run_.seg;
  if (!mergeable(a) || !mergeable(next) || inner_count_ + 1 >= kMaxMergeRun) return false;
  if (a.feed_mm_s != next.feed_mm_s || a.duration_s != next.duration_s || a.laser != next.laser ||
      a.power_pct != next.power_pct || a.mist != next.mist || a.flood != next.flood ||
      a.digital_out != next.digital_out || a.analog_out != next.analog_out ||
      a.feed_control != next.feed_control)
    return false;
  const double q = std::min(merge_tolerance(a), merge_tolerance(next));
  const Vec3 s0 = a.start.head<3>(), s1 = next.end.head<3>();
  if ((a.end.head<3>() - s0).dot(s1 - next.start.head<3>()) <= 0.0) return false;  // reversal
  if (distance_to_segment(next.start.head<3>(), s0, s1) > q) return false;
  for (std::size_t k = 0; k < inner_count_; ++k)
    if (distance_to_segment(inner_[k], s0, s1) > q) return false;
  return true;
}

SourceStatus LineMerger::next(IndexedSegment& out) {
  for (;;) {
    if (end_status_ != SourceStatus::Item) {
      if (!have_run_) return end_status_;
      out = run_;
      have_run_ = false;
      return SourceStatus::Item;
    }
    // With no run held, read straight into out: no copy for what passes through.
    IndexedSegment& cur = have_run_ ? read_ : out;
    const SourceStatus st = source_(cur.seg);
    if (st != SourceStatus::Item) {
      end_status_ = st;
      continue;
    }
    cur.index = count_++;
    if (!have_run_) {
      if (!mergeable(out.seg)) return SourceStatus::Item;
      run_ = out;  // a run starts
      have_run_ = true;
      inner_count_ = 0;
      continue;
    }
    if (extends_run(cur.seg)) {
      inner_[inner_count_++] = cur.seg.start.head<3>();
      run_.seg.end = cur.seg.end;
      run_.seg.line = cur.seg.line;
      run_.index = cur.index;
      continue;
    }
    // the run is complete: hand it on; what ended it may start the next
    out = run_;
    run_ = cur;
    inner_count_ = 0;
    return SourceStatus::Item;
  }
}

}  // namespace lcnc
