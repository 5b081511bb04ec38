// The daemon's program loads: a program (or a hole table) copied into a
// private snapshot and checked from where the machine stands, on a thread of
// its own so that the command thread answers the other commands meanwhile.
// What was loaded before stays loaded until a load is done and checked.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/program_snapshot.h"
#include "common/result.h"
#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "path/segment.h"
#include "rt/shm_interface.h"

namespace lcnc::app {

// A program checked from where the machine stands: its summary, and for a
// drilling job the segments built from its table.
struct CheckedJob {
  ProgramSummary summary;
  std::shared_ptr<const std::vector<Segment>> drill_segments;  // empty for G-code
};

// A hole table (.csv: the process database's rows, holes/hole_table.h) is a
// drilling job; anything else a G-code program.
[[nodiscard]] bool is_hole_table(const std::string& path);

// How `p` is read: its subroutines from the folder of the file it was copied
// from (an MDI command's or the framing's: from machine.subroutine_path
// alone), each file passing may_read() for whom it was loaded — the one
// policy of every file a job reads.
[[nodiscard]] ReaderOptions reading_of(const ProgramSnapshot& p, ReaderOptions ropt);

// Checks the program's copy (or builds and checks the drilling job) from
// ropt.start; changes nothing. Any thread: reads only the machine.
[[nodiscard]] Result<CheckedJob> check_job(const ProgramSnapshot& p, const MachineConfig& machine,
                                           ReaderOptions ropt);

// One load in progress: started at construction, answered by its owner
// once done(). `machine` outlives it.
class ProgramLoad {
 public:
  ProgramLoad(const shm::Command& c, const MachineConfig& machine, const Pose& start,
              std::uint64_t params_gen, FileAccess access);
  // Cancels the load and waits for its thread.
  ~ProgramLoad();
  ProgramLoad(const ProgramLoad&) = delete;
  ProgramLoad& operator=(const ProgramLoad&) = delete;

  // The stop, e-stop, reset and shutdown: the copy and the check end at
  // their next chunk or line, the load answered as cancelled.
  void cancel() noexcept { cancel_.store(true, std::memory_order_relaxed); }
  [[nodiscard]] bool done() const noexcept { return done_.load(std::memory_order_acquire); }
  // Waits for the thread; then the snapshot (null if the copy failed) and
  // what its check gave.
  void join();
  [[nodiscard]] const std::shared_ptr<const ProgramSnapshot>& snapshot() const { return snapshot_; }
  [[nodiscard]] Result<CheckedJob>& checked() { return *checked_; }

  [[nodiscard]] const shm::Command& command() const noexcept { return cmd_; }
  // The same request sent again while it loads: answered with it.
  std::vector<shm::Command> repeats;
  [[nodiscard]] const Pose& start() const noexcept { return start_; }
  // The offsets it is checked with (the daemon's count of their changes).
  [[nodiscard]] std::uint64_t params_gen() const noexcept { return params_gen_; }

 private:
  shm::Command cmd_;
  Pose start_ = Pose::Zero();
  std::uint64_t params_gen_ = 0;
  std::shared_ptr<const ProgramSnapshot> snapshot_;  // valid once done
  std::optional<Result<CheckedJob>> checked_;        // valid once done
  std::atomic<bool> done_{false};                    // release by the thread, acquire by done()
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace lcnc::app
