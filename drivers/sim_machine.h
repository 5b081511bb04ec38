// The simulated machine: a faithful stand-in for the drives and the laser
// where no hardware exists (named as such, DESIGN §2). It receives the DDA's
// pulse frames, counts pulses per axis into machine positions (in steps),
// checks every frame as a drive would see it (pulse ticks increasing and
// inside the period, at most one pulse per tick), and follows the laser power.
// Called from the RT thread: noexcept, no allocation, no locks.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

#include "machine/pulse_sink.h"

namespace lcnc::drivers {

class SimMachine final : public PulseSink {
 public:
  explicit SimMachine(const std::array<std::int64_t, kAxisCount>& start_steps);

  void emit(const PulseFrame& frame) noexcept override;

  // Relaxed snapshots, safe from any thread; exact once the RT thread stopped.
  [[nodiscard]] std::int64_t position_steps(int axis) const noexcept {
    return pos_[axis].load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t pulses(int axis) const noexcept {
    return pulses_[axis].load(std::memory_order_relaxed);
  }
  // Frames whose pulse train a drive would reject (out-of-order or
  // out-of-period ticks). Must stay 0.
  [[nodiscard]] std::uint64_t bad_frames() const noexcept {
    return bad_frames_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t frames() const noexcept { return frames_.load(std::memory_order_relaxed); }
  // Laser-on time (periods with power > 0) and energy in %·periods.
  [[nodiscard]] std::uint64_t laser_on_periods() const noexcept {
    return laser_on_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] float power_pct() const noexcept { return power_.load(std::memory_order_relaxed); }

 private:
  // Written by the RT thread only (single writer); atomics so readers on
  // other threads see whole values (relaxed: counters, no ordering needed).
  std::array<std::atomic<std::int64_t>, kAxisCount> pos_{};
  std::array<std::atomic<std::uint64_t>, kAxisCount> pulses_{};
  std::atomic<std::uint64_t> bad_frames_{0};
  std::atomic<std::uint64_t> frames_{0};
  std::atomic<std::uint64_t> laser_on_{0};
  std::atomic<float> power_{0.0f};
};

}  // namespace lcnc::drivers
