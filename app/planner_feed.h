// The planner thread of a job (docs/design.md §2, §5.3): reads the program, plans it
// (blends, look-ahead, coarse interpolation), quantizes to steps and keeps
// the RT kernel's position buffer filled, streaming: memory stays bounded
// whatever the program's length. Used by `lasercnc run` and by lasercncd.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/result.h"
#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "plan/planner.h"
#include "plan/program_source.h"
#include "rt/rt_kernel.h"

namespace lcnc::app {

// What the planner thread hands back when it is done.
struct PlannedJob {
  bool failed = false;
  Diagnostic error;
  std::array<std::int64_t, kAxisCount> start_steps{};  // where the job began
  std::array<std::int64_t, kAxisCount> commanded{};    // where the plan ends
  std::array<double, kAxisCount> peak_v{};             // per axis, at the nominal period
  std::array<double, kAxisCount> peak_a{};
  std::uint64_t increments = 0;  // entries pushed
  // An increment that would have crossed a soft limit (code RtSoftLimit) or
  // broken an axis' velocity or acceleration limit (PlanBeyondLimit;
  // plan/increment_guard.h): the planner stopped queueing before it
  // (stopped_short()); says the axis, what it would have done and the line.
  bool limit = false;
  Diagnostic limit_error;
  // The program's reader's warnings at its end (e.g. the parameter file
  // could not be written): the job ran, they say what it did not keep.
  std::vector<Diagnostic> warnings;
};

class PlannerFeed {
 public:
  PlannerFeed(const MachineConfig& machine, rt::PositionBuffer& buffer, rt::KernelControl& kernel);
  ~PlannerFeed();  // aborts and joins
  PlannerFeed(const PlannerFeed&) = delete;
  PlannerFeed& operator=(const PlannerFeed&) = delete;

  // Starts the planner thread on a (checked) program from options.start; it
  // tells the kernel it streams (RtKernel::stream_begin) until its last push.
  void start(const std::string& program, const ReaderOptions& options);
  // The same on segments built in code (a drilling job, holes/drill_job.h),
  // from `start`; `name` stands for the program in messages.
  void start(const std::shared_ptr<const std::vector<Segment>>& segments, const Pose& start,
             const std::string& name);
  // True once half the buffer is filled, or the whole job is in it, or the
  // planner stopped short: the moment to start the kernel on the job.
  [[nodiscard]] bool prefilled() const noexcept;
  // Blocks until prefilled().
  void wait_prefilled() const;
  // Stops pushing (a stopped or e-stopped job) and joins the thread.
  void abort();
  // The same without the join: the planner thread pushes at most the entry
  // it holds after this returns, and then finishes (done()).
  void request_abort() noexcept { abort_.store(true, std::memory_order_relaxed); }
  // Joins the thread once it has finished by itself.
  void join();
  [[nodiscard]] bool done() const noexcept { return done_.load(std::memory_order_acquire); }
  // The planner stopped queueing short of a soft limit, while the machine
  // may be moving (a cross-check: the reader already refuses moves beyond
  // the travel). The caller stops the kernel (RtCommandType::Stop): the
  // buffer holds at least the braking reserve, so the machine stops along
  // the path, short of the limit. A read error mid-way needs no stop: the
  // motion before it is planned to rest and ends as a job does, and
  // result().failed says why.
  [[nodiscard]] bool stopped_short() const noexcept { return stopped_short_.load(std::memory_order_acquire); }
  [[nodiscard]] bool running() const noexcept { return thread_.joinable(); }

  // Fault injection (the reliability tests, RELIABILITY.md): while on, the
  // planner thread pushes nothing, as a planner starved of the CPU or
  // blocked would. The kernel brakes along the path on its reserve and
  // runs on once the entries come again.
  void inject_stall(bool on) noexcept { stall_after_.store(on ? 0 : kNever, std::memory_order_relaxed); }
  // The same from the moment `increments` entries have been pushed: at a
  // point of the job whatever the threads' timing.
  void inject_stall_after(std::uint64_t increments) noexcept {
    stall_after_.store(increments, std::memory_order_relaxed);
  }
  // Valid once done().
  [[nodiscard]] const PlannedJob& result() const noexcept { return result_; }

 private:
  // Opens the job's segment source on the planner thread; false (and the
  // error set) if it cannot.
  using OpenSource = std::function<bool(SegmentSource& source, Diagnostic& error)>;
  void launch(std::string name, const Pose& start, OpenSource open);
  void run(const std::string& name, const Pose& start, const OpenSource& open);
  bool push(const PeriodIncrement& inc);

  const MachineConfig& machine_;
  rt::PositionBuffer& buffer_;
  rt::KernelControl& kernel_;
  PlannedJob result_;
  std::atomic<bool> abort_{false};
  std::atomic<bool> done_{false};
  std::atomic<bool> stopped_short_{false};
  static constexpr std::uint64_t kNever = ~std::uint64_t{0};
  std::atomic<std::uint64_t> stall_after_{kNever};
  std::string program_;
  std::unique_ptr<ProgramSource> program_source_;  // a program job's source (planner thread)
  Diagnostic source_error_;                        // why the source failed
  std::thread thread_;
};

}  // namespace lcnc::app
