// Coarse interpolation (docs/design.md §5.3, Chi, Wu and Cui (2020) §3): the planned path sampled
// once per RT period T on one global time line. Segments shorter than one
// period's travel are consumed several per period, the time left over from
// one segment carried into the next — so no segment costs a whole period and
// no speed is capped by the period (Chi, Wu and Cui 2020).
//
//   sample k is the commanded pose at t = k·T, k = 1, 2, …; the last sample
//   is exactly the program's end pose.
//
// StepQuantizer turns poses into integer steps per period, carrying the
// remainder: each period the target is round(pose·steps_per_unit) and the
// increment is target − steps already emitted (clamped to the DDA's largest
// magnitude; what is clamped is carried to the next period). So Σ increments
// equals the commanded position in steps exactly, whatever the program.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "machine/machine_config.h"
#include "plan/period_increment.h"
#include "plan/planned_segment.h"

namespace lcnc {

struct PeriodSample : EntrySignals {
  PeriodSample() noexcept { kind = MotionKind::Dwell; }  // at rest until sampled
  double t_s = 0.0;                                      // end of the period
  Pose pose = Pose::Zero();                              // commanded pose at t_s (mm, deg)
  double speed = 0.0;                                    // path speed at t_s
  // The signals: the segment's (pause and the M66 wait on its first sample
  // only, as PeriodIncrement's).
};

class CoarseInterpolator {
 public:
  CoarseInterpolator(const MachineConfig& machine, PlannedSource source);
  // The next period's sample; End after the sample with end_of_program —
  // Error instead when the source failed: the motion before the failure
  // still ends at rest, with end_of_program, where its last segment ends.
  [[nodiscard]] SourceStatus next(PeriodSample& out);
  [[nodiscard]] std::uint64_t periods() const noexcept { return periods_; }
  [[nodiscard]] std::uint32_t segments_started() const noexcept { return started_; }
  // A feed override raised to k (Planner::set_feed_scale): the rest of the
  // current segment, when it is a straight cut, speeds up to F·k within its
  // axes' limits, from where and how fast it is now to the speed it was
  // planned to end at (the look-ahead plans what follows from there). Arcs,
  // rapids and dwells run on as planned.
  void raise_feed_scale(double k);

 private:
  // The next segment that takes time becomes the current one; false at the
  // end or on an error (the current one is then no longer valid: the last
  // sample comes from its end, kept apart).
  bool pull();
  [[nodiscard]] float laser_power(double speed) const noexcept {
    if (!dynamic_) return power_;
    // above 1 on a segment planned at an override above 100 %: the RT caps it
    const double k = std::max(speed / programmed_speed_, 0.0);
    return static_cast<float>(power_pct_ * k);
  }

  double period_s_;
  PlannedSource source_;
  // The current segment, as its source handed it out (valid until the
  // source is asked again), and its duration.
  const PlannedSegment* cur_ = nullptr;
  double duration_ = 0.0;
  // The current segment's profile from s_from_ on: its own, or the rest of
  // it re-planned for a raised feed override.
  Trapezoid profile_;
  double s_from_ = 0.0;
  // What every period of the current segment reports alike, read from it
  // once (not from its few hundred bytes each period): the laser power (a
  // constant, or M4's scaled by speed), the power cap; where it came from
  // and whether it is a dwell are in end_.
  bool pause_ = false;    // a pause pulled, not yet on a sample
  bool dynamic_ = false;  // M4 on a cut: power_pct_ scaled by speed / programmed_speed_
  float power_ = 0.0f, power_cap_ = 0.0f;
  std::int8_t wait_input_ = -1;  // an M66 segment's, until a sample carries it
  std::uint8_t wait_mode_ = 0;
  float wait_timeout_s_ = 0.0f;
  std::uint16_t outputs_ = 0;  // the segment's outputs word and analog values
  std::array<float, kAnalogOutputs> analog_{};
  std::uint8_t feed_control_ = 0;  // the segment's
  double power_pct_ = 0.0, programmed_speed_ = 0.0;
  float k_plan_ = 1.0f;
  // Where the current segment ends: the program's last sample.
  struct End {
    Pose pose = Pose::Zero();
    double speed = 0.0;
    std::uint32_t line = 0, segment = 0;
    MotionKind kind = MotionKind::Dwell;
  } end_;
  bool done_ = false;
  bool error_ = false;
  double tau_ = 0.0;  // time into cur_
  std::uint64_t periods_ = 0;
  std::uint32_t started_ = 0;
};

class StepQuantizer {
 public:
  StepQuantizer(const MachineConfig& machine, const Pose& start);

  // Increments for one period's sample (remainders carried).
  [[nodiscard]] PeriodIncrement quantize(const PeriodSample& sample);
  // True while clamped steps are still owed after the last sample.
  [[nodiscard]] bool owed() const noexcept;
  // One more period paying owed steps (call while owed()).
  [[nodiscard]] PeriodIncrement pay_owed(const PeriodSample& last);

  // Absolute commanded position in steps (of the last sample) and steps emitted.
  [[nodiscard]] std::int64_t commanded(int axis) const noexcept { return target_[axis]; }
  [[nodiscard]] std::int64_t emitted(int axis) const noexcept { return emitted_[axis]; }
  [[nodiscard]] std::int64_t to_steps(int axis, double pos) const noexcept;

 private:
  PeriodIncrement increment_for(const PeriodSample& s);

  std::array<double, kAxisCount> steps_per_unit_{};
  // The axes the machine has: an absent axis stays at 0 steps (its
  // steps_per_unit is 0), so only these are quantized.
  std::array<int, kAxisCount> present_{};
  int present_count_ = 0;
  std::int32_t max_pulses_ = 0;
  std::array<std::int64_t, kAxisCount> target_{};
  std::array<std::int64_t, kAxisCount> emitted_{};
};

namespace detail {

// (Inline, with quantize(): once per period per axis.)
// std::llround without the library call (which was most of the quantizer's
// time): truncate toward zero, then round the remainder half away from zero.
// Same result: x − trunc(x) is exact in doubles.
inline std::int64_t round_half_away(double x) noexcept {
  if (!(std::abs(x) < 0x1p62)) return std::llround(x);  // huge or NaN: as before
  std::int64_t i = static_cast<std::int64_t>(x);
  const double rest = x - static_cast<double>(i);
  if (rest >= 0.5) ++i;
  if (rest <= -0.5) --i;
  return i;
}

}  // namespace detail

inline std::int64_t StepQuantizer::to_steps(int axis, double pos) const noexcept {
  return detail::round_half_away(pos * steps_per_unit_[axis]);
}

inline PeriodIncrement StepQuantizer::increment_for(const PeriodSample& s) {
  PeriodIncrement inc;  // absent axes: 0
  static_cast<EntrySignals&>(inc) = s;
  for (int k = 0; k < present_count_; ++k) {
    const int i = present_[k];
    const std::int64_t owed = target_[i] - emitted_[i];
    const std::int64_t step = std::clamp<std::int64_t>(owed, -max_pulses_, max_pulses_);
    inc.steps[i] = static_cast<std::int32_t>(step);
    emitted_[i] += step;
  }
  inc.end_of_program = s.end_of_program && !owed();
  return inc;
}

inline PeriodIncrement StepQuantizer::quantize(const PeriodSample& s) {
  for (int k = 0; k < present_count_; ++k) {
    const int i = present_[k];
    target_[i] = to_steps(i, s.pose[i]);
  }
  return increment_for(s);
}

}  // namespace lcnc
