// Optional jerk limit (S-curve acceleration, docs/design.md §5.2 "jerk limiting as an
// option"): a moving average of the planner's period samples, switched on by
// machine.max_jerk (J, mm/s³, linear axes).
//
// Filter. Each output pose is the mean of the last M input poses (M taps,
// τ = M·T). Averaging positions averages velocity and acceleration too, so
// neither can exceed its limit. The filtered acceleration changes by
// (a_in(k) − a_in(k−M))/M per period, so its jerk is at most
//     Δa_in / τ,   Δa_in = 2·a + kJunctionJumpShare·a                    (1)
// where 2·a is a swing from full acceleration to full deceleration and the
// second term the velocity jump the look-ahead allows at a near-tangent join
// (kJunctionJumpShare·amax·T per axis, plan/lookahead.h). So M = ⌈Δa_in/(J·T)⌉.
// The plan is at the machine's limits; the RT runs it at K ≤ 1 (the feed
// override's period scaling), where the acceleration is K²·a and the jerk
// K³·J of the plan's, no more.
// Rotary axes get the same window: one τ for all axes keeps the path's shape
// (their jerk is then at most Δa_in/τ of their own acceleration; J is in mm).
//
// Cost: path deviation. Where each axis accelerates at most a_i, the mean of
// M samples lies within
//     e_i = a_i·T²·(M² − 1)/24      (continuous: a_i·τ²/24)               (2)
// of the path point at the window's centre (Taylor: the linear term averages
// out). In X Y Z: e_f = |a|·T²(M² − 1)/24, |a| the norm of the linear axes'
// accelerations (√3·a for three equal axes: e_f ≈ √3·a³/(6·J²) with τ = 2a/J).
// Lines stay lines: the filter moves points only where the path curves.
// e_f comes out of the path tolerance P: corner blends get P − e_f − the
// half-step margin (plan/path_blender.h), so the executed path stays within P.
// (Not budgeted: a near-tangent join's velocity jump Δv ≤ kJunctionJumpShare·
// a·T moves the mean by at most Δv·τ/8, 0.3/M of e_f: < 1 % for M ≥ 70.)
//
// Trade-off: e_f grows as a³/J². When it would exceed half of the machine's
// path tolerance (machine.path_tolerance_mm), the planned acceleration of the
// linear axes is lowered by accel_scale so that e_f ≤ P/2 — with a jerk
// limit and a tight tolerance the machine cannot use its full acceleration.
// The default machine (X, Y at 5000 mm/s², Z at 3000, P = 0.01 mm): at
// J = 50 m/s³ it plans X and Y at 354 mm/s² (7.1 %), M = 198 (τ = 14.9 ms);
// at J = 500 m/s³ at 1625 mm/s² (32.5 %), M = 91 (τ = 6.8 ms).
// tests/vectors/plate.ngc then takes 4.95 s and 2.46 s instead of 1.66 s.
// The full acceleration needs J ≥ 2705 m/s³ at this P (or P ≥ 0.28 mm at
// 500 m/s³). BENCHMARKS.md has the bench cases.
//
// A program whose G64 P is below e_f + the half-step margin gets no corner
// blends (the tolerance left for them is ≤ 0): its corners are stopped at and
// reached exactly, lines stay on the path, but on curved segments (program
// arcs, near-tangent joins) the deviation can reach e_f, more than its P.
// Such a program needs a higher max_jerk (or its own P ≥ e_f). G61 programs
// likewise: exact at every corner, within e_f ≤ P_machine/2 on arcs.
//
// Exact stops (StopHolds). A moving average reaches a stop pose only once its
// whole window holds it, so wherever the plan comes to rest between two
// segments — G61 corners, stopped corners, dwells, rapid↔feed changes, the
// program's start and end — a hold of about M periods is inserted: at least M
// samples of the stop pose. The filtered path then reaches the stop pose
// exactly (JerkFilter outputs the pose itself when all M inputs are equal)
// and leaves it smoothly. A hold costs τ; an S-curve stop costs about the same
// (2·a/J more than the trapezoid's stop and start).
//
// Laser, line and segment of an output are those of the input at the window's
// centre (delay ⌊M/2⌋ ≈ (M − 1)/2, the filter's group delay), so they stay in
// step with the delayed motion. A hold is two halves: the first carries the
// arriving segment's kind and laser, the second the departing one's — the
// filtered head is still moving along that segment while the window's centre
// is in that half. M4 power is 0 at rest, and the output's M4 power is the
// window's mean of the input power: power ∝ speed, and the speed is filtered
// likewise. M3 keeps its constant power through a hold next to a cut: the
// head moves on that cut until the window's centre is at the corner and
// stands there one or two periods — as an unfiltered exact stop passes
// through speed 0 with M3 on. Halves next to a dwell, the start or the end
// stand still with the laser off, so a G4 with M3 fires exactly its own time.
// An output moves only while its centre is in motion or in a hold half
// next to motion, so Dwell outputs (which the RT kernel runs at the nominal
// period whatever the override) never move.
//
// The final pose is exact (the end hold fills the window); Σ steps equals the
// commanded end as without the filter.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "machine/machine_config.h"
#include "plan/coarse_interpolator.h"
#include "plan/planned_segment.h"

namespace lcnc {

// The filter's parameters for a machine (planned units).
struct JerkLimit {
  std::uint32_t taps = 1;    // M: periods averaged; 1 = no filter
  double accel_scale = 1.0;  // planned linear-axis accelerations × this (≤ 1)
  double error_mm = 0.0;     // e_f, eq. (2): largest X Y Z deviation the filter adds

  [[nodiscard]] bool enabled() const noexcept { return taps > 1; }
};

// M, the acceleration scale and e_f from machine.max_jerk, eq. (1) and (2),
// with e_f ≤ machine.path_tolerance_mm / 2. Disabled when max_jerk is 0 or
// when the trapezoids already keep the jerk (M would be 1).
[[nodiscard]] JerkLimit jerk_limit(const MachineConfig& machine);

// The machine as the look-ahead plans it: linear axes' max_acceleration
// × accel_scale; everything else as given.
[[nodiscard]] MachineConfig planned_machine(const MachineConfig& machine, const JerkLimit& limit);

// Inserts the holds at every stop of the planned segment stream (above).
// Streaming: holds back nothing; at most three segments queued.
class StopHolds {
 public:
  StopHolds(PlannedSource source, const JerkLimit& limit, double period_s);
  // The next segment, valid until next() is called again.
  [[nodiscard]] SourceStatus next(const PlannedSegment*& out);

 private:
  // Half a hold at `at`, like `neighbour` (its kind and laser) or, when
  // `stand`, a laser-off stand-still.
  [[nodiscard]] PlannedSegment half(const PlannedSegment& neighbour, bool stand, const Pose& at) const;
  void queue(const PlannedSegment& s) { queue_[(front_ + count_++) % queue_.size()] = s; }

  PlannedSource source_;
  bool enabled_;
  double half_s_;  // duration of one half: (⌈M/2⌉ + 1)·T, so ≥ ⌈M/2⌉ samples each
  std::array<PlannedSegment, 3> queue_;
  std::size_t front_ = 0, count_ = 0;
  PlannedSegment last_;  // the last segment handed out that takes time
  bool have_last_ = false;
  bool at_rest_ = true;  // last_ ends at speed 0 (or there is none yet)
  bool done_ = false;
  SourceStatus end_status_ = SourceStatus::End;
};

// The moving average over M period samples. Allocates its window once.
class JerkFilter {
 public:
  explicit JerkFilter(std::uint32_t taps);

  // One period's sample in, the filtered sample for the same period out.
  // The first sample fills the window (the machine stood there before).
  [[nodiscard]] PeriodSample filter(const PeriodSample& in);

 private:
  std::uint32_t taps_;
  std::uint32_t delay_;             // ⌊M/2⌋: where the window's centre is
  std::vector<PeriodSample> ring_;  // the last M inputs; ring_[next_] is the oldest
  std::size_t next_ = 0;
  bool started_ = false;
  // Running sums over the window. Rounding drifts them by ~1 ulp of the sum
  // per period (1e-13 mm over a window of poses of 1 m); they restart from
  // the pose at every stop, where the window is constant.
  Pose pose_sum_ = Pose::Zero();
  double speed_sum_ = 0.0;
  double power_sum_ = 0.0;
  // Inputs in the window that move / have power: at 0 their sum is exactly 0
  // (M4 is dark at rest, not at 1e-15 %).
  int moving_ = 0, lit_ = 0;
  std::uint32_t same_ = 0;  // the last inputs with one pose (up to M)
};

}  // namespace lcnc
