#include "plan/lookahead.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

#include "plan/tolerances.h"

namespace lcnc {
namespace {

// The trapezoid v0 → vc → v1 with (nearly) the highest vc ≤ v_max that fits
// in L at acceleration a and deceleration d allowed over [v0, vc] and
// [v1, vc]. Both fall as vc rises. Two fixed-point steps: the peak at the
// accelerations of max(v0, v1) overshoots (they are the largest); the peak
// at the accelerations of that overshoot is safe (theirs are no larger than
// at the final speed) and within a hair of the optimum.
void fit_profile(const SegmentLimits& lim, double v_max, double L, double v0, double v1, Trapezoid& out) {
  auto fits = [&](double vc, const Accel& a) {
    return (vc * vc - v0 * v0) / a.accel + (vc * vc - v1 * v1) / a.decel <=
           2.0 * L * (1.0 + plan::kProfileFitRel);
  };
  auto peak = [&](const Accel& a) { return std::sqrt(Trapezoid::peak_sqr(L, a.accel, a.decel, v0, v1)); };
  auto at = [&](double vc) { return lim.at(vc, v0, v1); };
  const double lo = std::max(v0, v1);
  double vc = std::max(lo, v_max);
  Accel at_vc = at(vc);
  if (!fits(vc, at_vc)) {
    const double over = std::min(v_max, peak(at(lo)));
    vc = std::max(lo, std::min(v_max, peak(at(over))));
    at_vc = at(vc);
    if (!fits(vc, at_vc)) {
      vc = lo;
      at_vc = at(vc);
    }
  }
  out.set(L, at_vc.accel, at_vc.decel, v0, vc, v1);
}

}  // namespace

Lookahead::Lookahead(const MachineConfig& machine, IndexedSource source)
    : machine_(machine), source_(std::move(source)) {
  // The weakest acceleration: how far back a stop can reach.
  double a_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kAxisCount; ++i)
    if (machine.axes[i].present) a_min = std::min(a_min, machine.axes[i].max_acceleration);
  a_brake_ = std::isfinite(a_min) ? a_min : 0.0;
}

double Lookahead::junction_limit(const PlannedSegment& a, const PlannedSegment& b) {
  // a's end tangent if known; b's is known below when b is a line
  std::optional<Pose> ta = std::exchange(back_end_tangent_, std::nullopt);
  const Segment& sa = a.seg;
  const Segment& sb = b.seg;
  if (sa.kind == MotionKind::Dwell || sb.kind == MotionKind::Dwell) return 0.0;
  if (sa.path_mode != PathMode::Blend) return 0.0;  // G61 / G61.1: stop at the end
  if ((sa.kind == MotionKind::Rapid) != (sb.kind == MotionKind::Rapid)) return 0.0;
  if (!ta) ta = a.geo.end_tangent();
  const Pose tb = b.geo.start_tangent();
  if (!b.geo.is_arc() && !b.geo.is_curve()) back_end_tangent_ = tb;  // a line ends as it starts
  double v = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kAxisCount; ++i) {
    const double jump = std::abs(tb[i] - (*ta)[i]);
    if (jump <= plan::kTangentJump) continue;       // tangent (blends, tangent arcs)
    if (jump > plan::kMaxJunctionJump) return 0.0;  // a corner: stop there
    v = std::min(v,
                 plan::kJunctionJumpShare * machine_.axes[i].max_acceleration * machine_.period_s() / jump);
  }
  return v;
}

void Lookahead::set_speed(std::size_t k, double k_plan) {
  Node& n = node(k);
  PlannedSegment& p = segment(k);
  // rapids and moves under M50 P0 / M49 run at 100 % whatever the override
  const bool fixed = p.seg.kind == MotionKind::Rapid || (p.seg.feed_control & kFeedOverrideOff) != 0;
  p.k_plan = fixed ? 1.0 : k_plan;
  // one evaluation: the tangential limits are functions of the speed
  p.programmed_speed = target_speed(p.seg, p.geo, n.lim, p.k_plan);
  p.v_limit = n.lim.v_max;
  n.x_max = p.programmed_speed * p.programmed_speed;
}

void Lookahead::set_feed_scale(double k) {
  const bool raise = k > feed_scale_;
  feed_scale_ = k;
  if (!raise) return;
  // What was handed out is committed; the rest is planned again from where
  // the last of it ends.
  const double x_from = handed_ > 0 ? node(handed_ - 1).x_exit : x_released_from_;
  head_ = (head_ + handed_) & mask_;
  size_ -= handed_;
  released_ = handed_ = 0;
  // what a raise before the next release starts from (handed_ = 0 there)
  x_start_ = x_released_from_ = x_from;
  if (size_ == 0) return;
  braking_length_ = 0.0;
  tail_length_ = 0.0;
  for (std::size_t j = 0; j < size_; ++j) {
    Node& n = node(j);
    n.planned_back = false;
    if (j > 0) tail_length_ += n.length;
    if (!n.dwell && segment(j).k_plan < k) set_speed(j, k);  // never slower than planned
    braking_length_ = std::max(braking_length_, braking_length(j));
  }
  for (std::size_t j = 0; j + 1 < size_; ++j) {
    Node& n = node(j);
    n.x_junction = std::min({n.x_junction_geo, n.x_max, node(j + 1).x_max});
  }
  plan_and_release();
}

void Lookahead::grow() {
  const std::size_t cap = nodes_.empty() ? kInitialCapacity : 2 * nodes_.size();
  std::vector<Node> nodes(cap);
  std::vector<PlannedSegment> segments(cap);
  for (std::size_t k = 0; k < size_; ++k) {
    nodes[k] = node(k);
    segments[k] = segment(k);
  }
  nodes_.swap(nodes);
  segments_.swap(segments);
  head_ = 0;
  mask_ = cap - 1;
}

bool Lookahead::fill() {
  while (!source_done_ && size_ < kMaxWindow &&
         (size_ < 2 || tail_length_ < kRefillDepth * braking_length_)) {
    const IndexedSegment* in = nullptr;
    const SourceStatus st = source_(in);
    if (st != SourceStatus::Item) {
      source_done_ = true;
      source_error_ = st == SourceStatus::Error;
      break;
    }
    if (size_ == nodes_.size()) grow();
    const std::size_t k = size_++;
    PlannedSegment& p = segment(k);
    // The limits from the source's segment, before it is copied: the
    // copy's loads would wait for the stores that made it.
    Node& n = node(k);
    n = Node{};
    n.length = in->geo.length();
    const bool dwell = in->seg.kind == MotionKind::Dwell;
    if (!dwell) segment_limits(in->geo, machine_, n.lim);
    p.seg = in->seg;
    p.geo = in->geo;
    p.programmed_speed = 0.0;  // (the profile is set when the segment is handed out)
    p.index = in->index;
    if (k == 0) back_end_tangent_.reset();  // belonged to a released segment
    if (dwell) {
      n.dwell = true;
      p.profile = Trapezoid::hold(p.seg.dwell_s);
      p.k_plan = 1.0;  // a dwell's time is the program's, whatever the override
      p.v_limit = 0.0;
    } else {
      set_speed(k, feed_scale_);
      braking_length_ = std::max(braking_length_, braking_length(k));
    }
    if (k > 0) {
      Node& before = node(k - 1);
      if (in->tangent_in) back_end_tangent_.reset();  // not looked at
      const double v =
          in->tangent_in ? std::numeric_limits<double>::infinity() : junction_limit(segment(k - 1), p);
      before.x_junction_geo = v * v;
      before.x_junction = std::min({before.x_junction_geo, before.x_max, n.x_max});
      tail_length_ += n.length;
    }
    max_window_ = std::max(max_window_, size_);
  }
  return size_ > 0;
}

void Lookahead::plan_and_release() {
  const std::size_t n = size_;
  // What to release: the front, while what stays behind it covers the
  // braking length (all of it at the program's end).
  double behind = tail_length_;
  std::size_t count = 0;
  while (count < n && (source_done_ || behind >= braking_length_ || count == 0)) {
    ++count;
    if (count < n) behind -= node(count).length;
  }
  tail_length_ = count == n ? 0.0 : std::max(0.0, behind);

  // Backward: the window's last segment ends at rest (program end, or the
  // conservative assumption that it might). A segment's entry depends only
  // on its exit: once one comes out as in the previous plan, so does
  // everything before it.
  double next_entry = 0.0;
  for (std::size_t k = n; k-- > 0;) {
    Node& s = node(k);
    const double exit = (k + 1 == n) ? 0.0 : std::min(s.x_junction, next_entry);
    // the reach is at least the exit: no need to ask when that covers x_max
    const double reach = s.dwell ? 0.0 : exit >= s.x_max ? exit : s.lim.reach_down_sqr(exit, s.length);
    const double entry = std::min(s.x_max, reach);
    s.entry_by_reach = reach < s.x_max;
    const bool unchanged = s.planned_back && entry == s.x_entry_back;
    s.x_exit_back = exit;
    s.x_entry_back = entry;
    s.planned_back = true;
    if (unchanged) break;
    next_entry = entry;
  }
  // Forward from the speed we are committed to, over the segments released.
  x_released_from_ = x_start_;
  double entry = x_start_;
  for (std::size_t k = 0; k < count; ++k) {
    Node& s = node(k);
    s.x_entry = std::min(s.x_entry_back, entry);
    s.x_exit = s.x_exit_back;
    s.shape = Node::Shape::Fit;
    // the reach is at least the entry (≤ x_max): no need to ask when that
    // already covers the exit the backward pass allows
    if (s.x_entry < s.x_exit_back) {
      const double reach = s.lim.reach_up_sqr(s.x_entry, s.length);
      if (reach < s.x_exit_back) {
        s.x_exit = reach;  // speeding up all the way
        s.shape = Node::Shape::SpeedUp;
      }
    }
    if (s.shape == Node::Shape::Fit && s.entry_by_reach && s.x_entry == s.x_entry_back)
      s.shape = Node::Shape::SlowDown;  // slowing down all the way to x_exit_back
    entry = s.x_exit;
  }
  x_start_ = entry;
  released_ = count;
  handed_ = 0;
  // The braking length of what stays (the released may have been faster).
  braking_length_ = 0.0;
  for (std::size_t k = count; k < n; ++k) braking_length_ = std::max(braking_length_, braking_length(k));
}

SourceStatus Lookahead::next(const PlannedSegment*& out) {
  while (handed_ == released_) {
    head_ = (head_ + released_) & mask_;
    size_ -= released_;
    released_ = handed_ = 0;
    if (!fill()) return source_error_ ? SourceStatus::Error : SourceStatus::End;
    plan_and_release();
  }
  const Node& s = node(handed_);
  PlannedSegment& p = segment(handed_);
  ++handed_;
  out = &p;
  if (s.dwell) return SourceStatus::Item;
  const double v_entry = std::sqrt(s.x_entry), v_exit = std::sqrt(s.x_exit);
  switch (s.shape) {
    case Node::Shape::Fit:
      fit_profile(s.lim, p.programmed_speed, s.length, v_entry, v_exit, p.profile);
      break;
    case Node::Shape::SpeedUp:
    case Node::Shape::SlowDown: {
      // v_exit (v_entry) is the reach at the accelerations over [v_entry,
      // v_exit] ([v_exit, v_entry])
      const double peak = std::max(v_entry, v_exit);
      const Accel a = s.lim.at(peak, v_entry, v_exit);
      p.profile.set(s.length, a.accel, a.decel, v_entry, peak, v_exit);
      break;
    }
  }
  return SourceStatus::Item;
}

}  // namespace lcnc
