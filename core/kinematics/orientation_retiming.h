// Re-timing of an orientation move under the A and C limits (the fallback of
// the pole-smoothed interpolator when the pole is farther than the
// tolerance, and the reference for the planner integration): the fastest
// rest-to-rest time law u(t) within
//   |X'·u̇| ≤ v_max,   |X''·u̇² + X'·ü| ≤ a_max      (X = A, C; ' = d/du)
// and the programmed caps u̇ ≤ max_u_rate, |ü| ≤ max_u_accel.
// Method (the look-ahead of docs/design.md §5.2 along u): on a grid of
// kRetimeSamples, the velocity limit curve
//   u̇_lim = min(v_max/|X'|, sqrt(½·a_max/|X''|), max_u_rate)
// gives half of each axis' acceleration to the curvature term X''·u̇²; the
// other half bounds the path acceleration |ü| ≤ ½·a_max/|X'| (and
// max_u_accel). A forward pass u̇²(i+1) ≤ u̇²(i) + 2·ü·Δu from rest and a
// backward pass to rest give the speed at each grid point; between points
// ü is constant. Away from the pole the programmed caps rule, so only the
// pole pass is slowed.
#pragma once

#include <vector>

#include "kinematics/orientation_interpolation.h"

namespace lcnc {

namespace kin {
// Grid of the re-timing: resolves C's swing at a pole pass of δ down to
// about Θ/16384 of arc (0.004° on a 60° move).
inline constexpr int kRetimeSamples = 16384;
}  // namespace kin

class RetimedLaw {
 public:
  [[nodiscard]] double duration_s() const noexcept { return t_s_.empty() ? 0.0 : t_s_.back(); }
  // u at time t (0 before, 1 after the move).
  [[nodiscard]] double u_at(double t_s) const noexcept;
  // Peak du/dt (1/s).
  [[nodiscard]] double peak_u_rate() const noexcept;

 private:
  friend RetimedLaw retime(const OrientationMove&, const RotaryLimits&, double, double);
  std::vector<double> t_s_;   // time at grid point i
  std::vector<double> rate_;  // du/dt at grid point i
};

// The re-timed law of a move (caps > 0; infinity for none).
[[nodiscard]] RetimedLaw retime(const OrientationMove& move, const RotaryLimits& limits, double max_u_rate,
                                double max_u_accel);

// evaluate() along a re-timed law.
[[nodiscard]] OrientationReport evaluate(const OrientationMove& move, const RetimedLaw& law,
                                         double sample_dt_s);

}  // namespace lcnc
