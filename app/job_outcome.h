// How a daemon's job ended, as the operator reads it: the outcome, the fault
// code and one line that says where and why ("job stopped at line 12, 37 %:
// the operator's stop"). The first cause that holds decides, in this order:
// the planner failed; the planner stopped it short of a limit; the kernel
// faulted (an e-stop, a stop by a fault); the operator stopped it; its own
// check found a breach (an axis past its limit, the path past its
// tolerance); else it is done.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/planner_feed.h"
#include "app/program_snapshot.h"
#include "machine/machine_config.h"
#include "rt/kernel_control.h"
#include "rt/shm_interface.h"

namespace lcnc::app {

// What is known when the kernel says a job has ended.
struct JobEnd {
  const PlannedJob* planned = nullptr;       // the planner's result
  const ProgramSnapshot* running = nullptr;  // what ran (names the file in messages)
  rt::RtFault fault;                         // the kernel's
  bool estopped = false;                     // the kernel is in e-stop
  bool completed = false;                    // the kernel ran its last entry
  std::vector<std::string> breaches;         // the job's check
  std::uint32_t line = 0;                    // where it stopped
  double progress = 0.0;                     // 0 … 1, of its segments
  double cycle_time_s = 0.0;
  std::uint64_t underruns = 0;
};

struct JobOutcomeText {
  shm::JobOutcome outcome = shm::JobOutcome::None;
  std::uint16_t fault = 0;    // ErrorCode, 0: none
  double progress = 0.0;      // 1 once done
  bool failed_check = false;  // decided by the job's own check: its breaches say why
  std::string message;
};

[[nodiscard]] JobOutcomeText job_outcome(const JobEnd& end, const MachineConfig& machine);

}  // namespace lcnc::app
