// What the end-to-end tests of lasercncd read of it: its status as
// `lasercnc status --json` prints it, and waits on its machine time.
#pragma once

#include <chrono>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "e2e_support.h"

namespace e2e {

inline nlohmann::json status(const std::string& shm) {
  const CmdResult r = lasercnc("status --json --shm " + shm);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out, nullptr, false);
}

// Waits until the daemon's machine time has run `seconds` on from now: a
// wait on the machine, not on the computer's clock (a loaded computer makes
// the machine slower, and a wall-clock sleep would then be too short to
// see, say, the end of a ramp). The deadline only fails a daemon that
// stopped.
inline bool wait_machine_time(const std::string& shm, double seconds) {
  const nlohmann::json first = status(shm);
  if (!first.is_object()) return false;
  const double until_s = first["machine_time_s"].get<double>() + seconds;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    const nlohmann::json s = status(shm);
    if (s.is_object() && s["machine_time_s"].get<double>() >= until_s) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace e2e
