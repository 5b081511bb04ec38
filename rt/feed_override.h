// Feed override by period scaling (DESIGN §5.5, seed 001 §3.5): the ramp of
// the override K that the RT kernel applies, one step per period.
//
// At override K an entry of the position buffer (planned for the nominal
// period T) is executed in T/K: the DDA clock runs at K·F. Along the plan's
// time τ (dτ/dt = K) an axis then moves at  v = K·v_p  and accelerates at
//
//     a = dv/dt = K²·a_p + (dK/dt)·v_p                                   (1)
//
// The planner keeps |v_p| ≤ vmax/K_max and |a_p| ≤ amax/K_max² (it plans at
// the highest override, machine.max_feed_override), so
//
//     |a| ≤ amax·K²/K_max² + |dK/dt|·vmax/K_max.                         (2)
//
// Ramp rate. K changes linearly in machine time at ρ = |dK/dt| — the seed's
// V(i+1) = V(i) + a·T(i) with V ∝ K and T(i) = T/K(i) the length of period i:
//
//     K(i+1) = K(i) ± ρ·T(i),   T(i) = T/K(i)  (T while held)           (3)
//
// ρ spends a fixed share s = kOverrideRampShare of every axis's acceleration
// on the ramp term of (2):
//
//     ρ = s · K_max · min_axes(amax / vmax)                              (4)
//
// so (dK/dt)·v_p ≤ s·amax on every axis, and by (2) |a| ≤ amax for every
// K ≤ K_max·sqrt(1 − s). With s = 1/3 on the default machine (amax/vmax =
// 10 /s on every axis, K_max = 1.5): ρ = 5 /s — 100 % to 0 (a feed hold) or
// 0 to 100 % in 0.2 s, and within the limits at every K ≤ 122 %. Above that,
// only in the worst coincidence (an axis at its planned speed limit and at
// its planned acceleration limit in the ramp's direction at the same
// instant) can |a| reach (K²/K_max² + s)·amax ≤ 4/3·amax at K_max: the plan
// leaves no margin at K_max itself, so no ramp that can ever leave K_max fits
// there. Planning at a_p ≤ (1 − s)·amax/K_max² would close that gap.
//
// Hold. Below K_min the machine holds: no entry is executed (position held,
// laser off) and periods last T. K_min = sqrt(ρ·T): the step between held and
// moving at K_min (speed K_min·v_p within one period T/K_min) then costs
// K_min²·v_p/T = ρ·v_p, the ramp's own acceleration, so the hold is entered
// and left as smoothly as the ramp runs. A ramp down lands on K_min exactly
// before it holds, for the same reason. Non-zero targets below K_min are
// raised to K_min: it is the slowest the machine runs.
#pragma once

#include "machine/machine_config.h"

namespace lcnc::rt {

// Share s of each axis's acceleration that an override ramp may use, eq. (4).
inline constexpr double kOverrideRampShare = 1.0 / 3.0;

class FeedOverrideRamp {
 public:
  explicit FeedOverrideRamp(const MachineConfig& machine) noexcept;

  // ρ: |dK/dt| of the ramp, per second of machine time, eq. (4).
  [[nodiscard]] double rate_per_s() const noexcept { return rate_per_s_; }
  // Below this the machine holds.
  [[nodiscard]] double k_min() const noexcept { return k_min_; }
  [[nodiscard]] double k_max() const noexcept { return k_max_; }

  // A requested override as the ramp's target: ≤ 0 and NaN → 0 (hold),
  // (0, K_min) → K_min, above K_max → K_max.
  [[nodiscard]] double clamp_target(double k) const noexcept;

  // True while K holds the machine (K < K_min).
  [[nodiscard]] bool holds(double k) const noexcept { return k < k_min_; }

  // K for the next period, eq. (3): one step toward `target` after a period
  // of `length_s` (T/K, or T while held); never past the target.
  [[nodiscard]] double step(double k, double target, double length_s) const noexcept;

 private:
  double rate_per_s_;
  double k_min_;
  double k_max_;
};

}  // namespace lcnc::rt
