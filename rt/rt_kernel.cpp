#include "rt/rt_kernel.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

namespace lcnc::rt {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

inline std::int64_t to_ns(const timespec& t) noexcept { return t.tv_sec * kNsPerS + t.tv_nsec; }
inline timespec to_timespec(std::int64_t ns) noexcept {
  return timespec{static_cast<time_t>(ns / kNsPerS), static_cast<long>(ns % kNsPerS)};
}

}  // namespace

RtKernel::RtKernel(const MachineConfig& machine, PositionBuffer& buffer, PulseSink& sink,
                   TraceRing* trace, const std::array<std::int64_t, kAxisCount>& start_steps)
    : period_ns_(machine.period_ns),
      ramp_(machine),
      buffer_(buffer),
      sink_(sink),
      trace_(trace),
      dda_(machine.dda),
      pos_steps_(start_steps) {
  target_k_.store(ramp_.clamp_target(1.0), std::memory_order_relaxed);
}

RtKernel::~RtKernel() {
  stop();
  join();
}

void RtKernel::start(const RtOptions& options) {
  warning_.clear();
  schedule_ = RtSchedule::Normal;
  // The run begins at the override already asked for, with no ramp. The
  // thread's creation below orders these writes before its first read.
  k_ = target_k_.load(std::memory_order_relaxed);
  k_now_.store(k_, std::memory_order_relaxed);
  if (!options.try_realtime) {
    warning_ = "real-time scheduling not requested: normal scheduling";
  } else if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    warning_ = std::string("mlockall failed (") + std::strerror(errno) + "): memory may page; ";
  }
  thread_ = std::thread([this, options] { run(options); });
  // From here the RT thread runs: the warning string may still grow below
  // (on this thread, before anyone reads it), nothing else is touched.
  if (options.try_realtime) {
    sched_param sp{};
    sp.sched_priority = options.fifo_priority;
    const int rc = pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &sp);
    if (rc == 0) {
      schedule_ = RtSchedule::Fifo;
    } else {
      warning_ += std::string("SCHED_FIFO not permitted (") + std::strerror(rc) +
                  "): the RT thread runs with normal scheduling and its latency is not bounded";
    }
  }
}

void RtKernel::join() {
  if (thread_.joinable()) thread_.join();
}

void RtKernel::run(const RtOptions& options) noexcept {
  // Timer slack (50 µs by default for normal threads) would delay every
  // wake-up; SCHED_FIFO threads have none, the fallback should not either.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  if (options.on_loop_enter) options.on_loop_enter();
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  // The first period starts one nominal period from now; after that each
  // deadline is t0 + machine time so far, rounded once (no drift).
  const std::int64_t t0 = to_ns(now) + period_ns_;
  double machine_ns = 0.0;  // Σ lengths of the periods before this one
  std::uint64_t period = 0;
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    // 1. sleep to the absolute deadline
    const std::int64_t deadline = t0 + std::llround(machine_ns);
    const timespec until = to_timespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) == EINTR) {
    }
    // 2. wake-up latency
    clock_gettime(CLOCK_MONOTONIC, &now);
    const std::int64_t late = to_ns(now) - deadline;
    latency_.add(late);
    // 3. the period's entry: held → none (zero increments, laser off, not an
    // underrun); else one PeriodIncrement; empty while the job runs →
    // underrun: hold position (zero increments), count it
    const bool held = ramp_.holds(k_);
    PeriodIncrement inc;
    bool underrun = false;
    if (held) {
      held_periods_.fetch_add(1, std::memory_order_relaxed);
    } else if (buffer_.try_pop(inc)) {
      motion_periods_.fetch_add(1, std::memory_order_relaxed);
      segment_.store(inc.segment, std::memory_order_relaxed);
      end_seen_ = inc.end_of_program;
    } else {
      underrun = true;
      underruns_.fetch_add(1, std::memory_order_relaxed);
    }
    // this period's length: T/K; T while held, and for a dwell, whose time is
    // a process parameter (a pierce) that the override must not change
    const bool nominal = held || (!underrun && inc.kind == MotionKind::Dwell);
    const double length_ns = nominal ? static_cast<double>(period_ns_) : period_ns_ / k_;
    // woken after the period's end: an overrun
    if (static_cast<double>(late) > length_ns) overruns_.fetch_add(1, std::memory_order_relaxed);
    // a stall makes the periods after it late too, catching up: log the
    // streak once, where it starts
    if (late > kLateLogNs && !late_streak_) log(period, RtLogCode::LateWakeup, late);
    late_streak_ = static_cast<double>(late) > length_ns;
    // state changes worth a log line
    if (underrun && underrun_since_ == 0) {
      underrun_since_ = period + 1;
      log(period, RtLogCode::UnderrunBegin, static_cast<std::int64_t>(period));
    } else if (!underrun && !held && underrun_since_ != 0) {
      log(period, RtLogCode::UnderrunEnd, static_cast<std::int64_t>(period + 1 - underrun_since_));
      underrun_since_ = 0;
    }
    if (held != was_held_) log(period, held ? RtLogCode::HoldBegin : RtLogCode::HoldEnd, 0);
    was_held_ = held;
    // 4–6. the period's work
    machine_ns += length_ns;
    cycle(period++, inc, held, underrun, length_ns, std::llround(machine_ns));
    periods_.store(period, std::memory_order_relaxed);
    timespec done{};
    clock_gettime(CLOCK_MONOTONIC, &done);
    compute_.add(to_ns(done) - to_ns(now));
    if (end_seen_) break;
    // 7. ramp K toward the target for the next period. relaxed pairs with
    // set_feed_override()'s relaxed store: only the value is read.
    k_ = ramp_.step(k_, target_k_.load(std::memory_order_relaxed), length_ns * 1e-9);
    k_now_.store(k_, std::memory_order_relaxed);
  }
  if (options.on_loop_exit) options.on_loop_exit();
  // release pairs with finished()'s acquire: counters and positions written
  // above are visible to a thread that sees finished.
  finished_.store(true, std::memory_order_release);
}

void RtKernel::log(std::uint64_t period, RtLogCode code, std::int64_t value) noexcept {
  if (log_ == nullptr) return;
  if (!log_->try_push(RtLogRecord{period, code, value}))
    log_drops_.fetch_add(1, std::memory_order_relaxed);
}

void RtKernel::cycle(std::uint64_t period, const PeriodIncrement& inc, bool held, bool underrun,
                     double length_ns, std::int64_t end_ns) noexcept {
  // 4–5. DDA and the pulse sink; M4 power follows the actual speed, K times
  // the planned one, up to the programmed power
  dda_.run_period(inc.steps, frame_);
  float power = inc.power_pct;
  if (inc.power_cap_pct > 0.0f) power = std::min(inc.power_cap_pct, power * static_cast<float>(k_));
  frame_.power_pct = power;
  sink_.emit(frame_);
  // 6. position, machine time, trace
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t n = frame_.axes[i].count;
    pos_steps_[i] += frame_.axes[i].negative ? -n : n;
  }
  machine_time_ns_.store(end_ns, std::memory_order_relaxed);
  if (power > 0.0f) {
    laser_on_exact_ns_ += length_ns;
    laser_on_ns_.store(std::llround(laser_on_exact_ns_), std::memory_order_relaxed);
  }
  if (trace_ != nullptr) {
    TraceRecord rec;
    rec.period = period;
    rec.t_ns = end_ns;
    rec.pos_steps = pos_steps_;
    rec.feed_override = k_;
    rec.power_pct = power;
    rec.line = inc.line;
    rec.segment = inc.segment;
    rec.underrun = underrun;
    rec.held = held;
    if (!trace_->try_push(rec)) trace_drops_.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace lcnc::rt
