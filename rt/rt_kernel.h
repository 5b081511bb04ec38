// The real-time kernel: one thread that, every period, pops one entry of the
// position buffer, runs the DDA for every axis and hands the pulses to the
// pulse sink (DESIGN §2, §5.3, §5.4), at the feed override K (DESIGN §5.5):
// a period lasts T/K, so the DDA clock runs at K·F (rt/feed_override.h).
//
// The cycle, in order:
//   1. sleep to the absolute deadline (clock_nanosleep, TIMER_ABSTIME)
//   2. record wake-up latency
//   3. take the period's entry: held (K < K_min) → none (zero increments,
//      laser off, not an underrun); else pop one PeriodIncrement; empty while
//      the job runs → underrun: hold position (zero increments), count it.
//      The period lasts T/K; T while held and for a dwell, whose time is a
//      process parameter (a pierce) that the override must not change
//   4. DDA for all axes → PulseFrame
//   5. emit to the pulse sink (pulses and laser power: M4 power × K — it
//      follows the actual speed — up to the programmed power)
//   6. account the commanded position and machine time, publish a trace record
//   7. ramp K one step toward the operator's target (set_feed_override)
// Deadlines follow machine time: deadline(i) = t0 + Σ_{j<i} length(j).
// The RT path never allocates, locks, throws, logs or makes a syscall but the
// clock sleep (clock_gettime goes through the vDSO).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "machine/machine_config.h"
#include "machine/pulse_sink.h"
#include "plan/period_increment.h"
#include "rt/dda.h"
#include "rt/feed_override.h"
#include "rt/latency_histogram.h"
#include "rt/rt_log.h"
#include "rt/spsc_ring.h"

namespace lcnc::rt {

inline constexpr std::size_t kPositionBufferCapacity = 8192;  // 0.6 s at 75 µs
inline constexpr std::size_t kTraceRingCapacity = 1 << 16;    // 4.9 s at 75 µs

using PositionBuffer = SpscRing<PeriodIncrement, kPositionBufferCapacity>;

// What the RT thread executed in one period, for the trace and the report.
struct TraceRecord {
  std::uint64_t period = 0;                      // period index since start
  std::int64_t t_ns = 0;                         // machine time at the end of the period
  std::array<std::int64_t, kAxisCount> pos_steps{};  // commanded position after the period
  double feed_override = 1.0;                    // K of the period: it lasted T/K
  float power_pct = 0.0f;                        // laser output during the period, % of rated
  std::uint32_t line = 0;
  std::uint32_t segment = 0;
  bool underrun = false;  // the buffer was empty: position held
  bool held = false;      // feed hold (K < K_min): no entry taken, position held
};
using TraceRing = SpscRing<TraceRecord, kTraceRingCapacity>;

enum class RtSchedule : std::uint8_t { Fifo, Normal };

struct RtOptions {
  bool try_realtime = true;  // SCHED_FIFO + mlockall when permitted
  int fifo_priority = 80;
  // Called on the RT thread just before the first period and just after the
  // last (CPU pinning, diagnostics, the tests' syscall filter). Not on the
  // RT path itself.
  std::function<void()> on_loop_enter;
  std::function<void()> on_loop_exit;
};

class RtKernel {
 public:
  RtKernel(const MachineConfig& machine, PositionBuffer& buffer, PulseSink& sink,
           TraceRing* trace, const std::array<std::int64_t, kAxisCount>& start_steps);
  ~RtKernel();
  RtKernel(const RtKernel&) = delete;
  RtKernel& operator=(const RtKernel&) = delete;

  // Where the RT thread logs (state changes, underruns, late wake-ups); set
  // before start(). Null: no log.
  void set_log(RtLogRing* log) noexcept { log_ = log; }
  [[nodiscard]] std::uint64_t log_drops() const noexcept {
    return log_drops_.load(std::memory_order_relaxed);
  }

  // Starts the RT thread. Where SCHED_FIFO or mlockall is not permitted it
  // runs anyway; warning() then says so.
  void start(const RtOptions& options = {});
  // Waits for the thread to finish (end of program or stop()).
  void join();
  // Asks the thread to end after the current period (holding position).
  void stop() noexcept { stop_requested_.store(true, std::memory_order_relaxed); }

  // Feed override K (1 = 100 %), from any thread, lock-free. Clamped to
  // 0 … K_max (FeedOverrideRamp::clamp_target); 0 is a feed hold. While
  // running, the RT thread ramps toward it at override_ramp().rate_per_s();
  // set before start(), the run begins at it with no ramp. Default 1.
  void set_feed_override(double k) noexcept {
    // relaxed: a lone value, read by the RT thread's relaxed load in run();
    // nothing else is published with it.
    target_k_.store(ramp_.clamp_target(k), std::memory_order_relaxed);
  }
  // The override the RT thread runs at now (ramping toward the target).
  [[nodiscard]] double feed_override() const noexcept {
    return k_now_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] const FeedOverrideRamp& override_ramp() const noexcept { return ramp_; }

  [[nodiscard]] bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  [[nodiscard]] RtSchedule schedule() const noexcept { return schedule_; }
  [[nodiscard]] const std::string& warning() const noexcept { return warning_; }

  // Live counters (relaxed snapshots; exact after join()).
  [[nodiscard]] std::uint64_t periods() const noexcept { return periods_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint64_t motion_periods() const noexcept {
    return motion_periods_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t underruns() const noexcept { return underruns_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint64_t overruns() const noexcept { return overruns_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint64_t trace_drops() const noexcept { return trace_drops_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint32_t current_segment() const noexcept {
    return segment_.load(std::memory_order_relaxed);
  }
  // Machine time: Σ of the executed periods' lengths (T/K, T while held), and
  // the part of it with the laser on.
  [[nodiscard]] std::int64_t machine_time_ns() const noexcept {
    return machine_time_ns_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::int64_t laser_on_ns() const noexcept {
    return laser_on_ns_.load(std::memory_order_relaxed);
  }
  // Periods held by the feed override (K < K_min).
  [[nodiscard]] std::uint64_t held_periods() const noexcept {
    return held_periods_.load(std::memory_order_relaxed);
  }

  // Valid after join().
  [[nodiscard]] const LatencyHistogram& latency() const noexcept { return latency_; }
  // Compute time of each period's work: from the wake-up to the end of the
  // cycle (pop, DDA for every axis, emit, publish), in 10 ns buckets.
  [[nodiscard]] const LatencyHistogram& compute_time() const noexcept { return compute_; }
  [[nodiscard]] std::int64_t position_steps(int axis) const noexcept { return pos_steps_[axis]; }

 private:
  void run(const RtOptions& options) noexcept;
  void log(std::uint64_t period, RtLogCode code, std::int64_t value) noexcept;
  // Steps 4–7 for a period of length_ns ending at machine time end_ns.
  void cycle(std::uint64_t period, const PeriodIncrement& inc, bool held, bool underrun,
             double length_ns, std::int64_t end_ns) noexcept;

  std::uint32_t period_ns_;
  FeedOverrideRamp ramp_;
  PositionBuffer& buffer_;
  PulseSink& sink_;
  TraceRing* trace_;
  RtLogRing* log_ = nullptr;
  std::uint64_t underrun_since_ = 0;  // first period of the running underrun, 0 if none
  bool was_held_ = false;
  bool late_streak_ = false;  // the last period woke after its end
  std::atomic<std::uint64_t> log_drops_{0};
  Dda dda_;
  PulseFrame frame_{};
  LatencyHistogram latency_{};
  LatencyHistogram compute_{10};
  std::array<std::int64_t, kAxisCount> pos_steps_{};
  bool end_seen_ = false;
  double k_ = 1.0;                  // RT thread's current K (from the target in start())
  double laser_on_exact_ns_ = 0.0;  // RT thread's laser-on time, unrounded

  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> periods_{0};
  std::atomic<std::uint64_t> motion_periods_{0};
  std::atomic<std::uint64_t> underruns_{0};
  std::atomic<std::uint64_t> overruns_{0};
  std::atomic<std::uint64_t> trace_drops_{0};
  std::atomic<std::uint32_t> segment_{0};
  // The operator's target K: set_feed_override()'s relaxed store pairs with
  // run()'s relaxed load (a lone value, nothing published with it).
  std::atomic<double> target_k_{1.0};
  // Like the counters: written by the RT thread only, relaxed snapshots.
  std::atomic<double> k_now_{1.0};
  std::atomic<std::int64_t> machine_time_ns_{0};
  std::atomic<std::int64_t> laser_on_ns_{0};
  std::atomic<std::uint64_t> held_periods_{0};
  static_assert(std::atomic<double>::is_always_lock_free);

  RtSchedule schedule_ = RtSchedule::Normal;
  std::string warning_;
  std::thread thread_;
};

}  // namespace lcnc::rt
