// What the user asks of a decomposition: the contour speed and the limits of
// the two axis groups (docs/design.md §5.7, Kondratenko et al. (2015)). mm, s, mm/s, mm/s², degrees.
#pragma once

#include <cstdint>

#include "decompose/decompose_tolerances.h"

namespace lcnc::decompose {

enum class Mode : std::uint8_t {
  Seed,  // Kondratenko et al. (2015) eq. 1–13, faithfully (limits reported, not guaranteed)
  Sync,  // time-synchronous: S1(t) + S2(t) = S(t), limits guaranteed
};

// Sync mode: which of the feasible main paths (filter half-widths τ) to take.
enum class SyncGoal : std::uint8_t {
  SmoothestMain,   // the largest τ the field allows: lowest main-axis acceleration
  ShortestLeadIn,  // the smallest τ the main-axis limits allow: least time at
                   // rest before and after each contour (2τ per contour)
};

struct Options {
  Mode mode = Mode::Sync;
  double speed_mm_s = 100.0;  // contour speed vk (6 m/min)
  double main_accel_mm_s2 = kDefaultMainAccel_mm_s2;
  double main_speed_mm_s = kDefaultMainSpeed_mm_s;
  double aux_speed_mm_s = kDefaultAuxSpeed_mm_s;
  double aux_half_field_mm = kDefaultAuxHalfField_mm;     // |P|, |Q| ≤ this
  double critical_angle_deg = kDefaultCriticalAngle_deg;  // Seed mode only
  SyncGoal goal = SyncGoal::SmoothestMain;                // Sync mode only
};

}  // namespace lcnc::decompose
