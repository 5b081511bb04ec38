// The daemon's first look at a command: a frame from the shm ring or the
// Modbus slave, written by another process, so nothing in it is trusted.
// The type must be one of CommandType, the axis one the machine has (jog,
// home), the value finite and in range (override, jog), the path
// NUL-terminated within its field (load). Whether the machine's state lets
// the command through is the daemon's to decide afterwards.
#pragma once

#include <cstdint>

#include "common/result.h"
#include "rt/shm_interface.h"

namespace lcnc::shm {

struct CommandLimits {
  std::uint32_t axes_mask = 0;  // bit per axis the machine has
  double max_override = 1.0;    // K (1 = 100 %)
  double max_jog = 1e5;         // mm or deg per jog command
};

// Ok, or RtRefused with a message saying what was wrong.
[[nodiscard]] lcnc::Status check_command_frame(const Command& c, const CommandLimits& limits);

}  // namespace lcnc::shm
