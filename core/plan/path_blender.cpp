#include "plan/path_blender.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "kinematics/five_axis.h"
#include "path/segment_geometry.h"
#include "plan/arc_transition.h"
#include "plan/tolerances.h"

namespace lcnc {
namespace {

// (A curve's corners are its own: the tool-centre-point expander rounds them.)
bool blendable_line(const Segment& s) {
  return s.kind == MotionKind::Linear && !s.curve && s.path_mode == PathMode::Blend &&
         (s.end.head<3>() - s.start.head<3>()).norm() > plan::kMinSegmentLength;
}

// Arcs in a G17/G18/G19 plane, without helix or rotary motion, can take part
// in a corner (fillet_transition).
bool blendable_arc(const Segment& s) {
  if (s.kind != MotionKind::Arc || s.path_mode != PathMode::Blend || s.plane == Plane::Free) return false;
  const Pose d = s.end - s.start;
  return d[plane_axes(s.plane).normal] == 0.0 && d.tail<3>().norm() == 0.0;
}

bool blendable(const Segment& s) { return blendable_line(s) || blendable_arc(s); }

// Whether any rotary axis moves at all: its rate per unit of path is then
// not zero, and a join with a segment where it is zero is no tangent one.
bool moves_rotary(const Segment& s) { return s.end.tail<3>() != s.start.tail<3>(); }

// Rotary travel per mm of path (deg/mm) of a segment `length` long.
Vec3 rotary_rate(const Segment& s, double length) {
  return length > 0.0 ? Vec3((s.end.tail<3>() - s.start.tail<3>()) / length) : Vec3::Zero();
}

}  // namespace

PathBlender::PathBlender(const MachineConfig& machine, SegmentSource source, const ToleranceBudget& budget)
    : merger_(std::move(source)), budget_(budget) {
  if (machine.tcp.enabled) tip_mm_per_deg_ = tip_lever_mm(machine.kinematics) * std::numbers::pi / 180.0;
}

void PathBlender::hand_out(IndexedSegment& s, bool with_geometry) {
  if (!with_geometry) s.geo.set(s.seg);
  // Lines used up entirely by their two blends carry no motion: drop them.
  // (Their path length is at most their travel in all axes: only a short
  // one needs that.)
  if (s.seg.kind == MotionKind::Linear && s.geo.length() <= plan::kMinSegmentLength &&
      (s.seg.end - s.seg.start).norm() <= plan::kMinSegmentLength)
    return;
  rotary_out_ = moves_rotary(s.seg);
  ready_[(ready_front_ + ready_count_++) % ready_.size()] = &s;
}

SourceStatus PathBlender::next(const IndexedSegment*& out) {
  while (ready_count_ == 0) {
    if (end_status_ != SourceStatus::Item) return end_status_;
    // read into the slot the pending line does not hold: it becomes the
    // pending one by a flip, not a copy
    IndexedSegment& pending = slots_[pending_slot_];
    IndexedSegment& cur = slots_[1 - pending_slot_];
    const SourceStatus st = merger_.next(cur);
    cur.tangent_in = cur.seg.smooth_in;  // a piece of the curve before it
    if (st != SourceStatus::Item) {
      if (have_pending_) hand_out(pending);
      have_pending_ = false;
      end_status_ = st;
      continue;
    }
    const bool cur_blendable = blendable(cur.seg);
    if (have_pending_ && cur_blendable) {
      const Segment& a = pending.seg;
      double tol = budget_.corner_mm(std::min(a.blend_tolerance_mm, cur.seg.blend_tolerance_mm),
                                     std::max(merge_tolerance(a), merge_tolerance(cur.seg)));
      const double len_a = pending_length_;
      const double len_b = path_length(cur.seg);
      // Under tool-centre-point control the rotary axes run linearly across
      // the blend while their rate per mm jumps at the corner: in the blend's
      // middle they are off the lines' by trim·|rate jump|/2, which moves the
      // tip by tip_mm_per_deg_ × that. Half the tolerance goes to X Y Z, half
      // to the rotary axes, which bounds the trim.
      double trim_cap = std::numeric_limits<double>::infinity();
      if (tip_mm_per_deg_ > 0.0) {
        const double jump = (rotary_rate(cur.seg, len_b) - rotary_rate(a, len_a)).norm();
        if (jump > 0.0) {
          tol *= plan::kTcpXyzShare;
          trim_cap = tol / (0.5 * tip_mm_per_deg_ * jump);
        }
      }
      // A corner takes at most half of a line and 45 % of an arc (an arc
      // trimmed to nothing would read as a full circle).
      const double share_a = a.kind == MotionKind::Arc ? plan::kCornerArcShare : plan::kCornerLineShare;
      const double share_b = cur.seg.kind == MotionKind::Arc ? plan::kCornerArcShare : plan::kCornerLineShare;
      const double max_a = std::min({pending_full_length_ * share_a, len_a, trim_cap});
      const double max_b = std::min(len_b * share_b, trim_cap);
      // A line–line blend goes straight into arc_, its geometry as built
      // (a fillet's is computed as any arc's).
      ArcTransition& t = corner_;
      const bool line_line = a.kind == MotionKind::Linear && cur.seg.kind == MotionKind::Linear;
      if (line_line) {
        // (a line's path length is its X Y Z length: blendable lines have one)
        (void)arc_transition(a, cur.seg, len_a, len_b, tol, max_a, max_b, t, arc_.seg, arc_.geo);
      } else {
        t = fillet_transition(a, cur.seg, tol, max_a, max_b);
        if (t.blended) arc_.seg = t.arc;
      }
      if (t.blended) {
        pending.seg.end = t.q0;
        hand_out(pending);
        arc_.index = cur.index;
        // A line–line blend is tangent to both lines by construction — in
        // X Y Z: with rotary axes moving, their rates per mm jump at its ends.
        // So the whole pose is tangent only where neither side moves one.
        // The side before is what was queued last, not the pending line: one
        // used up entirely by its two blends is dropped (and has no rotary
        // travel left), and the arc then follows the previous blend, which
        // still carries that line's rotary rate.
        const bool arc_rotary = moves_rotary(arc_.seg);
        arc_.tangent_in = line_line && !arc_rotary && !rotary_out_;
        hand_out(arc_, line_line);
        cur.tangent_in = line_line && !arc_rotary && !moves_rotary(cur.seg);
        pending_full_length_ = len_b;
        cur.seg.start = t.q2;
        pending_length_ = path_length(cur.seg);
        pending_slot_ = 1 - pending_slot_;
        continue;
      }
    }
    if (have_pending_) hand_out(pending);
    have_pending_ = cur_blendable;
    if (have_pending_) {
      pending_slot_ = 1 - pending_slot_;
      pending_full_length_ = pending_length_ = path_length(cur.seg);
    } else {
      hand_out(cur);
    }
  }
  out = ready_[ready_front_];
  ready_front_ = (ready_front_ + 1) % ready_.size();
  --ready_count_;
  return SourceStatus::Item;
}

}  // namespace lcnc
