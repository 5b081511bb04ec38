// The real-time kernel (docs/design.md §2, §5.3–5.5): one thread
// that, every period, takes the operator's commands, reads the machine's
// inputs, makes the period's motion (a position-buffer entry, or its own jog
// or homing move), guards the limits, runs the DDA for every axis, emits the
// pulses and the laser power, and publishes what it did.
//
// The cycle, in order:
//   1. sleep to the absolute deadline (clock_nanosleep, TIMER_ABSTIME)
//   2. record wake-up latency (of periods that slept; one already due, the
//      machine catching up after a stall, starts at once and is counted)
//   3. commands: the e-stop word first (an atomic counter any process bumps,
//      rt/shm_interface.h EStopWord), then the lock-free ring from one
//      control thread: start, hold, resume, stop, e-stop, reset, jog, home —
//      an e-stop acts in this period
//   4. inputs (e-stop, hard limits, home switches) from the pulse sink
//   5. the period's motion, by state:
//        Running/FeedHold/Stopping: held (K < K_min) → none; else pop one
//          PeriodIncrement; empty while the job runs → underrun: hold
//          position, count it. The effective override target is 0 while the
//          operator holds, while stopping and while the buffer is below its
//          braking reserve (a streaming producer fell behind): the machine
//          then decelerates along the path instead of running dry.
//        Jog/Homing: the kernel's own single-axis move (rt/axis_mover.h)
//        Idle/EStop: none (an aborted job's entries are discarded)
//   6. limits: hard-limit inputs in the direction of motion → e-stop; an
//      entry that would take a homed axis across its soft limit is not
//      executed → e-stop naming the axis and line. (The planner thread checks
//      increments before queueing them and stops a job short of the limit,
//      along the path: app/planner_feed.h.)
//   7. DDA for all axes → PulseFrame; emit to the pulse sink (M4 power × K up
//      to the programmed power; laser off when not on the path)
//   8. account the position and machine time; trace record; status
//      (rt/status_publisher.h)
//   9. ramp K one step toward the effective target
// A period lasts T/K on the path (T while held, for a dwell, and in every
// other state). Deadlines follow machine time: deadline(i) = t0 + Σ lengths.
// The RT path never allocates, locks, throws, logs or makes a syscall but the
// clock sleep (clock_gettime goes through the vDSO).
//
// Modes. The kernel is in one MachineState at a time, and a FeedHold has one
// cause (HoldCause). Every change goes through RtKernel::transition(), which
// refuses an event its mode does not take (rt/rt_kernel_modes.cpp):
//
//   event         from                              to
//   Start         Idle, no flush pending            Running    fault cleared; K at the override
//   Jog, Home     Idle, no flush pending            Jog, Homing
//   Hold          Running                           FeedHold(Operator)
//   ProgramPause  Running, FeedHold                 FeedHold(ProgramPause)  K = 0 at once
//   InputWait     Running, FeedHold                 FeedHold(InputWait)     K = 0 at once
//   Resume        FeedHold(Operator, ProgramPause)  Running
//   InputCame     FeedHold(InputWait)               Running
//   PauseUp       FeedHold(ProgramPause)            Running    (an unattended pause's time)
//   Stop          Running, FeedHold                 Stopping   ramps K to 0 along the path
//   Stop          Jog, Homing                       (same)     the axis move decelerates
//   AtRest        Stopping, K at 0                  Idle       job aborted, its entries flushed
//   JobEnd        Running, FeedHold, Stopping       Idle       job completed
//   MoveDone      Jog, Homing                       Idle
//   EStop         any                               EStop      on the path: job aborted, flushed
//   Reset         EStop, no flush pending           Idle       fault cleared
//
// Beside the mode, two conditions of the path: starving (the buffer below
// its braking reserve while a producer streams: K ramps to 0 until it is
// refilled) and flushing (an aborted job's entries being discarded, a
// bounded number a period, until the producer has ended its stream).
// Commands from the control thread are taken at a period's start in the
// mode it began in; one that finds the mode already changed in the same
// period (by an e-stop or another command) is not taken.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "machine/machine_config.h"
#include "machine/pulse_sink.h"
#include "plan/period_increment.h"
#include "rt/axis_mover.h"
#include "rt/dda.h"
#include "rt/feed_override.h"
#include "rt/input_wait.h"
#include "rt/kernel_control.h"
#include "rt/kernel_port.h"
#include "rt/latency_histogram.h"
#include "rt/pitch_compensation.h"
#include "rt/rt_clock.h"
#include "rt/rt_log.h"
#include "rt/shm_interface.h"
#include "rt/spsc_ring.h"
#include "rt/status_publisher.h"

namespace lcnc::rt {

inline constexpr std::size_t kPositionBufferCapacity = 16384;  // 1.2 s at 75 µs
inline constexpr std::size_t kTraceRingCapacity = 1 << 16;     // 4.9 s at 75 µs

using PositionBuffer = SpscRing<PeriodIncrement, kPositionBufferCapacity>;

// What the RT thread executed in one period, for the trace and the report.
struct TraceRecord {
  std::uint64_t period = 0;                          // period index since start
  std::int64_t t_ns = 0;                             // machine time at the end of the period
  std::array<std::int64_t, kAxisCount> pos_steps{};  // commanded position after the period
  double feed_override = 1.0;                        // K of the period: it lasted T/K
  float power_pct = 0.0f;                            // laser output during the period, % of rated
  std::uint32_t line = 0;
  std::uint32_t segment = 0;
  bool underrun = false;  // the buffer was empty: position held
  bool held = false;      // feed hold (K < K_min): no entry taken, position held
  bool on_path = false;   // a job's entry taken this period: `segment` is the job's segment
};
using TraceRing = SpscRing<TraceRecord, kTraceRingCapacity>;

enum class RtSchedule : std::uint8_t { Fifo, Normal };

// Why a FeedHold holds: the operator's hold, the program's pause (M0, M1,
// M60) or its input wait (M66).
enum class HoldCause : std::uint8_t { None, Operator, ProgramPause, InputWait };

// What changes the kernel's mode (the table above).
enum class KernelEvent : std::uint8_t {
  Start,
  Jog,
  Home,
  Hold,
  ProgramPause,
  InputWait,
  Resume,
  InputCame,
  PauseUp,
  Stop,
  AtRest,
  JobEnd,
  MoveDone,
  EStop,
  Reset,
};

struct RtOptions {
  bool try_realtime = true;  // SCHED_FIFO + mlockall when permitted
  int fifo_priority = 80;
  // Called on the RT thread just before the first period and just after the
  // last (CPU pinning, diagnostics, the tests' syscall filter). Not on the
  // RT path itself.
  std::function<void()> on_loop_enter;
  std::function<void()> on_loop_exit;
  // One job, then the thread ends (lasercnc run, tests). Otherwise the kernel
  // runs until shutdown(), Idle between jobs (the daemon).
  bool exit_at_end = true;
  // Begin Running (the buffer holds a job); otherwise Idle until StartJob.
  bool start_running = true;
  // Every axis's position known at start (the simulated machine); false for
  // real drives: unhomed until each axis is homed.
  bool start_homed = true;
  // The first period's deadline (its work runs then), CLOCK_MONOTONIC ns;
  // 0: one period after the thread starts. Kernels given the same epoch and
  // period share their period boundaries — two axis groups on one time base.
  std::int64_t epoch_ns = 0;
  // What the periods follow (RtClock).
  RtClock clock = RtClock::Wall;
  // Unattended runs (`lasercnc run --pause S`): a program pause (M0, M1,
  // M60) ends by itself after this many periods, counted by the kernel so
  // it lasts the same machine time on either clock. 0: it waits for a
  // resume command (the operator's).
  std::uint64_t program_pause_periods = 0;
};

// The kernel's own port, a base so that it is built before KernelControl
// refers to it.
struct OwnKernelPort {
  KernelPort own_port_;
};

class RtKernel : private OwnKernelPort, public KernelControl {
 public:
  // `port`: the port shared with the control side when it is not this
  // object's own (a shared-memory segment); it outlives the kernel.
  RtKernel(const MachineConfig& machine, PositionBuffer& buffer, PulseSink& sink, TraceRing* trace,
           const std::array<std::int64_t, kAxisCount>& start_steps, KernelPort* port = nullptr);
  ~RtKernel();
  RtKernel(const RtKernel&) = delete;
  RtKernel& operator=(const RtKernel&) = delete;

  // Where the RT thread logs (state changes, underruns, late wake-ups); set
  // before start(). Null: no log.
  void set_log(RtLogRing* log) noexcept { log_ = log; }

  // Where the RT thread publishes its status (the shm block's seqlock); set
  // before start(). Null: none.
  void set_status(Seqlock<shm::Status>* status) noexcept { status_.attach(status); }

  // The e-stop word the RT thread polls every period (the shm block's
  // EStopWord): a count that differs from the one last seen is an e-stop,
  // this period, whatever the control thread is doing. Set before start();
  // null: none.
  void set_estop_word(const std::atomic<std::uint32_t>* word) noexcept { estop_word_ = word; }

  // Starts the RT thread. Where SCHED_FIFO or mlockall is not permitted it
  // runs anyway; warning() then says so.
  void start(const RtOptions& options = {});
  // Waits for the thread to finish (end of a one-shot job, or shutdown()).
  void join();
  // Driven by a periodic thread of someone else's (a HAL thread) instead of
  // start(): begin() once, then period() once each period on that thread —
  // `late`: its wake-up after the deadline, ns, or < 0 where not measured —
  // until it returns false (a one-shot run's end) or the thread stops; then
  // end_periods(). period() is the RT path: it never allocates, locks or
  // blocks.
  void begin(const RtOptions& options) noexcept;
  [[nodiscard]] bool period(std::int64_t wake_ns, std::int64_t late) noexcept;
  void end_periods() noexcept;
  // Ends the thread after the current period (holding position).
  void shutdown() noexcept { port_.shutdown_requested.store(true, std::memory_order_relaxed); }

  [[nodiscard]] RtSchedule schedule() const noexcept { return schedule_; }
  [[nodiscard]] const std::string& warning() const noexcept { return warning_; }

  // Valid after join().
  [[nodiscard]] const LatencyHistogram& latency() const noexcept { return latency_; }
  // Compute time of each period's work: from the wake-up to the end of the
  // cycle (pop, DDA for every axis, emit, publish), in 10 ns buckets.
  [[nodiscard]] const LatencyHistogram& compute_time() const noexcept { return compute_; }

 private:
  // What step 5 decided for this period.
  struct Motion {
    PeriodIncrement inc{};
    bool on_path = false;   // a job's entry (override, power, trace line)
    bool held = false;      // on the path, K < K_min: no entry taken
    bool underrun = false;  // on the path, buffer empty while running
    bool nominal = true;    // the period lasts T, not T/K
  };

  // The thread driver (rt/rt_kernel_thread.cpp): the clock loop around
  // period().
  void run(const RtOptions& options) noexcept;
  // The fill at which a starving kernel runs on: twice the braking reserve
  // at K = 1 (or the whole buffer).
  [[nodiscard]] std::size_t refill_level() const noexcept;
  // The simulated clock: until the producer has filled the buffer to
  // refill_level() (or ended its stream) and the trace and log rings have
  // room for a period's records.
  void wait_simulated() const noexcept;

  // The modes (rt/rt_kernel_modes.cpp, the table atop this file).
  [[nodiscard]] bool takes(KernelEvent e) const noexcept;
  // Makes the transition if the mode takes the event; false if not.
  bool transition(KernelEvent e) noexcept;
  // Into mode s (a FeedHold for `cause`), published at once.
  void enter(MachineState s, HoldCause cause = HoldCause::None) noexcept;
  // The job left the path: ended (completed) or aborted (flushed).
  void job_ended(bool completed) noexcept;
  void set_fault(ErrorCode code, int axis, std::uint32_t line) noexcept;
  void enter_estop(ErrorCode code, int axis, std::uint32_t line) noexcept;
  // A controlled stop along the path; code Ok: the operator's, no fault.
  void begin_stop(ErrorCode code, int axis, std::uint32_t line) noexcept;
  [[nodiscard]] bool on_path_state() const noexcept {
    return state_now_ == MachineState::Running || state_now_ == MachineState::FeedHold ||
           state_now_ == MachineState::Stopping;
  }

  // The period step (rt/rt_kernel.cpp).
  void log(RtLogCode code, std::int64_t value, int axis = -1, std::uint32_t line = 0) noexcept;
  void take_commands() noexcept;
  // One command of the control thread's, `s` the mode the period began in;
  // false: refused.
  [[nodiscard]] bool take_command(const RtCommand& c, MachineState s) noexcept;
  [[nodiscard]] bool start_jog(int axis, double distance) noexcept;
  [[nodiscard]] bool start_home(int axis) noexcept;
  void take_inputs() noexcept;
  // K for a start from rest: the operator's override over what the first
  // queued entry is planned at, no ramp.
  void begin_at_override() noexcept;
  [[nodiscard]] double path_target(double e, std::uint8_t feed_control) const noexcept;
  void path_motion(Motion& m) noexcept;
  // An entry's M0/M1/M60 or M66: the job holds here.
  void take_entry_holds(const PeriodIncrement& inc) noexcept;
  void axis_motion(Motion& m) noexcept;
  void flush_some() noexcept;
  void guard_limits(Motion& m) noexcept;
  // Steps 7–8 for a period of length_ns ending at machine time end_ns.
  void cycle(const Motion& m, double length_ns, std::int64_t end_ns) noexcept;
  void publish_status(bool force) noexcept;

  std::uint32_t period_ns_;
  AxisMover mover_;  // jog and homing; and the axes' soft limits
  std::array<double, kAxisCount> units_per_step_{};
  std::uint32_t axes_mask_ = 0;  // bit per axis present
  StatusPublisher status_;
  const std::atomic<std::uint32_t>* estop_word_ = nullptr;
  std::uint32_t estop_seen_ = 0;  // the word's count at start or at the last e-stop taken
  RtOptions options_;
  // The mode (the atomics of the port publish it).
  MachineState state_now_ = MachineState::Idle;
  HoldCause hold_cause_ = HoldCause::None;  // in FeedHold
  std::uint64_t pause_left_ = 0;  // periods an unattended program pause still holds; 0: until a resume
  InputWait wait_;                // M66, in FeedHold(InputWait)
  bool starving_ = false;         // below the braking reserve while streaming
  bool flushing_ = false;         // discarding an aborted job's entries
  bool reset_pending_ = false;    // a Reset taken in EStop, done once the flush is
  bool job_aborted_ = false;      // the last job ended by a stop or an e-stop
  bool job_end_pending_ = false;  // the job's end entry ran this period
  std::uint32_t line_ = 0;        // line of the last entry executed
  std::uint64_t period_ = 0;      // index of the period being executed
  MachineInputs inputs_{};
  float power_now_ = 0.0f;
  std::array<std::int64_t, kAxisCount> emitted_{};
  // Pitch-error compensation (rt/pitch_compensation.h): the pulses are the
  // commanded steps plus the change of the correction; what the DDA cannot
  // take in one period is carried to the next.
  std::vector<PitchCompensation> comp_;
  std::array<std::int64_t, kAxisCount> comp_now_{};
  std::array<std::int64_t, kAxisCount> owed_{};
  std::int64_t max_pulses_ = 0;
  PositionBuffer& buffer_;
  PulseSink& sink_;
  TraceRing* trace_;
  RtLogRing* log_ = nullptr;
  // edges worth a log line
  std::uint64_t underrun_since_ = 0;  // first period of the running underrun, 0 if none
  bool was_held_ = false;             // the last period was held (K < K_min)
  bool late_streak_ = false;          // the last period woke after its end
  Dda dda_;
  PulseFrame frame_{};
  LatencyHistogram latency_{};
  LatencyHistogram compute_{10};
  std::array<std::int64_t, kAxisCount> pos_steps_{};
  double k_ = 1.0;                  // RT thread's period scale K ≤ 1 (feed_override.h)
  float k_plan_ = 1.0f;             // the override the entries now running are planned at
  double machine_ns_ = 0.0;         // Σ lengths of the periods executed
  double laser_on_exact_ns_ = 0.0;  // RT thread's laser-on time, unrounded

  RtSchedule schedule_ = RtSchedule::Normal;
  std::string warning_;
  std::thread thread_;
};

}  // namespace lcnc::rt
