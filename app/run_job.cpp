#include "app/run_job.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "app/job_session.h"
#include "app/machine_files.h"
#include "app/planner_feed.h"
#include "app/rt_text.h"
#include "common/output_file.h"
#include "common/share_path.h"
#include "drivers/sim_machine.h"
#include "gcode/program_reader.h"
#include "machine/feed_override_percent.h"
#include "plan/motion_check.h"
#include "plan/path_check.h"
#include "plan/program_source.h"
#include "plan/tolerances.h"
#include "rt/rt_kernel.h"
#include "rt/rt_log.h"

namespace lcnc::app {
namespace {

// The trace CSV: an OutputFile (common/output_file.h), so the old file stays
// until the job has run to its end and nothing half-written replaces it.
class TraceWriter {
 public:
  // `inputs`: the job's files, which the trace must not be.
  [[nodiscard]] Status open(const std::string& path, const std::vector<std::string>& inputs) {
    if (path.empty()) return {};
    Result<OutputFile> f = OutputFile::open(path, inputs);
    if (!f) return f.error();
    file_.emplace(std::move(f).value());
    file_->write("t,x,y,z,a,b,c,power\n");
    return {};
  }
  // t: machine time at the end of the period (s); p: commanded pose (mm,
  // deg); power: laser output (% of rated).
  void write(double t, const Pose& p, double power_pct) {
    if (!file_ || file_->failed()) return;
    file_->printf("%.9f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.3f\n", t, p[0], p[1], p[2], p[3], p[4], p[5],
                  power_pct);
  }
  [[nodiscard]] Status commit() { return file_ ? file_->commit() : Status{}; }

 private:
  std::optional<OutputFile> file_;
};

// The RT thread's log records, written out here on a normal thread (the RT
// path never logs itself): to stderr, so stdout stays the report.
void drain_rt_log(rt::RtLogRing& ring, const MachineConfig& machine) {
  static const std::shared_ptr<spdlog::logger> logger = [] {
    auto l = spdlog::get("rt");
    return l ? l : spdlog::stderr_color_mt("rt");
  }();
  rt::RtLogRecord r;
  while (ring.try_pop(r)) {
    const RtLogLine line = describe_rt_log(r, machine);
    if (line.warning) {
      logger->warn("period {} (t ≈ {:.4f} s): {}", r.period,
                   static_cast<double>(r.period) * machine.period_s(), line.text);
    } else {
      logger->info("period {}: {}", r.period, line.text);
    }
  }
}

}  // namespace

Result<MachineConfig> load_machine(const RunOptions& options) {
  const std::string file = options.machine_file.empty() ? default_machine_file() : options.machine_file;
  Result<MachineConfig> loaded = load_machine_config(file);
  if (!loaded) return loaded;
  MachineConfig m = std::move(loaded).value();
  for (Axis a : {Axis::X, Axis::Y, Axis::Z}) {
    AxisConfig& ax = m.axis(a);
    if (!ax.present) continue;
    if (options.vmax) ax.max_velocity = *options.vmax;
    if (options.amax) ax.max_acceleration = *options.amax;
  }
  if (options.tolerance_mm) m.path_tolerance_mm = *options.tolerance_mm;
  if (options.vmax || options.amax || options.tolerance_mm) {
    Status s = validate(m, "command line (--vmax/--amax/--tolerance over " + file + ")");
    if (!s) return s.error();
  }
  return m;
}

bool run_succeeded(const RunReport& report) {
  return report.steps_match && report.bad_frames == 0 && report.fault.empty() && report.breaches.empty();
}

namespace {

// Relative slack on the plan's own peaks (sampled without quantization):
// floating-point rounding of the profile, nothing more.
constexpr double kPlannedPeakSlack = 1e-6;
// The plan's peak acceleration is differenced period by period. At a
// near-tangent join (CAM arcs rounded to a few decimals) the look-ahead lets
// an axis's speed step by up to kJunctionJumpShare of one period's
// acceleration (plan/lookahead.h): 0.04 mm/s on a 5000 mm/s² axis, far
// below one step per period, but a period's difference reads it as that
// share of amax on top of the profile's. The trace's check, over its
// window, measures the real acceleration against the limit itself.
constexpr double kPlannedAccelSlack = kPlannedPeakSlack + plan::kJunctionJumpShare;

// The run's own check (RunReport::breaches): the plan's peaks at the run's
// override and the trace's measured motion against every axis limit, and
// the executed path against its tolerance.
void check_run(RunReport& report, const JobCheck& check) {
  const MotionCheck& motion = check.motion();
  report.velocity_window = motion.velocity_window();
  report.acceleration_window = motion.acceleration_window();
  for (int i = 0; i < kAxisCount; ++i) {
    AxisReport& a = report.axes[i];
    const AxisMotionCheck& m = motion.axes()[i];
    if (!a.present) continue;
    a.measured_velocity = m.velocity.peak;
    a.measured_acceleration = m.acceleration.peak;
    a.velocity_limit = m.velocity.limit;
    a.acceleration_limit = m.acceleration.limit;
    const bool rot = is_rotary(static_cast<Axis>(i));
    char msg[200];
    if (a.peak_velocity > a.velocity_limit * (1.0 + kPlannedPeakSlack)) {
      std::snprintf(msg, sizeof msg, "axis %c planned velocity %.3f %s, above its limit %g", kAxisLetters[i],
                    a.peak_velocity, rot ? "deg/s" : "mm/s", a.velocity_limit);
      report.breaches.emplace_back(msg);
    }
    if (a.peak_acceleration > a.acceleration_limit * (1.0 + kPlannedAccelSlack)) {
      std::snprintf(msg, sizeof msg, "axis %c planned acceleration %.1f %s, above its limit %g",
                    kAxisLetters[i], a.peak_acceleration, rot ? "deg/s2" : "mm/s2", a.acceleration_limit);
      report.breaches.emplace_back(msg);
    }
  }
  for (std::string& b : check.breaches()) report.breaches.push_back(std::move(b));
}

// Trace records read between two looks at the kernel (segment, laser,
// progress): 20 ms of periods at 75 µs.
constexpr int kDrainChunk = 256;

}  // namespace

// The figures of a finished run: from the kernel's counters, the simulated
// drives and what the planner queued.
void fill_run_figures(RunReport& report, const rt::RtKernel& kernel, const drivers::SimMachine& sim,
                      const PlannedJob& planned, const MachineConfig& machine,
                      const std::array<std::int64_t, kAxisCount>& start_steps) {
  report.periods = kernel.periods();
  report.cycle_time_s = static_cast<double>(kernel.machine_time_ns()) * 1e-9;
  report.feed_override = kernel.feed_override_target();
  // The plan's peaks are at the nominal period, and the override above 100 %
  // is in them (planned for); the RT ran every period at K = min(1, override).
  const double k = std::min(1.0, report.feed_override);
  report.steps_match = true;
  for (int i = 0; i < kAxisCount; ++i) {
    AxisReport& a = report.axes[i];
    a.present = machine.axes[i].present;
    a.peak_velocity = planned.peak_v[i] * k;
    a.peak_acceleration = planned.peak_a[i] * k * k;
    // the pulses are the commanded steps plus the change of the pitch
    // correction between the start and the end (rt/pitch_compensation.h)
    const rt::PitchCompensation comp(machine.axes[i]);
    a.steps_sent = sim.position_steps(i) - start_steps[i];
    a.steps_commanded = planned.commanded[i] - start_steps[i] + comp.correction_steps(planned.commanded[i]) -
                        comp.correction_steps(start_steps[i]);
    report.steps_match =
        report.steps_match && a.steps_sent == a.steps_commanded && kernel.pulses_emitted(i) == a.steps_sent;
  }
  report.underruns = kernel.underruns();
  report.starvations = kernel.starvations();
  if (const rt::RtFault f = kernel.fault(); f.active) report.fault = describe_fault(f, machine);
  if (planned.limit) report.fault = planned.limit_error.to_string();
  report.overruns = kernel.overruns();
  report.trace_drops = kernel.trace_drops();
  report.bad_frames = sim.bad_frames();
  report.laser_on_s = static_cast<double>(kernel.laser_on_ns()) * 1e-9;
  const rt::LatencyHistogram& lat = kernel.latency();
  report.latency_p50_us = lat.quantile_us(0.50);
  report.latency_p99_us = lat.quantile_us(0.99);
  report.latency_max_us = static_cast<double>(lat.max_ns()) / 1000.0;
  report.schedule = kernel.schedule() == rt::RtSchedule::Fifo ? "SCHED_FIFO" : "normal";
  report.rt_warning = kernel.warning();
}

std::vector<std::string> job_inputs(const RunOptions& options, const ProgramSummary& summary) {
  std::vector<std::string> in{options.program,
                              options.machine_file.empty() ? default_machine_file() : options.machine_file};
  in.insert(in.end(), summary.files.begin(), summary.files.end());
  return in;
}

Result<RunReport> run_job(const RunOptions& options, const ProgressFn& progress) {
  // The Modbus devices answer in wall time; on the simulated clock the job
  // would run past them (`run --fast`, `drill --fast`).
  if (rt::is_simulated(options.clock) && (options.devices || options.laser || options.power_meter))
    return make_error(ErrorCode::Usage,
                      "--fast runs the machine on the simulated clock; the laser source, power meter "
                      "and scanning head keep wall time: run --devices, --laser and --power-meter "
                      "without --fast");
  Result<MachineConfig> loaded = load_machine(options);
  if (!loaded) return loaded.error();
  const MachineConfig machine = std::move(loaded).value();
  const Result<double> k_start =
      override_from_percent(options.feed_override_pct, kMinRunOverridePct, machine.max_feed_override,
                            ErrorCode::Usage, "--feed-override");
  if (!k_start) return k_start.error();

  // The whole program is checked before anything moves.
  const ReaderOptions ropt;
  Result<ProgramSummary> summary =
      options.segments
          ? (options.summary
                 ? Result<ProgramSummary>(*options.summary)
                 : Result<ProgramSummary>(make_error(ErrorCode::Internal, "a segment job needs its summary")))
          : check_job_program(options.program, machine, ropt);
  if (!summary) return summary.error();
  const JobSource source = options.segments
                               ? JobSource::segments(options.segments, options.program, ropt.start)
                               : JobSource::program(options.program, ropt);

  RunReport report;
  report.program = options.program;
  report.machine = machine.name;
  report.lines = summary->lines;
  report.line_unit = options.line_unit;
  report.segments = summary->segments;
  report.path_length_mm = summary->path_length_mm;
  report.feed_length_mm = summary->feed_length_mm;
  report.period_s = machine.period_s();

  TraceWriter trace_out;
  if (Status s = trace_out.open(options.trace_file, job_inputs(options, *summary)); !s) return s.error();

  std::array<double, kAxisCount> spu{};
  std::array<std::int64_t, kAxisCount> start_steps{};
  {
    StepQuantizer q(machine, ropt.start);
    for (int i = 0; i < kAxisCount; ++i) {
      spu[i] = machine.axes[i].present ? machine.axes[i].steps_per_unit : 1.0;
      start_steps[i] = q.commanded(i);
    }
  }

  // Every return from here on tears the session down in order (planner,
  // laser, RT thread).
  JobSession session(machine, start_steps, options.inputs_high, options.adaptive_feed);
  rt::RtKernel& kernel = session.kernel();
  rt::TraceRing& trace = session.trace();
  PlannerFeed& feed = session.feed();
  // The laser source over Modbus: enabled and ready, or nothing moves.
  if (options.devices || options.laser) {
    if (Status s = session.link_laser(options.devices, options.laser, options.power_meter); !s)
      return s.error();
  }
  LaserLink* const laser = session.laser();

  // The job's own check reads the program again: opened before the job
  // starts, so it reads the offsets the job starts from, not those the job
  // keeps in the parameter file at its end (a G10 would move the check's
  // path under the job's feet).
  Result<std::unique_ptr<PathCheck>> path_check = source.path_check(machine);
  if (!path_check) return path_check.error();

  // Planner thread: plan, coarse-interpolate, quantize, keep the buffer
  // full; the RT thread starts once half the buffer (or the whole job) is in.
  // M0/M1/M60: unattended, each pause ends after options.pause_s of machine
  // time, counted by the kernel (at least one period)
  const auto pause_periods =
      static_cast<std::uint64_t>(std::max(1.0, std::round(options.pause_s / machine.period_s())));
  session.start(source, *k_start, options.realtime, options.clock, pause_periods);
  const auto started = std::chrono::steady_clock::now();

  // Drain the trace while the job runs: CSV, the job's check, progress.
  JobCheck check(machine, std::move(path_check).value(), start_steps);
  std::uint32_t segment_seen = UINT32_MAX;
  const double total_segments = std::max<double>(1.0, static_cast<double>(summary->segments));
  auto last_progress = std::chrono::steady_clock::now();
  rt::TraceRecord rec;
  bool stop_sent = false;
  std::string laser_fault;  // why the laser source failed during the job
  float power_now = 0.0f;   // the commanded laser power of the latest period, %
  for (;;) {
    bool got = false;
    drain_rt_log(session.rt_log(), machine);
    // in chunks: the segment, the laser and the progress below are followed
    // between them however far the trace's reading lags (a slow machine, a
    // sanitizer build)
    for (int n = 0; n < kDrainChunk && trace.try_pop(rec); ++n) {
      got = true;
      Pose p = Pose::Zero();
      for (int i = 0; i < kAxisCount; ++i) p[i] = static_cast<double>(rec.pos_steps[i]) / spu[i];
      trace_out.write(static_cast<double>(rec.t_ns) * 1e-9, p, rec.power_pct);
      check.add(rec);
      power_now = rec.power_pct;
    }
    if (laser) {
      laser->follow(power_now);
      // a lost or alarming source: the beam off at once, the job stops
      // along the path (the run then fails with the reason)
      if (laser_fault.empty()) {
        laser_fault = laser->fault();
        if (!laser_fault.empty()) kernel.laser_inhibit();
      }
      if (!laser_fault.empty() && !stop_sent) stop_sent = kernel.command({rt::RtCommandType::Stop, 0, 0.0});
    }
    if (options.on_segment && kernel.current_segment() != segment_seen) {
      segment_seen = kernel.current_segment();
      options.on_segment(segment_seen, static_cast<double>(kernel.machine_time_ns()) * 1e-9);
    }
    if (progress) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_progress > std::chrono::milliseconds(100)) {
        last_progress = now;
        progress(std::min(1.0, kernel.current_segment() / total_segments));
      }
    }
    // short of a soft limit: stop along the path with what is queued
    if (feed.stopped_short() && !stop_sent) stop_sent = kernel.command({rt::RtCommandType::Stop, 0, 0.0});
    // a fault (an e-stop, a limit) or a stop ends the job: the planner stops pushing
    if (kernel.state() == rt::MachineState::EStop || kernel.fault().active || kernel.jobs_ended() > 0)
      feed.abort();
    if (kernel.finished() && trace.empty()) break;
    if (!got) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kernel.join();
  const double wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  drain_rt_log(session.rt_log(), machine);
  feed.abort();
  if (laser) report.peripherals = laser->finish();
  if (progress) progress(1.0);
  const PlannedJob& planned = feed.result();
  if (planned.failed) return planned.error;

  fill_run_figures(report, kernel, session.sim(), planned, machine, start_steps);
  report.clock = options.clock;
  report.wall_time_s = wall_time_s;
  if (rt::is_simulated(options.clock)) report.rt_warning.clear();  // nothing was asked for
  report.program_pauses = kernel.program_pauses();
  for (const Diagnostic& w : planned.warnings) report.program_warnings.push_back(w.to_string());
  if (!laser_fault.empty() && report.fault.empty()) report.fault = "laser source: " + laser_fault;
  report.max_deviation_mm = check.path().max_mm();
  check.finish();
  check_run(report, check);
  // The job ran to its end (its checks may still fail: then the trace is
  // what shows why), so its trace replaces the old file.
  if (Status s = trace_out.commit(); !s) return s.error();
  return report;
}

}  // namespace lcnc::app
