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

enum class Side : std::uint8_t { SpeedUp, SlowDown };

// A segment's accelerations as a function of the speed (SegmentLimits::at),
// remembering what was asked for: one segment's passes and its profile ask
// for the same few speeds, and on arcs each answer costs a dozen divisions.
// Those at the segment's top speed are computed once, in fill(): a cruising
// segment asks for nothing else.
class AccelAt {
 public:
  AccelAt(const SegmentLimits& lim, double v_max, const Accel& at_v_max)
      : lim_(lim), v_max_(v_max), at_v_max_(at_v_max) {}

  [[nodiscard]] double v_max() const noexcept { return v_max_; }

  [[nodiscard]] Accel operator()(double v) {
    if (v == v_max_) return at_v_max_;
    if (!lim_.arc) return lim_.at(v);  // the same at every speed
    for (std::size_t k = 0; k < std::min(known_count_, kKnown); ++k)
      if (known_v_[k] == v) return known_[k];
    const Accel a = lim_.at(v);
    remember(v, a);
    return a;
  }
  [[nodiscard]] double operator()(double v, Side side) {
    const Accel a = (*this)(v);
    return side == Side::SpeedUp ? a.accel : a.decel;
  }
  // An answer found earlier (the backward pass's, kept in the window).
  void remember(double v, const Accel& a) {
    known_v_[known_count_ % kKnown] = v;
    known_[known_count_ % kKnown] = a;
    ++known_count_;
  }

 private:
  static constexpr std::size_t kKnown = 3;
  const SegmentLimits& lim_;
  double v_max_;
  const Accel& at_v_max_;
  std::array<double, kKnown> known_v_{};
  std::array<Accel, kKnown> known_{};
  std::size_t known_count_ = 0;
};

// Speed reachable from v over length L — speeding up (forward pass) or, read
// backward, the entry speed from which v is reached slowing down — with the
// acceleration taken at an upper bound of the speeds on the way (it falls as
// the speed rises, so the result is safe). Never below min(v, v_max):
// sqrt(v·v + x) ≥ v in floating point for x ≥ 0.
double reach(AccelAt& acc, Side side, double v, double L) {
  const double guess = std::min(acc.v_max(), std::sqrt(v * v + 2.0 * acc(v, side) * L));
  return std::min(acc.v_max(), std::sqrt(v * v + 2.0 * acc(guess, side) * L));
}

// The trapezoid v0 → vc → v1 with (nearly) the highest vc ≤ v_max that fits
// in L at acceleration a(vc) and deceleration d(vc). Two fixed-point steps:
// the peak at the accelerations of max(v0, v1) overshoots (they are the
// largest); the peak at the accelerations of that overshoot is safe (theirs
// are no larger than at the final speed) and within a hair of the optimum.
Trapezoid fit_profile(AccelAt& acc, double L, double v0, double v1) {
  auto fits = [&](double vc, const Accel& a) {
    return (vc * vc - v0 * v0) / a.accel + (vc * vc - v1 * v1) / a.decel <= 2.0 * L * (1.0 + 1e-12);
  };
  auto peak = [&](const Accel& a) {
    return std::sqrt((2.0 * L + v0 * v0 / a.accel + v1 * v1 / a.decel) /
                     (1.0 / a.accel + 1.0 / a.decel));
  };
  const double lo = std::max(v0, v1);
  double vc = std::max(lo, acc.v_max());
  Accel at_vc = acc(vc);
  if (!fits(vc, at_vc)) {
    const double over = std::min(acc.v_max(), peak(acc(lo)));
    vc = std::max(lo, std::min(acc.v_max(), peak(acc(over))));
    at_vc = acc(vc);
    if (!fits(vc, at_vc)) {
      vc = lo;
      at_vc = acc(vc);
    }
  }
  return Trapezoid::plan(L, at_vc.accel, at_vc.decel, v0, vc, v1);
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

double Lookahead::junction_limit(const Node& a, const Node& b) {
  // a's end tangent if known; b's is known below when b is a line
  std::optional<Pose> ta = std::exchange(back_end_tangent_, std::nullopt);
  const Segment& sa = a.p.seg;
  const Segment& sb = b.p.seg;
  if (sa.kind == MotionKind::Dwell || sb.kind == MotionKind::Dwell) return 0.0;
  if (sa.path_mode != PathMode::Blend) return 0.0;  // G61 / G61.1: stop at the end
  if ((sa.kind == MotionKind::Rapid) != (sb.kind == MotionKind::Rapid)) return 0.0;
  if (!ta) ta = a.p.geo.end_tangent();
  const Pose tb = b.p.geo.start_tangent();
  if (!b.p.geo.is_arc()) back_end_tangent_ = tb;  // a line ends as it starts
  double v = std::min(a.v_max, b.v_max);
  for (int i = 0; i < kAxisCount; ++i) {
    const double jump = std::abs(tb[i] - (*ta)[i]);
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
    Node& n = window_.emplace_back(in);
    if (window_.size() == 1) back_end_tangent_.reset();  // belonged to a released segment
    if (in.seg.kind == MotionKind::Dwell) {
      n.p.profile = Trapezoid::hold(in.seg.dwell_s);
    } else {
      // one evaluation: the tangential limits are functions of the speed
      n.lim = segment_limits(in.seg, n.p.geo, machine_);
      n.p.programmed_speed = target_speed(in.seg, n.p.geo, n.lim);
      n.v_max = n.p.programmed_speed;
    }
    n.at_v_max = n.lim.at(n.v_max);
    if (window_.size() > 1) {
      Node& prev = window_[window_.size() - 2];
      prev.v_junction = junction_limit(prev, n);
      tail_length_ += n.p.geo.length();
    }
    max_window_ = std::max(max_window_, window_.size());
  }
  return !window_.empty();
}

void Lookahead::plan_and_release() {
  const std::size_t n = window_.size();
  // What to release: the front, while what stays behind it covers the
  // braking length (all of it at the program's end).
  double behind = tail_length_;
  std::size_t count = 0;
  while (count < n && (source_done_ || behind >= braking_length_ || count == 0)) {
    ++count;
    if (count < n) behind -= window_[count].p.geo.length();
  }
  tail_length_ = count == n ? 0.0 : std::max(0.0, behind);

  // Backward: the window's last segment ends at rest (program end, or the
  // conservative assumption that it might). A segment's entry depends only
  // on its exit: once one comes out as in the previous plan, so does
  // everything before it.
  double next_entry = 0.0;
  for (std::size_t k = n; k-- > 0;) {
    Node& s = window_[k];
    const double exit = (k + 1 == n) ? 0.0 : std::min(s.v_junction, next_entry);
    AccelAt acc(s.lim, s.v_max, s.at_v_max);
    s.at_exit_back = acc(exit);
    const double entry = s.p.seg.kind == MotionKind::Dwell
                             ? 0.0
                             : reach(acc, Side::SlowDown, exit, s.p.geo.length());
    const bool unchanged = s.planned_back && entry == s.v_entry_back;
    s.v_exit_back = exit;
    s.v_entry_back = entry;
    s.planned_back = true;
    if (unchanged) break;
    next_entry = entry;
  }
  // Forward from the speed we are committed to, over the segments released.
  double entry = v_start_;
  for (std::size_t k = 0; k < count; ++k) {
    Node& s = window_[k];
    AccelAt acc(s.lim, s.v_max, s.at_v_max);
    acc.remember(s.v_exit_back, s.at_exit_back);
    const double L = s.p.geo.length();
    const double v_entry = std::min(s.v_entry_back, entry);
    // reach() gives at least v_entry (≤ v_max): no need to ask when that
    // already covers the exit the backward pass allows
    const double v_exit = v_entry >= s.v_exit_back
                              ? s.v_exit_back
                              : std::min(s.v_exit_back, reach(acc, Side::SpeedUp, v_entry, L));
    if (s.p.seg.kind != MotionKind::Dwell) s.p.profile = fit_profile(acc, L, v_entry, v_exit);
    entry = v_exit;
  }
  v_start_ = entry;
  released_ = count;
  handed_ = 0;
}

SourceStatus Lookahead::next(PlannedSegment& out) {
  while (handed_ == released_) {
    window_.erase(window_.begin(), window_.begin() + static_cast<std::ptrdiff_t>(released_));
    released_ = handed_ = 0;
    if (!fill()) return source_error_ ? SourceStatus::Error : SourceStatus::End;
    plan_and_release();
  }
  out = window_[handed_++].p;
  return SourceStatus::Item;
}

}  // namespace lcnc
