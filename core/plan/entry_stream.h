// The one chain from a plan to what the RT kernel executes: each period's
// sample from the Planner quantized to whole steps (StepQuantizer), its
// ramp room measured (RampRoomMeter: how fast the RT may change the feed
// override while it runs the entry), and checked by the IncrementGuard
// (travel, velocity, acceleration) before it is handed out. At the plan's
// end the steps still owed by rounding are paid at rest; a plan with no
// motion at all gives one end entry, laser off, so a job always ends in a
// controlled way.
//
// `lasercnc run` and lasercncd push its entries into the position buffer
// (app/planner_feed.h); the planner benchmark and the hardware
// interpolator's vectors read the same entries, so what they measure and
// simulate is what a machine runs.
#pragma once

#include <array>
#include <cstdint>

#include "common/error.h"
#include "machine/machine_config.h"
#include "plan/coarse_interpolator.h"
#include "plan/increment_guard.h"
#include "plan/period_increment.h"
#include "plan/planner.h"
#include "plan/ramp_room.h"

namespace lcnc {

class EntryStream {
 public:
  enum class Next {
    Entry,  // `out` holds the next entry
    End,    // the plan is done and every owed step paid
    Error,  // the planner's source failed (the source says why); the
            // motion before it ends at rest, its owed steps paid, first
    Limit,  // the guard refused the entry (limit_error()): nothing more
  };

  // `planner` is the caller's (it may change its feed scale between
  // entries); `start` is where the machine stands.
  EntryStream(const MachineConfig& machine, Planner& planner, const Pose& start);

  Next next(PeriodIncrement& out);

  // The planned pose the last entry moves to.
  [[nodiscard]] const Pose& pose() const noexcept { return last_.pose; }
  // Where the machine stood, and where the entries so far take it, in steps.
  [[nodiscard]] std::int64_t start_steps(int axis) const noexcept { return start_[axis]; }
  [[nodiscard]] std::int64_t commanded(int axis) const noexcept { return quant_.commanded(axis); }
  [[nodiscard]] std::uint64_t entries() const noexcept { return entries_; }
  // Why the guard refused (code RtSoftLimit or PlanBeyondLimit, the axis,
  // the line).
  [[nodiscard]] const Diagnostic& limit_error() const noexcept { return guard_.error(); }

 private:
  Next hand_out(PeriodIncrement inc, PeriodIncrement& out);

  Planner& planner_;
  StepQuantizer quant_;
  RampRoomMeter room_;
  std::array<std::int64_t, kAxisCount> start_{};
  IncrementGuard guard_;
  PeriodSample last_;
  std::uint64_t entries_ = 0;
  enum class Stage { Planning, Paying, Done } stage_ = Stage::Planning;
  Next planned_end_ = Next::End;  // the planner's last answer: End or Error
  bool refused_ = false;
};

}  // namespace lcnc
