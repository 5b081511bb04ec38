#include "app/job_outcome.h"

#include <cstdio>

#include "app/rt_text.h"

namespace lcnc::app {

JobOutcomeText job_outcome(const JobEnd& end, const MachineConfig& machine) {
  JobOutcomeText out;
  out.progress = end.progress;
  out.fault = end.fault.active ? static_cast<std::uint16_t>(end.fault.code) : 0;
  // where it stopped: "at line 12, 37 %"
  char where[64];
  std::snprintf(where, sizeof where, "at line %u, %.0f %%", end.line, end.progress * 100.0);
  const PlannedJob& planned = *end.planned;
  char msg[256];
  if (planned.failed) {
    out.outcome = shm::JobOutcome::Failed;
    out.fault = static_cast<std::uint16_t>(planned.error.code);
    std::snprintf(msg, sizeof msg, "job failed %s: %s", where,
                  end.running->rename(planned.error).to_string().c_str());
  } else if (planned.limit) {
    out.outcome = shm::JobOutcome::Stopped;
    out.fault = static_cast<std::uint16_t>(planned.limit_error.code);
    std::snprintf(msg, sizeof msg, "job stopped %s: %s", where,
                  end.running->rename(planned.limit_error).to_string().c_str());
  } else if (end.fault.active) {
    out.outcome = end.estopped ? shm::JobOutcome::EStopped : shm::JobOutcome::Stopped;
    std::snprintf(msg, sizeof msg, "job %s %s: %s", end.estopped ? "e-stopped" : "stopped", where,
                  describe_fault(end.fault, machine).c_str());
  } else if (!end.completed) {
    out.outcome = shm::JobOutcome::Stopped;
    std::snprintf(msg, sizeof msg, "job stopped %s: the operator's stop", where);
  } else if (!end.breaches.empty()) {
    out.outcome = shm::JobOutcome::Failed;
    out.failed_check = true;
    out.fault = static_cast<std::uint16_t>(ErrorCode::PlanBeyondLimit);
    std::snprintf(msg, sizeof msg, "job failed its check: %s%s", end.breaches.front().c_str(),
                  end.breaches.size() > 1 ? " (and more, in the log)" : "");
  } else {
    out.outcome = shm::JobOutcome::Done;
    out.progress = 1.0;
    std::snprintf(msg, sizeof msg,
                  "job done: %s, cycle %.3f s, %llu underruns, every axis within its limits, the path "
                  "within its tolerance",
                  end.running->name().c_str(), end.cycle_time_s,
                  static_cast<unsigned long long>(end.underruns));
  }
  out.message = msg;
  return out;
}

}  // namespace lcnc::app
