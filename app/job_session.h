// A job on the machine, from what it runs to its own check.
//
//   JobSource   what a job runs: a program file (read by the planner as it
//               goes) or segments built in code (a drilling job);
//   JobCheck    the job's own check from the RT's trace: the executed
//               motion against every axis limit, the path against the
//               program's;
//   JobSession  a simulated machine of the job's own (`lasercnc run`,
//               `lasercnc drill`): the position buffer, the RT's trace and
//               log rings, the simulated drives, the RT kernel, the laser
//               link and the planner thread, torn down in that order's
//               reverse however the job ends.
//
// lasercncd keeps one kernel across jobs, so it uses JobSource and JobCheck
// alone. `lasercnc decompose --run` runs two axis groups on entries it
// computes itself, with no planner: app/decompose_run.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/laser_link.h"
#include "app/planner_feed.h"
#include "common/result.h"
#include "drivers/sim_machine.h"
#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "plan/motion_check.h"
#include "plan/path_check.h"
#include "rt/rt_kernel.h"
#include "rt/rt_log.h"

namespace lcnc::app {

class JobSource {
 public:
  // A program file, checked whole by the caller, read from options.start.
  static JobSource program(std::string path, ReaderOptions options);
  // Segments built in code and checked by the caller, from `start`; `name`
  // stands for the program in messages.
  static JobSource segments(std::shared_ptr<const std::vector<Segment>> segments, std::string name,
                            const Pose& start);

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] const ReaderOptions& options() const noexcept { return options_; }
  // The planner thread on it. A program keeps what it sets (G10 offsets,
  // tools) in the machine's parameter file: it outlives the job.
  void start(PlannerFeed& feed) const;
  // The path check's own reading of it.
  [[nodiscard]] Result<std::unique_ptr<PathCheck>> path_check(const MachineConfig& machine) const;

 private:
  std::string name_;
  ReaderOptions options_;
  std::shared_ptr<const std::vector<Segment>> segments_;  // null: a program
};

class JobCheck {
 public:
  // `at`: the axes' steps where the job begins; `t0_ns`: the machine time
  // then (records up to it are not the job's); `next_period`: the period
  // the trace's next record carries (a jump is a lost record).
  JobCheck(const MachineConfig& machine, std::unique_ptr<PathCheck> path,
           const std::array<std::int64_t, kAxisCount>& at, std::int64_t t0_ns = 0,
           std::uint64_t next_period = 0);
  // One record of the RT's trace, in the order traced.
  void add(const rt::TraceRecord& r);
  // After the last record: the motion's last windows measured.
  void finish() { motion_.finish(); }
  // Every way the job left an axis limit (motion) or its path's tolerance,
  // in words; empty when it kept them all. Valid after finish().
  [[nodiscard]] std::vector<std::string> breaches() const;

  [[nodiscard]] const MotionCheck& motion() const noexcept { return motion_; }
  [[nodiscard]] const PathCheck& path() const noexcept { return *path_; }

 private:
  const MachineConfig& machine_;
  std::unique_ptr<PathCheck> path_;
  MotionCheck motion_;
  std::int64_t t0_ns_;
  std::uint64_t next_period_;
};

class JobSession {
 public:
  // The machine at `start_steps`; the simulated drives' inputs for the
  // whole job: digital inputs high (bit n: input n) and the adaptive feed.
  JobSession(const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& start_steps,
             std::uint8_t inputs_high, float adaptive_feed);
  ~JobSession() = default;  // the members' own: planner, laser, kernel, drives
  JobSession(const JobSession&) = delete;
  JobSession& operator=(const JobSession&) = delete;

  // The laser source over Modbus: in-process simulators (`devices`) or the
  // devices at these endpoints, enabled and ready, or an error.
  [[nodiscard]] Status link_laser(bool devices, const std::optional<drivers::Endpoint>& laser,
                                  const std::optional<drivers::Endpoint>& power_meter);
  // The planner thread on `source` at feed override `k` (set before the
  // RT thread starts, so the job begins at it with no ramp); the RT thread
  // once half the buffer (or the whole job) is in, on `clock`: the wall
  // clock (SCHED_FIFO + mlockall tried where `realtime`) or the simulated
  // clock (rt/rt_kernel.h RtClock; normal scheduling, as fast as the
  // computer runs).
  // `pause_periods`: RtOptions::program_pause_periods (0: a program pause
  // waits for a resume).
  void start(const JobSource& source, double k, bool realtime, rt::RtClock clock,
             std::uint64_t pause_periods);

  [[nodiscard]] rt::RtKernel& kernel() noexcept { return *kernel_; }
  [[nodiscard]] const drivers::SimMachine& sim() const noexcept { return *sim_; }
  [[nodiscard]] rt::TraceRing& trace() noexcept { return *trace_; }
  [[nodiscard]] rt::RtLogRing& rt_log() noexcept { return *rt_log_; }
  [[nodiscard]] PlannerFeed& feed() noexcept { return *feed_; }
  [[nodiscard]] LaserLink* laser() noexcept { return laser_.get(); }

 private:
  // Declared in the order built; destroyed in reverse: the planner stops
  // pushing first, the laser is switched off, the RT thread is joined.
  std::unique_ptr<rt::PositionBuffer> buffer_;
  std::unique_ptr<rt::TraceRing> trace_;
  std::unique_ptr<rt::RtLogRing> rt_log_;
  std::unique_ptr<drivers::SimMachine> sim_;
  std::unique_ptr<rt::RtKernel> kernel_;
  std::unique_ptr<LaserLink> laser_;
  std::unique_ptr<PlannerFeed> feed_;
};

}  // namespace lcnc::app
