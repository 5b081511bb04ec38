#include "plan/increment_guard.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace lcnc {

IncrementGuard::IncrementGuard(const MachineConfig& machine,
                               const std::array<std::int64_t, kAxisCount>& start_steps)
    : machine_(machine), at_(start_steps) {
  const double t = machine.period_s();
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine.axes[i];
    const bool limited = ax.present && !ax.wrap;
    min_steps_[i] = limited ? std::llround(ax.min * ax.steps_per_unit) : INT64_MIN / 2;
    max_steps_[i] = limited ? std::llround(ax.max * ax.steps_per_unit) : INT64_MAX / 2;
    if (!ax.present) continue;
    max_inc_[i] = static_cast<std::int64_t>(std::floor(ax.max_velocity * t * ax.steps_per_unit)) + 1;
    max_inc_change_[i] =
        static_cast<std::int64_t>(std::floor(ax.max_acceleration * t * t * ax.steps_per_unit)) + 2;
  }
}

void IncrementGuard::refuse(ErrorCode code, const PeriodIncrement& inc, const char* msg) {
  error_ = Diagnostic{code, {}, inc.line, 0, msg};
}

bool IncrementGuard::admit(const PeriodIncrement& inc) {
  const double t = machine_.period_s();
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t d = inc.steps[i];
    const std::int64_t change = d - last_inc_[i];
    if (d == 0 && change == 0) continue;
    const AxisConfig& ax = machine_.axes[i];
    const bool rot = is_rotary(static_cast<Axis>(i));
    const char* unit = rot ? "deg" : "mm";
    char msg[240];
    const std::int64_t next = at_[i] + d;
    if (next < min_steps_[i] || next > max_steps_[i]) {
      std::snprintf(msg, sizeof msg,
                    "soft limit: axis %c would reach %.4f, outside its travel %g … %g; the job "
                    "stops short along the path",
                    kAxisLetters[i], static_cast<double>(next) / ax.steps_per_unit, ax.min, ax.max);
      refuse(ErrorCode::RtSoftLimit, inc, msg);
      return false;
    }
    if (std::llabs(d) > max_inc_[i]) {
      const double dist = static_cast<double>(std::llabs(d)) / ax.steps_per_unit;
      std::snprintf(msg, sizeof msg,
                    "axis %c would move %.4f %s in one period (%.1f %s/s), above its velocity "
                    "limit %g; the job stops short along the path",
                    kAxisLetters[i], dist, unit, dist / t, unit, ax.max_velocity);
      refuse(ErrorCode::PlanBeyondLimit, inc, msg);
      return false;
    }
    if (std::llabs(change) > max_inc_change_[i]) {
      const double dv = static_cast<double>(std::llabs(change)) / ax.steps_per_unit / t;
      std::snprintf(msg, sizeof msg,
                    "axis %c would change speed by %.1f %s/s in one period (%.0f %s/s2), above "
                    "its acceleration limit %g; the job stops short along the path",
                    kAxisLetters[i], dv, unit, dv / t, unit, ax.max_acceleration);
      refuse(ErrorCode::PlanBeyondLimit, inc, msg);
      return false;
    }
  }
  for (int i = 0; i < kAxisCount; ++i) {
    at_[i] += inc.steps[i];
    last_inc_[i] = inc.steps[i];
  }
  return true;
}

}  // namespace lcnc
