// `lasercnc status` and `lasercnc send CMD`: a client of lasercncd through
// its shared-memory segment (rt/shm_interface.h). Reads the status and job
// blocks (never blocking the daemon) and sends commands, waiting for the
// daemon's answer to each.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rt/shm_interface.h"

namespace lcnc::app {

// The longest --timeout: an hour (a longer one is a typing error, and would
// overflow the clocks' arithmetic).
inline constexpr double kMaxTimeoutS = 3600.0;

struct ClientOptions {
  std::string shm_name;    // empty: shm::kDefaultName
  bool json = false;       // status as one JSON object
  double timeout_s = 5.0;  // 0 < t ≤ kMaxTimeoutS: the wait for the lock and for the answer
  bool wait = false;       // send start / mdi / frame: wait for the job to end, print its result
  // send start: how the program runs
  std::uint32_t from_line = 0;  // run from this line (0: the start)
  bool single_block = false;    // a pause after each block (send resume runs the next)
  bool dry_run = false;         // every move with the beam off
};

// The status as `lasercnc status` prints it (text, or one JSON object),
// from blocks already sanitized (shm::sanitize); any bytes there print.
[[nodiscard]] std::string format_status(const shm::Status& st, const shm::JobStatus& job, bool json);
// Prints the daemon's status; returns the exit code (0, or 1 without daemon).
int client_status(const ClientOptions& options);
// Sends one command: args = {CMD, ARG...}; returns the exit code (0 accepted,
// 1 refused or no daemon, 2 bad command line).
int client_send(const std::vector<std::string>& args, const ClientOptions& options);

}  // namespace lcnc::app
