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
    c.velocity.limit = ax.max_velocity;
    c.acceleration.limit = ax.max_acceleration;
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
        if (!axes_[i].present) continue;
        const double v = std::abs(static_cast<double>(p1.pos[i] - p0.pos[i])) * unit_[i] / dt;
        axes_[i].velocity.take(v, unit_[i] / dt, p1.line, p1.t_ns);
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
        if (!axes_[i].present) continue;
        const double d2 = static_cast<double>(p2.pos[i] - p1.pos[i]) * unit_[i] / h2;
        const double d1 = static_cast<double>(p1.pos[i] - p0.pos[i]) * unit_[i] / h1;
        const double a = std::abs(2.0 * (d2 - d1) / (h1 + h2));
        axes_[i].acceleration.take(a, quant_factor * unit_[i], p1.line, p1.t_ns);
      }
    }
  }
}

void LimitReading::take(double value, double quant, std::uint32_t at_line, std::int64_t at_ns) noexcept {
  peak = std::max(peak, value);
  quantization = std::max(quantization, quant);
  const double over = value - limit - quant;
  if (over <= excess) return;
  excess = over;
  reading = value;
  reading_quantization = quant;
  line = at_line;
  time_s = static_cast<double>(at_ns) * 1e-9;
}

bool MotionCheck::ok() const noexcept {
  return std::none_of(axes_.begin(), axes_.end(), [](const AxisMotionCheck& c) {
    return c.velocity.excess > 0.0 || c.acceleration.excess > 0.0;
  });
}

std::vector<std::string> MotionCheck::breaches() const {
  std::vector<std::string> out;
  for (int i = 0; i < kAxisCount; ++i) {
    const bool rot = is_rotary(static_cast<Axis>(i));
    const struct {
      const LimitReading& r;
      const char* what;
      const char* unit;
      int window;
    } quantities[] = {{axes_[i].velocity, "velocity", rot ? "deg/s" : "mm/s", wv_},
                      {axes_[i].acceleration, "acceleration", rot ? "deg/s2" : "mm/s2", wa_}};
    for (const auto& q : quantities) {
      if (q.r.excess <= 0.0) continue;
      char msg[256];
      std::snprintf(msg, sizeof msg,
                    "axis %c %s %.1f %s over %d periods, above its limit %g (+%.1f quantization) "
                    "at line %u, t = %.4f s",
                    kAxisLetters[i], q.what, q.r.reading, q.unit, q.window, q.r.limit,
                    q.r.reading_quantization, q.r.line, q.r.time_s);
      out.emplace_back(msg);
    }
  }
  return out;
}

}  // namespace lcnc
