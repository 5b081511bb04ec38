// A run's own check of the motion it executed: per-axis velocity and
// acceleration measured from the step positions the RT thread sent, as an
// outsider with a position trace would measure them, against the machine's
// limits. Any breach makes the run fail (the CLI's exit 3).
//
// Measured over windows, because a trace is quantized to steps: a position
// is the true one within half a step (q = 1/steps_per_unit), so over one
// period T a speed reads within ±q/T of the truth and a second difference
// within ±4·(q/2)/T² = ±2q/T² — on a 1 µm axis at 75 µs that is 13 mm/s and
// 3.6·10⁵ mm/s², far beyond any limit. Over windows of W periods:
//
//   v_k = (p_k − p_{k−W}) / (t_k − t_{k−W})                 error ≤ q / Δt
//   a_k = 2·[(p_{k+W} − p_k)/h₂ − (p_k − p_{k−W})/h₁] / (h₁ + h₂)
//                         h₁ = t_k − t_{k−W}, h₂ = t_{k+W} − t_k
//                                             error ≤ 2q·(1/h₁ + 1/h₂)/(h₁ + h₂)
//
// Both are weighted averages of the true velocity and acceleration over the
// window (divided differences), so a motion within its limits never reads
// above limit + quantization error, and the check passes it; any reading
// above that is a real breach, never quantization. W is chosen per machine
// as the fewest periods that bring the quantization error under
// kVelocityQuantShare of the smallest velocity limit (kAccelQuantShare for
// acceleration); the report states both windows. A breach shorter than the
// acceleration window is averaged over it: a velocity step Δv reads as
// Δv/(W·T), so the window is part of what the check promises.
//
// Times are the trace's machine times, so a feed override (periods of T/K)
// is measured as executed. Before the first record the axes rest at the
// start, and after finish() at the last position: a jump at either end is
// measured like any other.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geom/pose.h"
#include "machine/machine_config.h"

namespace lcnc {

// The window's quantization error as a share of the smallest limit.
inline constexpr double kVelocityQuantShare = 0.02;
inline constexpr double kAccelQuantShare = 0.05;
// Longest windows, periods (on a coarse-stepped, low-limit axis the share
// would ask for more; the error bound then simply grows).
inline constexpr int kMaxVelocityWindow = 64;
inline constexpr int kMaxAccelWindow = 512;

// One quantity (an axis's velocity or acceleration) as read over the run.
struct LimitReading {
  double limit = 0.0;  // mm/s (mm/s²) or deg/s (deg/s²)
  double peak = 0.0;   // the largest reading
  // The largest quantization error of any window read (see above): a
  // reading within limit + this one keeps the limit.
  double quantization = 0.0;
  // The worst breach (reading − limit − its window's error; 0: none), what
  // read then, its window's error, and where.
  double excess = 0.0;
  double reading = 0.0, reading_quantization = 0.0;
  std::uint32_t line = 0;
  double time_s = 0.0;

  void take(double value, double quant, std::uint32_t at_line, std::int64_t at_ns) noexcept;
};

struct AxisMotionCheck {
  bool present = false;
  LimitReading velocity, acceleration;
};

class MotionCheck {
 public:
  // Machine time 0 at `start_steps`, at rest.
  MotionCheck(const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& start_steps);

  // One RT period: machine time at its end (ns), the commanded position
  // after it (steps) and the program line it executed.
  void add(std::int64_t t_ns, const std::array<std::int64_t, kAxisCount>& pos_steps, std::uint32_t line);
  // Records were lost (a trace ring overflowed): no window spans the gap;
  // counted, and a run with gaps is not fully checked.
  void gap();
  // The axes come to rest after the last record.
  void finish();

  [[nodiscard]] int velocity_window() const noexcept { return wv_; }
  [[nodiscard]] int acceleration_window() const noexcept { return wa_; }
  [[nodiscard]] double period_s() const noexcept { return period_s_; }
  [[nodiscard]] std::uint64_t gaps() const noexcept { return gaps_; }
  [[nodiscard]] const std::array<AxisMotionCheck, kAxisCount>& axes() const noexcept { return axes_; }
  // True when no axis read above its limits.
  [[nodiscard]] bool ok() const noexcept;
  // One line per breach, e.g. "axis X velocity 3400.2 mm/s > limit 500 (+13.3
  // quantization over 2 periods) at line 2, t = 0.0123 s"; empty when ok().
  [[nodiscard]] std::vector<std::string> breaches() const;

 private:
  struct Sample {
    std::int64_t t_ns = 0;
    std::array<std::int64_t, kAxisCount> pos{};
    std::uint32_t line = 0;
  };
  [[nodiscard]] const Sample& back(int k) const noexcept;  // k samples before the newest
  void push(const Sample& s);
  void measure();

  double period_s_;
  std::int64_t period_ns_;
  int wv_ = 1, wa_ = 1;
  std::array<double, kAxisCount> unit_{};  // mm or deg per step
  std::array<AxisMotionCheck, kAxisCount> axes_{};
  std::vector<Sample> ring_;  // the newest 2·wa_ + 1 samples
  std::size_t head_ = 0;      // next slot to write
  std::size_t count_ = 0;     // samples since the last (re)start, capped at the ring's size
  std::uint64_t gaps_ = 0;
};

}  // namespace lcnc
