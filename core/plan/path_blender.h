// The blending stage of the planner: a stream of program segments in, the
// same path with its G64 corners rounded out (plan/arc_transition.h).
//
// Program lines first pass the naive-CAM merger (G64 Q, plan/line_merger.h).
// Corners between two feed lines (G1) that are both in G64 get a tangent arc
// within the tolerance E of plan/tolerance_budget.h: min(P of the two
// blocks) less the merger's share, the quantization margin and the jerk
// filter's deviation, so that the executed path stays within P. Each
// corner may use at most half of each neighbouring line (Shao 2022:
// l_s = min(S(i)/2, S(i+1)/2)). Rotary axes moving along do not switch
// blending off. Corners with an arc on one or both sides get a fillet in the
// arc's plane (fillet_transition). Every other
// corner (G61, G61.1, rapids, helices, dwells) is passed through: the
// look-ahead decides its speed.
//
// Streaming: holds one line back (its end may still be trimmed); memory is
// constant whatever the program's length.
#pragma once

#include <array>
#include <cstdint>

#include "machine/machine_config.h"
#include "plan/arc_transition.h"
#include "plan/line_merger.h"
#include "plan/planned_segment.h"
#include "plan/tolerance_budget.h"

namespace lcnc {

class PathBlender {
 public:
  // budget: what of each corner's P the blend arc may not take.
  PathBlender(const MachineConfig& machine, SegmentSource source, const ToleranceBudget& budget);
  // The machine's budget without a jerk filter (e_f = 0).
  PathBlender(const MachineConfig& machine, SegmentSource source)
      : PathBlender(machine, std::move(source), tolerance_budget(machine, 0.0)) {}
  // The next segment, valid until next() is called again.
  [[nodiscard]] SourceStatus next(const IndexedSegment*& out);

 private:
  // Queues s to hand out, its geometry computed unless it has it already.
  void hand_out(IndexedSegment& s, bool with_geometry = false);

  LineMerger merger_;
  ToleranceBudget budget_;
  double tip_mm_per_deg_ = 0.0;  // under TCP: how far a degree of A or C moves the tip at most
  bool have_pending_ = false;
  // The pending line, whose end may still be blended, and the one read after
  // it: slots_[pending_slot_] and the other.
  std::array<IndexedSegment, 2> slots_;
  std::size_t pending_slot_ = 0;
  double pending_full_length_ = 0;  // its length as programmed
  double pending_length_ = 0;       // and as it is now (its start may be trimmed)
  // Whether the last segment queued moves a rotary axis: the next one is
  // marked tangent to it only if it does not (IndexedSegment::tangent_in).
  bool rotary_out_ = false;
  IndexedSegment arc_;    // the blend arc of the last corner
  ArcTransition corner_;  // and the rest of what its transition found
  // Segments ready to hand out, oldest first, where they are (a slot or
  // arc_): one step of next() emits at most two (a trimmed line and its
  // blend arc), and next() hands them out before it takes another step —
  // which is the first to write a slot or arc_ again.
  std::array<const IndexedSegment*, 2> ready_{};
  std::size_t ready_front_ = 0, ready_count_ = 0;
  SourceStatus end_status_ = SourceStatus::Item;
};

}  // namespace lcnc
