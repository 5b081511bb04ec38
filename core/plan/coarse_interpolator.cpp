#include "plan/coarse_interpolator.h"

#include <algorithm>
#include <cmath>

#include "plan/tolerances.h"

namespace lcnc {

CoarseInterpolator::CoarseInterpolator(const MachineConfig& machine, PlannedSource source)
    : period_s_(machine.period_s()), source_(std::move(source)) {}

bool CoarseInterpolator::pull() {
  for (;;) {
    const PlannedSegment* next = nullptr;
    const SourceStatus st = source_(next);
    if (st == SourceStatus::Error) error_ = true;
    if (st != SourceStatus::Item) return false;
    ++started_;
    // A zero-length move takes no time: read on.
    if (next->profile.duration() > 0.0) {
      cur_ = next;
      duration_ = next->profile.duration();
      profile_ = next->profile;
      s_from_ = 0.0;
      const Segment& s = next->seg;
      end_ = End{s.end, next->profile.v1, s.line, next->index, s.kind};
      pause_ = pause_ || s.pause;  // until a sample carries it
      if (s.wait_input >= 0) {
        wait_input_ = s.wait_input;
        wait_mode_ = s.wait_mode;
        wait_timeout_s_ = s.wait_timeout_s;
      }
      const bool cut = s.kind == MotionKind::Linear || s.kind == MotionKind::Arc;
      // M4 on a cut: power follows speed; at no programmed speed, none
      dynamic_ = cut && s.laser == LaserMode::Dynamic && next->programmed_speed > plan::kMinVelocity;
      power_pct_ = s.power_pct;
      // M4's power follows the speed against the program's F, not the F
      // times the override the segment is planned at: the RT scales it by
      // the K it runs at (≤ 1) and caps it at the programmed power.
      programmed_speed_ = next->programmed_speed / next->k_plan;
      k_plan_ = static_cast<float>(next->k_plan);
      // otherwise constant: M3 on cuts and dwells, nothing on rapids or with the laser off
      power_ = (s.laser == LaserMode::Constant && s.kind != MotionKind::Rapid)
                   ? static_cast<float>(s.power_pct)
                   : 0.0f;
      power_cap_ = cut && s.laser == LaserMode::Dynamic ? static_cast<float>(s.power_pct) : 0.0f;
      outputs_ = static_cast<std::uint16_t>(s.digital_out | (s.mist ? kOutputMist : 0) |
                                            (s.flood ? kOutputFlood : 0));
      analog_ = s.analog_out;
      feed_control_ = s.feed_control;
      return true;
    }
  }
}

SourceStatus CoarseInterpolator::next(PeriodSample& out) {
  if (done_) return error_ ? SourceStatus::Error : SourceStatus::End;
  if (cur_ == nullptr && !pull()) {
    done_ = true;
    return error_ ? SourceStatus::Error : SourceStatus::End;
  }
  tau_ += period_s_;
  ++periods_;
  out.t_s = static_cast<double>(periods_) * period_s_;
  while (tau_ >= duration_) {
    const double rest = tau_ - duration_;
    if (!pull()) {
      // The end, or a source error after the last good segment: the plan
      // already ends at rest there (the look-ahead plans its window to
      // rest), so arrive exactly; next() says Error afterwards.
      out.pose = end_.pose;
      out.speed = end_.speed;
      out.power_pct = 0.0f;
      out.power_cap_pct = 0.0f;
      out.line = end_.line;
      out.segment = end_.segment;
      out.kind = end_.kind;
      out.end_of_program = true;
      out.pause = false;
      out.wait_input = -1;
      out.outputs = outputs_;
      out.analog = analog_;
      out.feed_control = feed_control_;
      done_ = true;
      return SourceStatus::Item;
    }
    tau_ = rest;
  }
  const PlannedSegment& c = *cur_;
  double s, v;
  profile_.sample(tau_, s, v);
  if (end_.kind == MotionKind::Dwell)
    out.pose = end_.pose;
  else
    c.geo.at(s_from_ + s, out.pose);
  out.speed = v;
  out.power_pct = laser_power(v);
  out.power_cap_pct = power_cap_;
  out.k_plan = k_plan_;
  out.line = end_.line;
  out.segment = end_.segment;
  out.kind = end_.kind;
  out.end_of_program = false;
  out.pause = pause_;  // its first sample only
  out.outputs = outputs_;
  out.analog = analog_;
  out.feed_control = feed_control_;
  pause_ = false;
  out.wait_input = wait_input_;  // its first sample only, as a pause
  out.wait_mode = wait_mode_;
  out.wait_timeout_s = wait_timeout_s_;
  wait_input_ = -1;
  return SourceStatus::Item;
}

void CoarseInterpolator::raise_feed_scale(double k) {
  if (cur_ == nullptr || done_ || end_.kind != MotionKind::Linear || cur_->geo.is_arc() ||
      (feed_control_ & kFeedOverrideOff) != 0)
    return;
  const double v_new = std::min(cur_->v_limit, cur_->programmed_speed / cur_->k_plan * k);
  if (!(v_new > profile_.vc)) return;
  double s, v;
  profile_.sample(tau_, s, v);
  const double rest = cur_->geo.length() - (s_from_ + s);
  if (!(rest > plan::kMinSegmentLength)) return;
  Trapezoid t;
  t.set(rest, profile_.accel, profile_.decel, v, v_new, profile_.v1);
  profile_ = t;
  s_from_ += s;
  duration_ = profile_.duration();
  tau_ = 0.0;
  k_plan_ = static_cast<float>(k);
}

StepQuantizer::StepQuantizer(const MachineConfig& machine, const Pose& start)
    : max_pulses_(static_cast<std::int32_t>(machine.dda.max_pulses())) {
  for (int i = 0; i < kAxisCount; ++i) {
    steps_per_unit_[i] = machine.axes[i].present ? machine.axes[i].steps_per_unit : 0.0;
    target_[i] = to_steps(i, start[i]);
    emitted_[i] = target_[i];
    if (machine.axes[i].present) present_[present_count_++] = i;
  }
}

bool StepQuantizer::owed() const noexcept {
  for (int i = 0; i < kAxisCount; ++i)
    if (target_[i] != emitted_[i]) return true;
  return false;
}

PeriodIncrement StepQuantizer::pay_owed(const PeriodSample& last) {
  PeriodSample s = last;
  s.pause = false;    // a pause holds once, on its own entry
  s.wait_input = -1;  // and so does an M66 wait
  return increment_for(s);
}

}  // namespace lcnc
