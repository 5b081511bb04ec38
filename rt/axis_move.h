// One axis moved by the kernel itself, not by the planner (jog and homing):
// a trapezoidal velocity profile in steps, produced one
// period at a time on the RT thread. Whole steps go out each period; the
// fraction is carried, so a move of D steps emits exactly D steps.
//
// Each period the speed is  v' = min(vmax, v + a·T, sqrt(2·a·r))  where r is
// the distance left: it accelerates at a, cruises at vmax and brakes at a so
// that it reaches r = 0 at rest. A velocity move (homing search) has no end
// until stop(), which brakes at a from the current speed.
#pragma once

#include <cstdint>

namespace lcnc::rt {

class AxisMove {
 public:
  // Moves `distance_steps` (signed) at up to vmax steps/s, accelerating at
  // amax steps/s², starting from rest; period_s is the period length.
  void start(std::int64_t distance_steps, double vmax, double amax, double period_s) noexcept;
  // Moves at `velocity` steps/s (signed) until stop(), from rest.
  void start_velocity(double velocity, double amax, double period_s) noexcept;
  // Brakes to rest at amax as soon as possible (the distance it takes is
  // rounded up to whole steps).
  void stop() noexcept;

  // The next period's increment, in steps (0 once done).
  [[nodiscard]] std::int32_t next() noexcept;
  [[nodiscard]] bool done() const noexcept { return !active_; }
  // Current speed, steps/s (signed).
  [[nodiscard]] double velocity() const noexcept { return dir_ * v_; }

 private:
  bool active_ = false;
  bool unbounded_ = false;  // a velocity move before stop()
  int dir_ = 1;
  double v_ = 0.0;  // speed, steps/s, ≥ 0
  double vmax_ = 0.0;
  double amax_ = 0.0;
  double period_s_ = 0.0;
  double left_ = 0.0;         // distance left, steps, ≥ 0 (bounded moves)
  double travelled_ = 0.0;    // exact distance so far, steps
  std::int64_t emitted_ = 0;  // whole steps emitted so far (unsigned sense)
  std::int64_t total_ = 0;    // whole steps of a bounded move
};

}  // namespace lcnc::rt
