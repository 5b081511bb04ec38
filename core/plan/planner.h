// The planner, stage by stage (docs/design.md §2, §5.1–5.3):
//
//   program segments ─► LineMerger (G64 Q) ─► PathBlender (corner arcs, G64 P)
//     ─► Lookahead (forward/backward, streaming) ─► CoarseInterpolator (one
//     pose per RT period) ─► samples
//
// With a jerk limit (machine.max_jerk, plan/jerk_filter.h) the look-ahead
// plans at the accelerations the filter leaves, a hold is inserted at every
// stop before coarse interpolation (StopHolds), and the samples pass a moving
// average (JerkFilter); the blends keep the filter's deviation out of P
// (ToleranceBudget, plan/tolerance_budget.h).
// Without it every stage runs as before: the output is bit-identical.
//
// Pull-driven and streaming: memory stays bounded whatever the program's
// length. One object per job; not movable (the stages refer to each other).
#pragma once

#include "machine/machine_config.h"
#include "plan/coarse_interpolator.h"
#include "plan/jerk_filter.h"
#include "plan/lookahead.h"
#include "plan/path_blender.h"
#include "plan/tolerance_budget.h"

namespace lcnc {

class Planner {
 public:
  Planner(const MachineConfig& machine, SegmentSource source);
  Planner(const Planner&) = delete;
  Planner& operator=(const Planner&) = delete;

  // The next period's commanded sample; End after the one with end_of_program.
  [[nodiscard]] SourceStatus next(PeriodSample& out) {
    return jerk_.enabled() ? next_filtered(out) : interp_.next(out);
  }

  [[nodiscard]] std::uint64_t periods() const noexcept { return interp_.periods(); }
  [[nodiscard]] std::size_t max_window() const noexcept { return lookahead_.max_window_seen(); }
  // The feed override to plan for, ≥ 1 (Lookahead::set_feed_scale): a raise
  // shows after what is already sampled and what the look-ahead handed out.
  void set_feed_scale(double k) {
    k = std::max(1.0, k);
    if (k > lookahead_.feed_scale()) interp_.raise_feed_scale(k);
    lookahead_.set_feed_scale(k);
  }
  [[nodiscard]] double feed_scale() const noexcept { return lookahead_.feed_scale(); }
  // The jerk filter in force (taps 1: none).
  [[nodiscard]] const JerkLimit& jerk_limit() const noexcept { return jerk_; }
  // What of a corner's P the blends leave to rounding and the jerk filter.
  [[nodiscard]] const ToleranceBudget& tolerance_budget() const noexcept { return budget_; }
  // Observes every planned segment as it leaves the look-ahead (tests, benchmarks).
  void on_planned(std::function<void(const PlannedSegment&)> f) { on_planned_ = std::move(f); }

 private:
  JerkLimit jerk_;
  ToleranceBudget budget_;  // computed once here, from the machine and jerk_
  MachineConfig planned_;   // the machine as the look-ahead plans it (planned_machine())
  PathBlender blender_;
  Lookahead lookahead_;
  StopHolds holds_;
  CoarseInterpolator interp_;
  JerkFilter filter_;
  std::function<void(const PlannedSegment&)> on_planned_;

  [[nodiscard]] SourceStatus next_filtered(PeriodSample& out);
  // The look-ahead's next segment, shown to on_planned_.
  [[nodiscard]] SourceStatus planned(const PlannedSegment*& out);
};

}  // namespace lcnc
