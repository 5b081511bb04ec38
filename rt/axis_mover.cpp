#include "rt/axis_mover.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace lcnc::rt {

AxisMover::AxisMover(const MachineConfig& machine, double ramp_rate_per_s) noexcept {
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine.axes[i];
    if (!ax.present) continue;
    AxisLimits& l = axes_[i];
    const double spu = ax.steps_per_unit;
    l.present = true;
    l.min_steps = std::llround(ax.min * spu);
    l.max_steps = std::llround(ax.max * spu);
    // The jog at a quarter of the speed — an operator's speed, not a rapid.
    // The override scales these moves' periods too, and its ramp adds up to
    // ρ_max·v (rt/feed_override.h, eq. 1): their acceleration leaves that
    // much of the axis's.
    l.jog_speed = 0.25 * ax.max_velocity * spu;
    l.search_speed = ax.home_search_velocity_or_default() * spu;
    l.latch_speed = ax.home_latch_velocity_or_default() * spu;
    const double fastest = std::max({l.jog_speed, std::abs(l.search_speed), std::abs(l.latch_speed)});
    l.accel =
        std::max(0.5 * ax.max_acceleration * spu, ax.max_acceleration * spu - ramp_rate_per_s * fastest);
    l.home_steps = std::llround(ax.home_position_or_default() * spu);
    // A rotary axis that wraps has no travel limits.
    if (ax.wrap) {
      l.min_steps = std::numeric_limits<std::int64_t>::min() / 2;
      l.max_steps = std::numeric_limits<std::int64_t>::max() / 2;
    }
  }
}

std::int64_t AxisMover::start_jog(int axis, std::int64_t pos, std::int64_t target, bool homed,
                                  double period_s) noexcept {
  const AxisLimits& l = axes_[axis];
  std::int64_t short_by = 0;
  if (homed) {
    const std::int64_t clamped = std::clamp(target, std::min(l.min_steps, pos), std::max(l.max_steps, pos));
    short_by = std::llabs(target - clamped);
    target = clamped;
  }
  axis_ = axis;
  homing_ = false;
  abort_ = false;
  move_.start(target - pos, l.jog_speed, l.accel, period_s);
  return short_by;
}

void AxisMover::start_home(int axis, bool on_switch, double period_s) noexcept {
  const AxisLimits& l = axes_[axis];
  axis_ = axis;
  homing_ = true;
  abort_ = false;
  travel_ = 0;
  period_s_ = period_s;
  if (on_switch) {
    // already on the switch: back off and latch
    phase_ = HomePhase::Latch;
    move_.start_velocity(l.search_speed < 0 ? l.latch_speed : -l.latch_speed, l.accel, period_s);
  } else {
    phase_ = HomePhase::Search;
    move_.start_velocity(l.search_speed, l.accel, period_s);
  }
}

void AxisMover::stop() noexcept {
  move_.stop();
  abort_ = true;
}

void AxisMover::cancel() noexcept {
  move_ = AxisMove{};
  axis_ = -1;
  homing_ = false;
}

AxisMover::Step AxisMover::next(const MachineInputs& inputs, std::int64_t pos) noexcept {
  Step out;
  if (axis_ < 0) return out;
  if (homing_ && home_phase(inputs, pos, out)) {
    axis_ = -1;
    homing_ = false;
    return out;
  }
  out.steps = move_.next();
  if (!homing_ && move_.done()) {
    axis_ = -1;
    out.event = Event::Done;
  }
  return out;
}

bool AxisMover::home_phase(const MachineInputs& inputs, std::int64_t pos, Step& out) noexcept {
  const AxisLimits& l = axes_[axis_];
  const bool on_switch = inputs.home[axis_];
  if (abort_) {  // stopped (the operator, a failed search): brake, then Done
    if (!move_.done()) return false;
    out.event = Event::Done;
    return true;
  }
  switch (phase_) {
    case HomePhase::Search:
      if (on_switch) {
        move_.stop();
        phase_ = HomePhase::SearchBrake;
      } else if (std::llabs(travel_) > 2 * (l.max_steps - l.min_steps) + 1) {
        // twice the travel and no switch: give up, brake, then Done
        out.event = Event::SearchFailed;
        move_.stop();
        abort_ = true;
      }
      return false;
    case HomePhase::SearchBrake:
      if (move_.done()) {
        phase_ = HomePhase::Latch;
        move_.start_velocity(l.search_speed < 0 ? l.latch_speed : -l.latch_speed, l.accel, period_s_);
      }
      return false;
    case HomePhase::Latch:
      if (!on_switch) {
        // the switch released at the last step: that is its position
        latch_ = pos;
        move_.stop();
        phase_ = HomePhase::LatchBrake;
      }
      return false;
    case HomePhase::LatchBrake:
      if (!move_.done()) return false;
      // re-base the coordinate: the latch position is home_steps
      out.event = Event::Homed;
      out.rebased = l.home_steps + (pos - latch_);
      return true;
  }
  return false;
}

}  // namespace lcnc::rt
