#include "plan/jerk_filter.h"

#include <algorithm>
#include <cmath>

#include "plan/tolerance_budget.h"
#include "plan/tolerances.h"

namespace lcnc {

JerkLimit jerk_limit(const MachineConfig& m) {
  JerkLimit lim;
  if (!(m.max_jerk > 0.0)) return lim;
  const double period = m.period_s();
  const double jerk = m.max_jerk;
  double a_top = 0.0, a_sqr = 0.0;  // largest and Σ a² of the linear axes
  for (int i = 0; i < 3; ++i) {
    const AxisConfig& ax = m.axes[i];
    if (!ax.present) continue;
    const double a = ax.max_acceleration;
    a_top = std::max(a_top, a);
    a_sqr += a * a;
  }
  if (a_top <= 0.0) return lim;
  const double norm_ratio = std::sqrt(a_sqr) / a_top;   // |a| / a_top
  const double swing = 2.0 + plan::kJunctionJumpShare;  // Δa_in / a, eq. (1)
  const double budget = jerk_filter_budget_mm(m);
  // e_f of a window of `taps` when the largest axis acceleration is `a`, eq. (2)
  auto error = [&](double taps, double a) {
    return norm_ratio * a * period * period * (taps * taps - 1.0) / 24.0;
  };
  // The window the jerk asks for at full acceleration, eq. (1).
  double taps = std::ceil(swing * a_top / (jerk * period));
  double scale = 1.0;
  if (error(taps, a_top) > budget) {
    // Too much deviation: lower the acceleration. With M taps the jerk allows
    // a = J·M·T/swing, and e_f then grows as M³: take the largest M whose
    // e_f fits the budget (below the M above, where a ≥ a_top).
    auto accel_for = [&](double n) { return jerk * n * period / swing; };
    taps =
        std::floor(std::cbrt(24.0 * budget * swing / (norm_ratio * jerk * period * period * period))) + 1.0;
    while (taps > 2.0 && error(taps, accel_for(taps)) > budget) taps -= 1.0;
    scale = std::min(1.0, accel_for(taps) / a_top);
  }
  if (taps <= 1.0) return lim;  // the trapezoids keep within J already
  lim.taps = static_cast<std::uint32_t>(taps);
  lim.accel_scale = scale;
  lim.error_mm = error(taps, scale * a_top);
  return lim;
}

MachineConfig planned_machine(const MachineConfig& machine, const JerkLimit& limit) {
  MachineConfig m = machine;
  if (!limit.enabled()) return m;
  for (int i = 0; i < 3; ++i) m.axes[i].max_acceleration *= limit.accel_scale;
  return m;
}

namespace {

// Periods a stop holds on each side: half the filter's taps, rounded down,
// and one.
double hold_periods(const JerkLimit& limit) {
  const std::uint32_t periods = (limit.taps + 1) / 2 + 1;
  return static_cast<double>(periods);
}

}  // namespace

StopHolds::StopHolds(PlannedSource source, const JerkLimit& limit, double period_s)
    : source_(std::move(source)), enabled_(limit.enabled()), half_s_(hold_periods(limit) * period_s) {}

PlannedSegment StopHolds::half(const PlannedSegment& neighbour, bool stand, const Pose& at) const {
  PlannedSegment h = neighbour;
  Segment& s = h.seg;
  // A zero-length line or rapid: the interpolator samples it at `at`, with
  // the neighbour's laser (M3 on, M4 0 at speed 0, rapids dark).
  s.kind = stand ? MotionKind::Dwell : (s.kind == MotionKind::Rapid ? MotionKind::Rapid : MotionKind::Linear);
  s.start = s.end = at;
  s.dwell_s = stand ? half_s_ : 0.0;
  s.pause = false;    // a pause's own segment holds, not the stops around it
  s.wait_input = -1;  // and an M66's
  if (stand) s.laser = LaserMode::Off;
  h.geo.set(s);
  h.profile = Trapezoid::hold(half_s_);
  return h;
}

SourceStatus StopHolds::next(const PlannedSegment*& out) {
  if (!enabled_) return source_(out);
  while (count_ == 0) {
    if (done_) return end_status_;
    const PlannedSegment* in = nullptr;
    const SourceStatus st = source_(in);
    if (st != SourceStatus::Item) {
      done_ = true;
      end_status_ = st;
      if (have_last_) {  // the end (or a source error): arrive, then stand
        queue(half(last_, last_.seg.kind == MotionKind::Dwell, last_.seg.end));
        queue(half(last_, true, last_.seg.end));
      }
      continue;
    }
    out = in;
    if (in->profile.duration() <= 0.0) return SourceStatus::Item;  // takes no time: no stop of its own
    const bool stop_before = at_rest_;
    at_rest_ = in->profile.v1 <= 0.0;  // dwells too
    if (!stop_before) {
      last_ = *in;
      have_last_ = true;
      return SourceStatus::Item;
    }
    // A stop between last_ and in (or the start): arrive, then depart.
    const Pose at = have_last_ ? last_.seg.end : in->seg.start;
    queue(have_last_ ? half(last_, last_.seg.kind == MotionKind::Dwell, at) : half(*in, true, at));
    queue(half(*in, in->seg.kind == MotionKind::Dwell, at));
    queue(*in);
    last_ = *in;
    have_last_ = true;
  }
  out = &queue_[front_];
  front_ = (front_ + 1) % queue_.size();
  --count_;
  return SourceStatus::Item;
}

JerkFilter::JerkFilter(std::uint32_t taps)
    : taps_(std::max<std::uint32_t>(1, taps)), delay_(taps_ / 2), ring_(taps_) {}

PeriodSample JerkFilter::filter(const PeriodSample& in) {
  const double m = taps_;
  if (!started_) {
    // The machine stood at the first pose: a window full of it.
    std::fill(ring_.begin(), ring_.end(), in);
    pose_sum_ = in.pose * m;
    speed_sum_ = in.speed * m;
    power_sum_ = static_cast<double>(in.power_pct) * m;
    moving_ = in.speed != 0.0 ? static_cast<int>(taps_) : 0;
    lit_ = in.power_pct != 0.0f ? static_cast<int>(taps_) : 0;
    same_ = taps_;
    started_ = true;
  }
  const std::size_t newest = (next_ + taps_ - 1) % taps_;
  same_ = in.pose == ring_[newest].pose ? std::min(same_ + 1, taps_) : 1;
  PeriodSample& old = ring_[next_];
  pose_sum_ += in.pose - old.pose;
  speed_sum_ += in.speed - old.speed;
  power_sum_ += static_cast<double>(in.power_pct) - static_cast<double>(old.power_pct);
  moving_ += (in.speed != 0.0) - (old.speed != 0.0);
  lit_ += (in.power_pct != 0.0f) - (old.power_pct != 0.0f);
  old = in;
  next_ = (next_ + 1) % taps_;
  // Where the window is constant the sums restart exactly: no drift carried.
  if (same_ == taps_) pose_sum_ = in.pose * m;
  if (moving_ == 0) speed_sum_ = 0.0;
  if (lit_ == 0) power_sum_ = 0.0;

  const PeriodSample& centre = ring_[(next_ + taps_ - 1 - delay_) % taps_];
  PeriodSample out = centre;
  out.t_s = in.t_s;
  out.pose = same_ == taps_ ? in.pose : pose_sum_ / m;
  out.speed = speed_sum_ / m;
  if (centre.power_cap_pct > 0.0f)  // M4: power follows the (filtered) speed
    out.power_pct = static_cast<float>(std::min<double>(centre.power_cap_pct, power_sum_ / m));
  out.end_of_program = in.end_of_program;
  return out;
}

}  // namespace lcnc
