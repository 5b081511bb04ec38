#include "plan/motion_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lcnc {
namespace {

// The fewest periods W (1 … w_max) with error(W·T) ≤ budget.
template <typename Error>
int window_for(double period_s, double budget, int w_max, Error error) {
  int w = 1;
  while (w < w_max && error(w * period_s) > budget) ++w;
  return w;
}

}  // namespace

MotionCheck::MotionCheck(const MachineConfig& machine,
                         const std::array<std::int64_t, kAxisCount>& start_steps)
    : period_s_(machine.period_s()), period_ns_(machine.period_ns) {
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine.axes[i];
    AxisMotionCheck& c = axes_[i];
    c.present = ax.present;
    if (!ax.present) continue;
    c.velocity_limit = ax.max_velocity;
    c.acceleration_limit = ax.max_acceleration;
    const double q = unit_[i] = 1.0 / ax.steps_per_unit;
    wv_ = std::max(wv_, window_for(period_s_, kVelocityQuantShare * ax.max_velocity, kMaxVelocityWindow,
                                   [q](double dt) { return q / dt; }));
    wa_ = std::max(wa_, window_for(period_s_, kAccelQuantShare * ax.max_acceleration, kMaxAccelWindow,
                                   [q](double h) { return 2.0 * q / (h * h); }));
  }
  wa_ = std::max(wa_, wv_);
  ring_.resize(static_cast<std::size_t>(2 * wa_ + 1));
  // At rest at the start before machine time 0: the first periods are
  // measured against standing still.
  Sample rest;
  rest.pos = start_steps;
  for (int k = 2 * wa_; k >= 0; --k) {
    rest.t_ns = -static_cast<std::int64_t>(k) * period_ns_;
    push(rest);
  }
}

const MotionCheck::Sample& MotionCheck::back(int k) const noexcept {
  const std::size_t n = ring_.size();
  return ring_[(head_ + n - 1 - static_cast<std::size_t>(k)) % n];
}

void MotionCheck::push(const Sample& s) {
  ring_[head_] = s;
  head_ = (head_ + 1) % ring_.size();
  count_ = std::min(count_ + 1, ring_.size());
}

void MotionCheck::add(std::int64_t t_ns, const std::array<std::int64_t, kAxisCount>& pos_steps,
                      std::uint32_t line) {
  push(Sample{t_ns, pos_steps, line});
  measure();
}

void MotionCheck::gap() {
  ++gaps_;
  count_ = 0;
}

void MotionCheck::finish() {
  if (count_ == 0) return;
  Sample rest = back(0);
  for (int k = 0; k < 2 * wa_; ++k) {
    rest.t_ns += period_ns_;
    push(rest);
    measure();
  }
}

void MotionCheck::measure() {
  // Velocity over the newest wv_ periods.
  if (count_ > static_cast<std::size_t>(wv_)) {
    const Sample& p1 = back(0);
    const Sample& p0 = back(wv_);
    const double dt = static_cast<double>(p1.t_ns - p0.t_ns) * 1e-9;
    if (dt > 0.0) {
      for (int i = 0; i < kAxisCount; ++i) {
        AxisMotionCheck& c = axes_[i];
        if (!c.present) continue;
        const double v = std::abs(static_cast<double>(p1.pos[i] - p0.pos[i])) * unit_[i] / dt;
        const double quant = unit_[i] / dt;
        c.peak_velocity = std::max(c.peak_velocity, v);
        c.velocity_quantization = std::max(c.velocity_quantization, quant);
        const double excess = v - c.velocity_limit - quant;
        if (excess > c.velocity_excess) {
          c.velocity_excess = excess;
          c.velocity_reading = v;
          c.velocity_reading_quant = quant;
          c.velocity_line = p1.line;
          c.velocity_time_s = static_cast<double>(p1.t_ns) * 1e-9;
        }
      }
    }
  }
  // Acceleration about the sample wa_ periods back.
  if (count_ == ring_.size()) {
    const Sample& p2 = back(0);
    const Sample& p1 = back(wa_);
    const Sample& p0 = back(2 * wa_);
    const double h1 = static_cast<double>(p1.t_ns - p0.t_ns) * 1e-9;
    const double h2 = static_cast<double>(p2.t_ns - p1.t_ns) * 1e-9;
    if (h1 > 0.0 && h2 > 0.0) {
      const double quant_factor = 2.0 * (1.0 / h1 + 1.0 / h2) / (h1 + h2);
      for (int i = 0; i < kAxisCount; ++i) {
        AxisMotionCheck& c = axes_[i];
        if (!c.present) continue;
        const double d2 = static_cast<double>(p2.pos[i] - p1.pos[i]) * unit_[i] / h2;
        const double d1 = static_cast<double>(p1.pos[i] - p0.pos[i]) * unit_[i] / h1;
        const double a = std::abs(2.0 * (d2 - d1) / (h1 + h2));
        const double quant = quant_factor * unit_[i];
        c.peak_acceleration = std::max(c.peak_acceleration, a);
        c.acceleration_quantization = std::max(c.acceleration_quantization, quant);
        const double excess = a - c.acceleration_limit - quant;
        if (excess > c.acceleration_excess) {
          c.acceleration_excess = excess;
          c.acceleration_reading = a;
          c.acceleration_reading_quant = quant;
          c.acceleration_line = p1.line;
          c.acceleration_time_s = static_cast<double>(p1.t_ns) * 1e-9;
        }
      }
    }
  }
}

bool MotionCheck::ok() const noexcept {
  return std::none_of(axes_.begin(), axes_.end(), [](const AxisMotionCheck& c) {
    return c.velocity_excess > 0.0 || c.acceleration_excess > 0.0;
  });
}

std::vector<std::string> MotionCheck::breaches() const {
  std::vector<std::string> out;
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisMotionCheck& c = axes_[i];
    const bool rot = is_rotary(static_cast<Axis>(i));
    char msg[256];
    if (c.velocity_excess > 0.0) {
      std::snprintf(msg, sizeof msg,
                    "axis %c velocity %.1f %s over %d periods, above its limit %g (+%.1f "
                    "quantization) at line %u, t = %.4f s",
                    kAxisLetters[i], c.velocity_reading, rot ? "deg/s" : "mm/s", wv_,
                    c.velocity_limit, c.velocity_reading_quant, c.velocity_line,
                    c.velocity_time_s);
      out.emplace_back(msg);
    }
    if (c.acceleration_excess > 0.0) {
      std::snprintf(msg, sizeof msg,
                    "axis %c acceleration %.1f %s over %d periods, above its limit %g (+%.1f "
                    "quantization) at line %u, t = %.4f s",
                    kAxisLetters[i], c.acceleration_reading, rot ? "deg/s2" : "mm/s2", wa_,
                    c.acceleration_limit, c.acceleration_reading_quant, c.acceleration_line,
                    c.acceleration_time_s);
      out.emplace_back(msg);
    }
  }
  return out;
}

}  // namespace lcnc
