// The kernel's own single-axis moves, one step per period, in the Jog and
// Homing states (the path's motion comes from the position buffer instead):
//
//   jog    a distance at a quarter of the axis's top speed, clamped to the
//          soft limits of a homed axis;
//   home   search toward the switch at the search speed, brake, back off at
//          the latch speed until the switch releases — that step is the
//          switch's position — brake, and re-base the axis's coordinate
//          there (the home position).
//
// A command in (start_jog, start_home, stop, cancel), one step out per
// period (next); the kernel applies what a step reports (the move done, the
// axis homed, the search failed). RT path: no allocation, no lock, no
// syscall.
#pragma once

#include <array>
#include <cstdint>

#include "machine/machine_config.h"
#include "machine/pulse_sink.h"
#include "rt/axis_move.h"

namespace lcnc::rt {

class AxisMover {
 public:
  struct AxisLimits {
    bool present = false;
    std::int64_t min_steps = 0, max_steps = 0;  // soft limits (±∞ for a wrapping rotary axis)
    double jog_speed = 0.0;                     // steps/s
    double accel = 0.0;                         // steps/s², jog and homing
    double search_speed = 0.0;                  // steps/s, signed toward the switch; 0: no homing
    double latch_speed = 0.0;                   // steps/s, > 0
    std::int64_t home_steps = 0;                // coordinate of the switch
  };

  enum class Event : std::uint8_t {
    None,
    Done,          // the move is over (a jog's end, a stopped homing at rest)
    Homed,         // the axis is homed: its coordinate is now `rebased`
    SearchFailed,  // twice the travel and no switch: braking, then Done
  };
  struct Step {
    std::int32_t steps = 0;  // the axis's steps this period
    Event event = Event::None;
    std::int64_t rebased = 0;  // Homed: the axis's new coordinate, steps
  };

  // `ramp_rate_per_s`: the feed override ramp's top rate (rt/feed_override.h),
  // which scales these moves' periods too and so takes its share of each
  // axis's acceleration.
  AxisMover(const MachineConfig& machine, double ramp_rate_per_s) noexcept;

  [[nodiscard]] const AxisLimits& limits(int axis) const noexcept { return axes_[axis]; }
  [[nodiscard]] bool can_home(int axis) const noexcept { return axes_[axis].search_speed != 0.0; }
  // The axis moving, or -1.
  [[nodiscard]] int axis() const noexcept { return axis_; }

  // A jog of `axis` from `pos` to `target` (steps), clamped to the soft
  // limits when the axis is homed; returns the steps it falls short by.
  std::int64_t start_jog(int axis, std::int64_t pos, std::int64_t target, bool homed,
                         double period_s) noexcept;
  // Homing of `axis`, `on_switch` already (then it backs off at once).
  void start_home(int axis, bool on_switch, double period_s) noexcept;
  // The operator's stop: brake, then Done.
  void stop() noexcept;
  // An e-stop: nothing moves from this period on.
  void cancel() noexcept;

  // This period's step; `pos`: the moving axis's coordinate now, `inputs`:
  // this period's switches.
  [[nodiscard]] Step next(const MachineInputs& inputs, std::int64_t pos) noexcept;
  // The steps the moving axis took this period (a homing's search counts
  // its travel).
  void travelled(std::int64_t steps) noexcept {
    if (homing_) travel_ += steps;
  }

 private:
  enum class HomePhase : std::uint8_t { Search, SearchBrake, Latch, LatchBrake };
  // Homing's phase change this period; true when it takes no step (Done, Homed).
  bool home_phase(const MachineInputs& inputs, std::int64_t pos, Step& out) noexcept;

  std::array<AxisLimits, kAxisCount> axes_{};
  AxisMove move_;
  int axis_ = -1;
  bool homing_ = false;
  bool abort_ = false;  // stopped by the operator or the search's failure
  HomePhase phase_ = HomePhase::Search;
  std::int64_t latch_ = 0;   // where the switch released
  std::int64_t travel_ = 0;  // steps searched so far
  double period_s_ = 0.0;
};

}  // namespace lcnc::rt
