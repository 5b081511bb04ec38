// Acceleration-limited speed profile along one segment (grbl's trapezoid):
//
//   v
//   vc |     ________
//      |    /        \   .
//   v0 |___/          \___ v1
//      +---|--------|---|--> t
//        t_acc t_cruise t_dec
//
// From v0 accelerate at a to the cruise speed vc, cruise, decelerate at a to
// v1, over path length L. When L is too short to reach the target speed the
// peak is vc² = (2aL + v0² + v1²)/2 (triangle). Requires |v0² − v1²| ≤ 2aL,
// which the planner's passes guarantee.
#pragma once

namespace lcnc {

struct Trapezoid {
  double length = 0.0;  // L (path units)
  double accel = 0.0;   // a (path units/s²)
  double v0 = 0.0, vc = 0.0, v1 = 0.0;
  double t_acc = 0.0, t_cruise = 0.0, t_dec = 0.0;
  double s_acc = 0.0, s_cruise = 0.0;  // path length of the first two phases

  [[nodiscard]] static Trapezoid plan(double length, double accel, double v0, double v_target,
                                      double v1);
  // A stand-still of the given duration (dwell): no path, only time.
  [[nodiscard]] static Trapezoid hold(double duration_s);

  [[nodiscard]] double duration() const noexcept { return t_acc + t_cruise + t_dec; }
  // Path length travelled after time t (clamped to [0, duration]).
  [[nodiscard]] double position(double t) const noexcept;
  // Path speed at time t.
  [[nodiscard]] double speed(double t) const noexcept;
};

}  // namespace lcnc
