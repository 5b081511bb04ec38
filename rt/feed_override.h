// Feed override, the RT's part: the period scale K that the RT kernel
// applies, one step per period.
//
// The planner plans at the machine's full limits, and at the operator's
// override E when that is above 100 % (feed moves at E·F within the limits;
// each entry says the override it was planned at, k_plan). The RT runs an
// entry with every period scaled to T/K,
//
//     K = min(1, E / k_plan)                                             (0)
//
// so it only ever slows the plan down: a lowered override or a hold acts
// within a period, a raise shows once the planner's new entries arrive. At K
// an axis moves at v = K·v_p and accelerates at
//
//     a = dv/dt = K²·a_p + (dK/dt)·v_p                                   (1)
//
// with v_p, a_p the plan's. K² ≤ 1 keeps the first term within the limit;
// the second is the ramp's, and the plan leaves it only what its own
// acceleration does not use. Each entry carries that room (RampRoom,
// plan/ramp_room.h): |dK/dt| ≤ r0·(1 − K²·f), f for the ramp's direction.
//
// Ramp rate. K changes linearly in machine time at ρ = |dK/dt| — the paper's
// V(i+1) = V(i) + a·T(i) with V ∝ K and T(i) = T/K(i) the length of period i:
//
//     K(i+1) = K(i) ± ρ·T(i),   T(i) = T/K(i)  (T while held)           (2)
//
// ρ is at most ρ_max = s·min_axes(amax/vmax), s = kOverrideRampShare, and
// at most the entry's room. With s = 1/2 on the default machine (amax/vmax =
// 10 /s on every axis): ρ_max = 5 /s — 100 % to 0 (a feed hold) or 0 to
// 100 % in 0.2 s where the plan cruises. Where the plan brakes at an axis's
// full deceleration, a falling K waits (no room at K = 1) while the plan's
// own braking slows the machine; it goes on as soon as the braking eases.
//
// Hold. Below K_min the machine holds: no entry is executed (position held,
// laser off) and periods last T. K_min = sqrt(ρ_max·T): the step between
// held and moving at K_min (speed K_min·v_p within one period T/K_min) then
// costs K_min²·v_p/T = ρ_max·v_p, the ramp's own acceleration, so the hold
// is entered and left as smoothly as the ramp runs. A ramp down lands on
// K_min exactly before it holds, for the same reason. Non-zero targets
// below K_min are raised to K_min: it is the slowest the machine runs.
#pragma once

#include "machine/machine_config.h"
#include "plan/period_increment.h"

namespace lcnc::rt {

// Share s of each axis's acceleration per unit of speed that an override
// ramp may use at most (ρ_max).
inline constexpr double kOverrideRampShare = 0.5;

class FeedOverrideRamp {
 public:
  explicit FeedOverrideRamp(const MachineConfig& machine) noexcept;

  // ρ_max: the highest |dK/dt| of the ramp, per second of machine time.
  [[nodiscard]] double rate_per_s() const noexcept { return rate_per_s_; }
  // Below this the machine holds.
  [[nodiscard]] double k_min() const noexcept { return k_min_; }
  // The highest override the operator may set (machine.max_feed_override).
  [[nodiscard]] double k_max() const noexcept { return k_max_; }

  // A requested override E: ≤ 0 and NaN → 0 (hold), (0, K_min) → K_min,
  // above K_max → K_max.
  [[nodiscard]] double clamp_target(double k) const noexcept;
  // K for an entry planned at k_plan under override e, eq. (0): 0 for a
  // hold, else within [K_min, 1].
  [[nodiscard]] double period_scale(double e, double k_plan) const noexcept;

  // True while K holds the machine (K < K_min).
  [[nodiscard]] bool holds(double k) const noexcept { return k < k_min_; }

  // K for the next period, eq. (2): one step toward `target` after a period
  // of `length_s` (T/K, or T while held), at most as fast as `room` lets
  // the next entry's axes (a default RampRoom: ρ_max); never past the target.
  [[nodiscard]] double step(double k, double target, double length_s,
                            const RampRoom& room = RampRoom{}) const noexcept;

 private:
  double rate_per_s_;
  double k_min_;
  double k_max_;
};

}  // namespace lcnc::rt
