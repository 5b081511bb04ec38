// `lasercnc run`: a job end to end on the simulated machine. The program is
// checked whole first; then a planner thread plans and coarse-interpolates
// into the lock-free position buffer while the RT thread pops one entry per
// period and drives the DDA into the simulated machine. The caller's thread
// drains the RT trace (CSV, contour deviation) and shows progress.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/laser_link.h"
#include "common/result.h"
#include "gcode/program_reader.h"
#include "geom/pose.h"
#include "machine/machine_config.h"
#include "rt/rt_kernel.h"

namespace lcnc::app {

struct RunOptions {
  std::string program;
  std::string machine_file;            // empty: the default machine
  std::optional<double> vmax;          // every linear axis, mm/s
  std::optional<double> amax;          // every linear axis, mm/s²
  std::optional<double> tolerance_mm;  // path tolerance
  std::string trace_file;              // CSV t,x,y,z,a,b,c,power per RT period; empty: none
  bool realtime = true;                // try SCHED_FIFO + mlockall (wall clock only)
  // The wall clock (the machine's real time) or the simulated clock (`run
  // --fast`: the same job, periods and report, as fast as the computer runs;
  // rt/rt_kernel.h RtClock).
  rt::RtClock clock = rt::RtClock::Wall;
  // Feed override for the whole run, % (docs/operator_guide.md, rt/feed_override.h): 1 ≤ pct
  // ≤ 100·machine.max_feed_override, else a Usage error. Set before the RT
  // thread starts, so the run begins at it with no ramp.
  double feed_override_pct = 100.0;
  // M0/M1/M60 pause the job; unattended, the run resumes after this long (s
  // of machine time).
  double pause_s = 0.0;
  // The simulated machine's inputs for the whole run: digital inputs high
  // (bit n: input n, for M66) and the adaptive-feed factor (M52), 0 … 1.
  std::uint8_t inputs_high = 0;
  float adaptive_feed = 1.0f;
  // The laser source and power meter over Modbus (app/laser_link.h):
  // in-process simulators (devices), or devices at these endpoints.
  bool devices = false;
  std::optional<drivers::Endpoint> laser, power_meter;
  // A job built in code instead of the program file (a drilling job,
  // holes/drill_job.h), checked by the caller; `program` names it.
  std::shared_ptr<const std::vector<Segment>> segments;
  std::optional<ProgramSummary> summary;  // what the caller's check found (segments only)
  std::string line_unit = "lines";        // what the summary's lines count: "holes" for a drilling job
  // Called from the job's drain loop (never from the RT thread) each time
  // the segment being executed changes, with the machine time then (s).
  std::function<void(std::uint32_t segment, double machine_time_s)> on_segment;
};

// Every file a run of `options` reads, as its check found them: the program
// (or hole table), each subroutine file, the parameter file, the machine
// file. None of the run's outputs may be one of them.
[[nodiscard]] std::vector<std::string> job_inputs(const RunOptions& options, const ProgramSummary& summary);

struct AxisReport {
  bool present = false;
  // Commanded, as executed at the run's feed override K: the plan's peaks
  // (sampled at T) times K and K².
  double peak_velocity = 0.0;      // mm/s or deg/s
  double peak_acceleration = 0.0;  // mm/s² or deg/s²
  // Measured from the RT trace's step positions over the check's windows
  // (plan/motion_check.h), and the limits they are held to.
  double measured_velocity = 0.0, measured_acceleration = 0.0;
  double velocity_limit = 0.0, acceleration_limit = 0.0;
  std::int64_t steps_sent = 0;  // net pulses the machine received
  std::int64_t steps_commanded = 0;
};

struct RunReport {
  std::string program;
  std::string machine;
  std::uint32_t lines = 0;
  std::string line_unit = "lines";  // "holes" for a drilling job
  std::uint64_t segments = 0;
  double period_s = 0.0;  // nominal period T; at override K a period lasts T/K
  std::uint64_t periods = 0;
  double cycle_time_s = 0.0;   // machine time taken: Σ of the periods' lengths
  double feed_override = 1.0;  // K at the end of the run (1 = 100 %)
  double path_length_mm = 0.0;
  double feed_length_mm = 0.0;
  double max_deviation_mm = 0.0;
  std::array<AxisReport, kAxisCount> axes{};
  // The run's own check: every way the executed motion left an axis limit
  // or the path's tolerance, in words; empty when it kept them all. The
  // windows the trace was measured over, in periods of T.
  std::vector<std::string> breaches;
  int velocity_window = 0, acceleration_window = 0;
  bool steps_match = false;
  std::uint64_t underruns = 0;
  std::uint64_t overruns = 0;
  std::uint64_t trace_drops = 0;
  std::uint64_t bad_frames = 0;
  double laser_on_s = 0.0;  // machine time with the laser on
  double latency_p50_us = 0.0, latency_p99_us = 0.0, latency_max_us = 0.0;
  std::uint64_t starvations = 0;  // decelerations for a low buffer (planner behind)
  std::string fault;              // what stopped the job early (soft/hard limit, e-stop); empty if none
  std::string schedule;           // "SCHED_FIFO" or "normal"
  rt::RtClock clock = rt::RtClock::Wall;  // what the periods followed
  double wall_time_s = 0.0;          // how long the run took on the computer (from the RT thread's start)
  std::string rt_warning;            // why real-time scheduling was not had
  std::uint32_t program_pauses = 0;  // M0/M1/M60 held, each resumed after RunOptions::pause_s
  std::vector<std::string> program_warnings;  // the reader's (lines after the end, the parameter file)
  PeripheralReport peripherals;               // used: the laser source was linked
};

// Fraction of the job done (0 … 1), called from the caller's thread.
using ProgressFn = std::function<void(double fraction)>;

[[nodiscard]] Result<MachineConfig> load_machine(const RunOptions& options);
[[nodiscard]] Result<RunReport> run_job(const RunOptions& options, const ProgressFn& progress = {});

// The run did what was commanded and kept every limit: the steps match, no
// bad frame, no fault, no breach of its own check. Otherwise the CLI exits 3.
[[nodiscard]] bool run_succeeded(const RunReport& report);

[[nodiscard]] std::string format_report(const RunReport& report);
[[nodiscard]] std::string report_json(const RunReport& report);

}  // namespace lcnc::app
