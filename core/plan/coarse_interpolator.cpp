#include "plan/coarse_interpolator.h"

#include <algorithm>
#include <cmath>

#include "plan/tolerances.h"

namespace lcnc {

CoarseInterpolator::CoarseInterpolator(const MachineConfig& machine, PlannedSource source)
    : period_s_(machine.period_s()), source_(std::move(source)) {}

bool CoarseInterpolator::pull() {
  PlannedSegment next;
  for (;;) {
    const SourceStatus st = source_(next);
    if (st == SourceStatus::Error) error_ = true;
    if (st != SourceStatus::Item) return false;
    ++started_;
    if (next.profile.duration() > 0.0) {
      cur_ = std::move(next);
      have_cur_ = true;
      return true;
    }
    // A zero-length move takes no time; keep its pose as the current end.
    cur_ = std::move(next);
    have_cur_ = true;
  }
}

float CoarseInterpolator::laser_power(double speed) const {
  const Segment& s = cur_.seg;
  if (s.kind == MotionKind::Rapid) return 0.0f;
  if (s.kind == MotionKind::Dwell) {
    return s.laser == LaserMode::Constant ? static_cast<float>(s.power_pct) : 0.0f;
  }
  switch (s.laser) {
    case LaserMode::Off: return 0.0f;
    case LaserMode::Constant: return static_cast<float>(s.power_pct);
    case LaserMode::Dynamic: {
      if (cur_.programmed_speed <= plan::kMinVelocity) return 0.0f;
      const double k = std::clamp(speed / cur_.programmed_speed, 0.0, 1.0);
      return static_cast<float>(s.power_pct * k);
    }
  }
  return 0.0f;
}

SourceStatus CoarseInterpolator::next(PeriodSample& out) {
  if (done_) return error_ ? SourceStatus::Error : SourceStatus::End;
  if (!have_cur_ && !pull()) {
    done_ = true;
    return error_ ? SourceStatus::Error : SourceStatus::End;
  }
  tau_ += period_s_;
  bool last = false;
  while (tau_ >= cur_.profile.duration()) {
    const double rest = tau_ - cur_.profile.duration();
    const PlannedSegment prev = cur_;
    if (!pull()) {
      if (error_) {
        done_ = true;
        return SourceStatus::Error;
      }
      cur_ = prev;
      tau_ = cur_.profile.duration();
      last = true;
      break;
    }
    tau_ = rest;
  }
  ++periods_;
  const double s = cur_.profile.position(tau_);
  const double v = cur_.profile.speed(tau_);
  out.t_s = static_cast<double>(periods_) * period_s_;
  out.pose = cur_.seg.kind == MotionKind::Dwell ? cur_.seg.end : cur_.geo.at(s);
  out.speed = v;
  out.power_pct = laser_power(v);
  out.power_cap_pct = cur_.seg.laser == LaserMode::Dynamic &&
                              (cur_.seg.kind == MotionKind::Linear || cur_.seg.kind == MotionKind::Arc)
                          ? static_cast<float>(cur_.seg.power_pct)
                          : 0.0f;
  out.line = cur_.seg.line;
  out.segment = cur_.index;
  out.kind = cur_.seg.kind;
  out.end_of_program = last;
  if (last) {
    out.pose = cur_.seg.end;
    out.power_pct = 0.0f;
    out.power_cap_pct = 0.0f;
    done_ = true;
  }
  return SourceStatus::Item;
}

StepQuantizer::StepQuantizer(const MachineConfig& machine, const Pose& start)
    : max_pulses_(static_cast<std::int32_t>(machine.dda.max_pulses())) {
  for (int i = 0; i < kAxisCount; ++i) {
    steps_per_unit_[i] = machine.axes[i].present ? machine.axes[i].steps_per_unit : 0.0;
    target_[i] = to_steps(i, start[i]);
    emitted_[i] = target_[i];
  }
}

std::int64_t StepQuantizer::to_steps(int axis, double pos) const noexcept {
  return std::llround(pos * steps_per_unit_[axis]);
}

PeriodIncrement StepQuantizer::emit(const PeriodSample& s) {
  PeriodIncrement inc;
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t owed = target_[i] - emitted_[i];
    const std::int64_t step = std::clamp<std::int64_t>(owed, -max_pulses_, max_pulses_);
    inc.steps[i] = static_cast<std::int32_t>(step);
    emitted_[i] += step;
  }
  inc.power_pct = s.power_pct;
  inc.power_cap_pct = s.power_cap_pct;
  inc.line = s.line;
  inc.segment = s.segment;
  inc.kind = s.kind;
  inc.end_of_program = s.end_of_program && !owed();
  return inc;
}

PeriodIncrement StepQuantizer::quantize(const PeriodSample& s) {
  for (int i = 0; i < kAxisCount; ++i) target_[i] = to_steps(i, s.pose[i]);
  return emit(s);
}

bool StepQuantizer::owed() const noexcept {
  for (int i = 0; i < kAxisCount; ++i)
    if (target_[i] != emitted_[i]) return true;
  return false;
}

PeriodIncrement StepQuantizer::pay_owed(const PeriodSample& last) { return emit(last); }

}  // namespace lcnc
