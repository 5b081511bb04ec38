// Acceleration-limited speed profile along one segment (grbl's trapezoid):
//
//   v
//   vc |     ________
//      |    /        \   .
//   v0 |___/          \___ v1
//      +---|--------|---|--> t
//        t_acc t_cruise t_dec
//
// From v0 accelerate at a to the cruise speed vc, cruise, decelerate at d to
// v1, over path length L. When L is too short to reach the target speed the
// peak solves (vc² − v0²)/2a + (vc² − v1²)/2d = L (triangle):
//   vc² = (2L + v0²/a + v1²/d) / (1/a + 1/d).
// Requires v1² ≤ v0² + 2aL and v0² ≤ v1² + 2dL, which the planner's passes
// guarantee. (a and d differ on arcs, where the centripetal load helps one
// and hinders the other.)
#pragma once

#include <algorithm>

namespace lcnc {

struct Trapezoid {
  double length = 0.0;  // L (path units)
  double accel = 0.0;   // a (path units/s²)
  double decel = 0.0;   // d (path units/s², > 0)
  double v0 = 0.0, vc = 0.0, v1 = 0.0;
  double t_acc = 0.0, t_cruise = 0.0, t_dec = 0.0;
  double s_acc = 0.0, s_cruise = 0.0;  // path length of the first two phases

  [[nodiscard]] static Trapezoid plan(double length, double accel, double v0, double v_target, double v1) {
    return plan(length, accel, accel, v0, v_target, v1);
  }
  [[nodiscard]] static Trapezoid plan(double length, double accel, double decel, double v0, double v_target,
                                      double v1) {
    Trapezoid p;
    p.set(length, accel, decel, v0, v_target, v1);
    return p;
  }
  // The same in place (the look-ahead's, per segment: no temporary copied).
  void set(double length, double accel, double decel, double v0, double v_target, double v1);
  // The triangle's peak speed squared: (vc² − v0²)/2a + (vc² − v1²)/2d = L.
  [[nodiscard]] static double peak_sqr(double length, double accel, double decel, double v0,
                                       double v1) noexcept {
    // (2L + v0²/a + v1²/d) / (1/a + 1/d), times a·d / a·d
    return (2.0 * length * accel * decel + v0 * v0 * decel + v1 * v1 * accel) / (accel + decel);
  }
  // A stand-still of the given duration (dwell): no path, only time.
  [[nodiscard]] static Trapezoid hold(double duration_s);

  [[nodiscard]] double duration() const noexcept { return t_acc + t_cruise + t_dec; }
  // Path length travelled after time t (clamped to [0, duration]).
  // (Inline: the coarse interpolator asks every period.)
  [[nodiscard]] double position(double t) const noexcept {
    if (t <= 0.0) return 0.0;
    if (t < t_acc) return v0 * t + 0.5 * accel * t * t;
    t -= t_acc;
    if (t < t_cruise) return s_acc + vc * t;
    t -= t_cruise;
    if (t < t_dec) return std::min(length, s_acc + s_cruise + vc * t - 0.5 * decel * t * t);
    return length;
  }
  // Both at once (the coarse interpolator asks for both every period).
  void sample(double t, double& s, double& v) const noexcept {
    if (t <= 0.0) {
      s = 0.0;
      v = v0;
    } else if (t < t_acc) {
      s = v0 * t + 0.5 * accel * t * t;
      v = v0 + accel * t;
    } else if ((t -= t_acc) < t_cruise) {
      s = s_acc + vc * t;
      v = vc;
    } else if ((t -= t_cruise) < t_dec) {
      s = std::min(length, s_acc + s_cruise + vc * t - 0.5 * decel * t * t);
      v = vc - decel * t;
    } else {
      s = length;
      v = v1;
    }
  }
  // Path speed at time t.
  [[nodiscard]] double speed(double t) const noexcept {
    if (t <= 0.0) return v0;
    if (t < t_acc) return v0 + accel * t;
    t -= t_acc;
    if (t < t_cruise) return vc;
    t -= t_cruise;
    if (t < t_dec) return vc - decel * t;
    return v1;
  }
};

}  // namespace lcnc
