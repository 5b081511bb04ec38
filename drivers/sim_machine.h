// The simulated machine: a faithful stand-in for the drives, the switches and
// the laser where no hardware exists (named as such, docs/design.md §2). It receives
// the DDA's pulse frames, counts pulses per axis into positions (in steps),
// checks every frame as a drive would see it (pulse ticks increasing and
// inside the period, at most one pulse per tick), and follows the laser power.
//
// Switches (read_inputs()) live in the sim's own step count — the position it
// counts from pulses, starting at start_steps — not in the kernel's idea of
// the position: at power-on the two differ by an unknown offset, which homing
// finds. A home switch is a cam, active from its trip point to the end of
// travel on its side; a hard limit is active at or beyond its position.
// An optional leadscrew pitch error per axis gives the actual carriage
// position: actual = counted + error(counted), error a PitchTable in steps.
//
// send() and read_inputs() are called from the RT thread: noexcept, no
// allocation, no locks. Getters and set_estop_input() are safe from any thread.
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>

#include "machine/machine_config.h"
#include "machine/pulse_sink.h"

namespace lcnc::drivers {

// The side of a switch's trip point on which it is active.
enum class SwitchSide : std::uint8_t { Below, Above };

struct HomeSwitch {
  std::int64_t trip_steps = 0;            // sim count where the switch trips
  SwitchSide active = SwitchSide::Below;  // active at ≤ trip (Below) or ≥ trip (Above)
};

// The switches of one axis, in the sim's step count. Empty = not fitted.
struct SimSwitches {
  std::optional<HomeSwitch> home;
  std::optional<std::int64_t> limit_min_steps;  // active at count ≤ this
  std::optional<std::int64_t> limit_max_steps;  // active at count ≥ this
};

// Hard limit switches sit this far beyond the soft limits min/max (mm or deg).
inline constexpr double kHardLimitBeyondSoft = 2.0;

// The switches as a real machine is wired: hard limits kHardLimitBeyondSoft
// beyond min/max (none on a wrapping axis), the home switch at home_position
// active toward the sign of home_search_velocity (a search toward −: Below).
// Sim count = machine position · steps_per_unit + raw_offset_steps, rounded
// to the nearest step: with a non-zero offset the sim's counting starts where
// the kernel does not expect it, as on a machine just switched on.
// Axes not present get no switches.
[[nodiscard]] std::array<SimSwitches, kAxisCount> wired_switches(
    const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& raw_offset_steps = {});

class SimMachine final : public PulseSink {
 public:
  // No switches, no pitch error.
  explicit SimMachine(const std::array<std::int64_t, kAxisCount>& start_steps);
  // With switches and, optionally, a leadscrew pitch error per axis (a
  // PitchTable in steps: positions in counted steps, values in steps; empty =
  // a perfect screw). Tables are copied here, once.
  SimMachine(const std::array<std::int64_t, kAxisCount>& start_steps,
             const std::array<SimSwitches, kAxisCount>& switches,
             const std::array<PitchTable, kAxisCount>& pitch_error_steps = {});

  void send(const PulseFrame& frame) noexcept override;
  // Switch states at the current counted positions, and the e-stop input.
  [[nodiscard]] MachineInputs read_inputs() noexcept override;

  // The e-stop button, pressed (true) or released, from any thread.
  // Relaxed store, paired with the relaxed load in read_inputs(): a lone
  // flag, nothing else is published with it.
  void set_estop_input(bool pressed) noexcept { estop_.store(pressed, std::memory_order_relaxed); }
  // The program's digital inputs (M66), bit n: P n; from any thread (relaxed,
  // as the e-stop).
  void set_digital_inputs(std::uint8_t bits) noexcept { digital_in_.store(bits, std::memory_order_relaxed); }
  // The feed inputs (M52 adaptive feed, 0 … 1; M53 feed hold); from any
  // thread (relaxed, as the e-stop).
  void set_adaptive_feed(float factor) noexcept { adaptive_feed_.store(factor, std::memory_order_relaxed); }
  void set_feed_hold_input(bool on) noexcept { feed_hold_.store(on, std::memory_order_relaxed); }

  // Relaxed snapshots, safe from any thread; exact once the RT thread stopped.
  [[nodiscard]] std::int64_t position_steps(int axis) const noexcept {
    return pos_[axis].load(std::memory_order_relaxed);
  }
  // Where the carriage really is: counted + pitch error(counted), rounded to
  // the nearest step. Equals position_steps() without an error table.
  [[nodiscard]] std::int64_t actual_position_steps(int axis) const noexcept {
    const std::int64_t counted = position_steps(axis);
    if (pitch_error_steps_[axis].empty()) return counted;
    return counted + std::llround(pitch_error_steps_[axis].at(static_cast<double>(counted)));
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
  // Fixed at construction, read-only afterwards (so shared without sync).
  std::array<SimSwitches, kAxisCount> switches_{};
  std::array<PitchTable, kAxisCount> pitch_error_steps_{};
  // Written by the RT thread only (single writer); atomics so readers on
  // other threads see whole values (relaxed: counters, no ordering needed).
  std::array<std::atomic<std::int64_t>, kAxisCount> pos_{};
  std::array<std::atomic<std::uint64_t>, kAxisCount> pulses_{};
  std::atomic<std::uint64_t> bad_frames_{0};
  std::atomic<std::uint64_t> frames_{0};
  std::atomic<std::uint64_t> laser_on_{0};
  std::atomic<float> power_{0.0f};
  // Written by any thread (set_estop_input), read by read_inputs().
  std::atomic<bool> estop_{false};
  std::atomic<std::uint8_t> digital_in_{0};
  std::atomic<float> adaptive_feed_{1.0f};
  std::atomic<bool> feed_hold_{false};
};

}  // namespace lcnc::drivers
