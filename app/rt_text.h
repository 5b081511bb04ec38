// The RT kernel's states, commands, faults and log records in words: for
// the CLI's report, the daemon's log and answers, and the HMI's events.
#pragma once

#include <cstdint>
#include <string>

#include "machine/machine_config.h"
#include "rt/rt_kernel.h"

namespace lcnc::app {

// "soft limit reached: axis X (travel 0 … 1000) at line 12"
[[nodiscard]] std::string describe_fault(const rt::RtFault& f, const MachineConfig& machine);

// The RT kernel's log records in words, for the log and the HMI's events.
struct RtLogLine {
  std::string text;
  std::uint16_t code = 0;  // ErrorCode when it is a fault or a warning with one, else 0
  bool warning = false;
};
[[nodiscard]] RtLogLine describe_rt_log(const rt::RtLogRecord& r, const MachineConfig& machine);
[[nodiscard]] const char* state_name(rt::MachineState s);
[[nodiscard]] const char* rt_command_name(rt::RtCommandType t);

}  // namespace lcnc::app
