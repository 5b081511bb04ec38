#include "plan/lookahead.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plan/tolerances.h"

namespace lcnc {
namespace {

// Speed reachable from v over length L — speeding up (sign +1, forward pass)
// or, read backward, the entry speed from which v is reached slowing down
// (sign −1) — with the acceleration taken at an upper bound of the speeds on
// the way (it falls as the speed rises, so the result is safe).
double reach(const SegmentLimits& lim, double sign, double v, double L, double v_max) {
  const double guess = std::min(v_max, std::sqrt(v * v + 2.0 * lim.tangential(v, sign) * L));
  return std::min(v_max, std::sqrt(v * v + 2.0 * lim.tangential(guess, sign) * L));
}

// The trapezoid v0 → vc → v1 with (nearly) the highest vc ≤ v_max that fits
// in L at acceleration a(vc) and deceleration d(vc). Two fixed-point steps:
// the peak at the accelerations of max(v0, v1) overshoots (they are the
// largest); the peak at the accelerations of that overshoot is safe (theirs
// are no larger than at the final speed) and within a hair of the optimum.
Trapezoid fit_profile(const SegmentLimits& lim, double L, double v0, double v1, double v_max) {
  auto fits = [&](double vc) {
    return (vc * vc - v0 * v0) / lim.accel_at(vc) + (vc * vc - v1 * v1) / lim.decel_at(vc) <=
           2.0 * L * (1.0 + 1e-12);
  };
  auto peak = [&](double a, double d) {
    return std::sqrt((2.0 * L + v0 * v0 / a + v1 * v1 / d) / (1.0 / a + 1.0 / d));
  };
  const double lo = std::max(v0, v1);
  double vc = std::max(lo, v_max);
  if (!fits(vc)) {
    const double over = std::min(v_max, peak(lim.accel_at(lo), lim.decel_at(lo)));
    vc = std::max(lo, std::min(v_max, peak(lim.accel_at(over), lim.decel_at(over))));
    if (!fits(vc)) vc = lo;
  }
  return Trapezoid::plan(L, lim.accel_at(vc), lim.decel_at(vc), v0, vc, v1);
}

}  // namespace

Lookahead::Lookahead(const MachineConfig& machine, IndexedSource source)
    : machine_(machine), source_(std::move(source)) {
  // Highest path speed any segment can reach (all linear axes at their max)
  // and the weakest acceleration: the braking length the window must cover.
  double v2 = 0.0, a_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) continue;
    if (i < 3) v2 += ax.max_velocity * ax.max_velocity;
    a_min = std::min(a_min, ax.max_acceleration);
  }
  braking_length_ = std::isfinite(a_min) ? v2 / (2.0 * a_min) : 0.0;
}

double Lookahead::junction_limit(const Node& a, const Node& b) const {
  const Segment& sa = a.p.seg;
  const Segment& sb = b.p.seg;
  if (sa.kind == MotionKind::Dwell || sb.kind == MotionKind::Dwell) return 0.0;
  if (sa.path_mode != PathMode::Blend) return 0.0;  // G61 / G61.1: stop at the end
  if ((sa.kind == MotionKind::Rapid) != (sb.kind == MotionKind::Rapid)) return 0.0;
  const Pose ta = a.p.geo.tangent(a.p.geo.length());
  const Pose tb = b.p.geo.tangent(0.0);
  double v = std::min(a.v_max, b.v_max);
  for (int i = 0; i < kAxisCount; ++i) {
    const double jump = std::abs(tb[i] - ta[i]);
    if (jump <= plan::kTangentJump) continue;          // tangent (blends, tangent arcs)
    if (jump > plan::kMaxJunctionJump) return 0.0;     // a corner: stop there
    v = std::min(v, plan::kJunctionJumpShare * machine_.axes[i].max_acceleration *
                        machine_.period_s() / jump);
  }
  return v;
}

bool Lookahead::fill() {
  while (!source_done_ && window_.size() < kMaxWindow &&
         (window_.size() < 2 || tail_length_ < kRefillDepth * braking_length_)) {
    IndexedSegment in;
    const SourceStatus st = source_(in);
    if (st != SourceStatus::Item) {
      source_done_ = true;
      source_error_ = st == SourceStatus::Error;
      break;
    }
    Node n;
    n.p.seg = in.seg;
    n.p.geo = SegmentGeometry(in.seg);
    n.p.index = in.index;
    if (in.seg.kind == MotionKind::Dwell) {
      n.p.profile = Trapezoid::hold(in.seg.dwell_s);
    } else {
      // one evaluation: the tangential limits are functions of the speed
      n.lim = segment_limits(in.seg, n.p.geo, machine_);
      n.p.programmed_speed = target_speed(in.seg, n.p.geo, n.lim);
      n.v_max = n.p.programmed_speed;
    }
    if (!window_.empty()) {
      window_.back().v_junction = junction_limit(window_.back(), n);
      tail_length_ += n.p.geo.length();
    }
    window_.push_back(std::move(n));
    max_window_ = std::max(max_window_, window_.size());
  }
  return !window_.empty();
}

void Lookahead::plan_and_release() {
  const std::size_t n = window_.size();
  // Backward: the window's last segment ends at rest (program end, or the
  // conservative assumption that it might).
  window_[n - 1].v_junction = source_done_ ? 0.0 : window_[n - 1].v_junction;
  double next_entry = 0.0;
  for (std::size_t k = n; k-- > 0;) {
    Node& s = window_[k];
    s.v_exit = (k + 1 == n) ? 0.0 : std::min(s.v_junction, next_entry);
    s.v_entry = reach(s.lim, -1.0, s.v_exit, s.p.geo.length(), s.v_max);
    if (s.p.seg.kind == MotionKind::Dwell) s.v_entry = 0.0;
    next_entry = s.v_entry;
  }
  // Forward from the speed we are committed to.
  double entry = v_start_;
  for (std::size_t k = 0; k < n; ++k) {
    Node& s = window_[k];
    s.v_entry = std::min(s.v_entry, entry);
    s.v_exit = std::min(s.v_exit, reach(s.lim, +1.0, s.v_entry, s.p.geo.length(), s.v_max));
    entry = s.v_exit;
  }
  // Release the front while what stays behind it covers the braking length.
  double behind = tail_length_;
  std::size_t released = 0;
  while (!window_.empty()) {
    const bool deep = behind >= braking_length_;
    if (!(source_done_ || deep || released == 0)) break;
    Node& s = window_.front();
    if (s.p.seg.kind != MotionKind::Dwell) {
      s.p.profile = fit_profile(s.lim, s.p.geo.length(), s.v_entry, s.v_exit, s.v_max);
    }
    v_start_ = s.v_exit;
    ready_.push_back(std::move(s.p));
    window_.pop_front();
    ++released;
    if (!window_.empty()) behind -= window_.front().p.geo.length();
  }
  tail_length_ = std::max(0.0, behind);
  if (window_.empty()) tail_length_ = 0.0;
}

SourceStatus Lookahead::next(PlannedSegment& out) {
  while (ready_.empty()) {
    if (!fill()) return source_error_ ? SourceStatus::Error : SourceStatus::End;
    plan_and_release();
  }
  out = std::move(ready_.front());
  ready_.pop_front();
  return SourceStatus::Item;
}

}  // namespace lcnc
