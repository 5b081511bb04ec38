// lasercncd: the controller as a service. It hosts the
// planner and RT threads on the simulated machine and publishes them in
// POSIX shared memory (rt/shm_interface.h): the RT kernel writes the status,
// this control thread takes the commands of the HMI and `lasercnc send`,
// answers each in its own answer slot, and turns the kernel's log into
// events. A load is read and checked on a loader thread (the command thread
// answers the other commands meanwhile) into a private copy that the job
// then runs (app/program_snapshot.h); an e-stop does not pass through the
// daemon at all (rt/shm_interface.h EStopWord).
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/result.h"
#include "drivers/modbus/modbus_types.h"

namespace lcnc::app {

struct DaemonOptions {
  std::string machine_file;  // empty: the default machine
  std::string shm_name;      // empty: shm::kDefaultName
  bool realtime = true;      // try SCHED_FIFO + mlockall (wall clock only)
  // The simulated machine on the simulated clock at the wall clock's pace
  // (rt/rt_clock.h RtClock::SimulatedPaced): never ahead of wall time, the
  // kernel waits for the planner instead of running dry, and a computer
  // that cannot keep real time makes the machine slower, never different.
  // Not with `hal` (HAL's thread keeps the time there).
  bool simulated_clock = false;
  // The RT kernel runs in LinuxCNC's HAL (drivers/hal/, `loadrt lasercnc`),
  // on real drives: this process starts no RT thread and shares the
  // kernel's port, buffer, trace and log in the segment "<shm_name>.hal".
  bool hal = false;
  // The Modbus slave for a PLC or MES (app/cnc_modbus_host.h); none if unset.
  std::optional<drivers::Endpoint> modbus;
  // Folders a `load` may take programs from (any depth); empty: anywhere
  // the sender may read (app/program_snapshot.h).
  std::vector<std::string> program_dirs;
  // Where the work offsets (G10 L20 touch-off, G54 … G59.3, G92), G28/G30
  // positions and the tools programs set are kept from one job, MDI command
  // and daemon run to the next. Empty: the machine's parameter_file, else
  // $XDG_DATA_HOME/lasercnc/lasercncd.var (~/.local/share/lasercnc/…).
  std::string parameter_file;
};

class Daemon {
 public:
  // Loads the machine and takes the shared-memory segment: refused when a
  // live daemon holds it, recovered when its owner died.
  [[nodiscard]] static Result<std::unique_ptr<Daemon>> create(const DaemonOptions& options);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Runs until `quit` is set (SIGTERM), then stops any motion along the
  // path, ends the threads and removes the segment. Returns the exit code.
  int run(const std::atomic<bool>& quit);

  // The segment was left by a daemon that died; it was taken over.
  [[nodiscard]] bool recovered_stale() const noexcept;

 private:
  struct Impl;
  explicit Daemon(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcnc::app
