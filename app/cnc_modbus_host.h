// lasercncd's Modbus slave for a PLC or an MES (docs/design.md §8,
// Shao 2022 §4): the register map's "cnc" device (drivers/modbus/
// cnc_slave.h) hosted by the daemon.
//
//   * status — the daemon's control thread calls publish() with the kernel's
//     shm status every few ms: state, positions, override, line, buffer fill,
//     underruns and the e-stop / homed / laser / fault bits;
//   * commands — a coil written 1 (start, hold, resume, stop, reset) or the
//     override register arrives on the slave's thread; it is queued here and
//     waits (at most kCommandWait) for the control thread, which executes it
//     with the same rules as a command of the shm ring (drain()). A refusal
//     is the master's exception 04 and the daemon's log says why;
//   * the hole parameter block — range-checked by the map, then checked as a
//     whole as the hole processes need it (core/holes/hole_processes.h:
//     depth = layers × layer feed, radii, speeds; a free shape's polygon
//     comes from the process database, not from the block). A block that
//     fails is exception 04 and nothing is stored; a good one is kept
//     (parameters()).
#pragma once

#include <chrono>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include <spdlog/spdlog.h>

#include "common/result.h"
#include "drivers/modbus/cnc_slave.h"
#include "holes/hole_processes.h"
#include "rt/shm_interface.h"

namespace lcnc::app {

// What came of a command: accepted, or refused with why.
struct Ack {
  bool ok = false;
  ErrorCode code = ErrorCode::Internal;
  std::string message;
};

// A Modbus command as the daemon executes it: the shm command it stands for.
using CommandExecutor = std::function<Ack(const shm::Command&)>;

// Checks the hole parameter block (docs/design.md §6 fields 1–18, a hole process
// record without a free shape's polygon) as the hole generator would; a
// free shape is checked without its polygon.
[[nodiscard]] Status check_hole_block(const drivers::HoleParameters& p);
// The kernel's status as the register map publishes it.
[[nodiscard]] drivers::CncStatusSnapshot to_snapshot(const shm::Status& st, std::uint32_t axes_mask);

class CncModbusHost {
 public:
  // How long a master's command waits for the control thread.
  static constexpr std::chrono::milliseconds kCommandWait{1000};

  // Binds (TCP) or opens (RTU) the endpoint and starts serving; refusals
  // and publishing problems are logged to `log`.
  [[nodiscard]] static Result<std::unique_ptr<CncModbusHost>> start(const drivers::Endpoint& endpoint,
                                                                    std::shared_ptr<spdlog::logger> log);
  ~CncModbusHost();

  [[nodiscard]] drivers::Endpoint endpoint() const { return slave_->endpoint(); }
  // From the control thread: publish the status (false: a request is being
  // served, nothing published — try again); execute the queued commands.
  bool publish(const shm::Status& st);
  void drain(const CommandExecutor& execute);
  // The last hole parameter block accepted, and how many were.
  [[nodiscard]] drivers::HoleParameters parameters() const;
  [[nodiscard]] std::uint64_t blocks_accepted() const;

 private:
  struct Pending {
    shm::Command command;
    std::promise<Ack> answer;
  };
  CncModbusHost() = default;
  Status on_command(drivers::CncCommand command, double value);
  Status on_parameters(const drivers::HoleParameters& p);

  std::unique_ptr<drivers::CncSlave> slave_;
  std::shared_ptr<spdlog::logger> log_;
  mutable std::mutex mutex_;  // guards the members below (slave thread ↔ control thread)
  std::deque<std::shared_ptr<Pending>> inbox_;
  drivers::HoleParameters block_{};
  std::uint64_t blocks_ = 0;
  std::string last_publish_error_;
};

}  // namespace lcnc::app
