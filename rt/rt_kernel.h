// The real-time kernel: one thread that, every period T, pops one entry of
// the position buffer, runs the DDA for every axis and hands the pulses to the
// pulse sink (DESIGN §2, §5.3, §5.4).
//
// The cycle, in order:
//   1. sleep to the absolute deadline (clock_nanosleep, TIMER_ABSTIME)
//   2. record wake-up latency
//   3. pop one PeriodIncrement; empty while the job runs → underrun: hold
//      position (zero increments), count it
//   4. DDA for all axes → PulseFrame
//   5. emit to the pulse sink (pulses and laser power)
//   6. account the commanded position, publish a trace record
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
#include "rt/latency_histogram.h"
#include "rt/spsc_ring.h"

namespace lcnc::rt {

inline constexpr std::size_t kPositionBufferCapacity = 8192;  // 0.6 s at 75 µs
inline constexpr std::size_t kTraceRingCapacity = 1 << 16;    // 4.9 s at 75 µs

using PositionBuffer = SpscRing<PeriodIncrement, kPositionBufferCapacity>;

// What the RT thread executed in one period, for the trace and the report.
struct TraceRecord {
  std::uint64_t period = 0;                      // period index since start
  std::array<std::int64_t, kAxisCount> pos_steps{};  // commanded position after the period
  float power_pct = 0.0f;
  std::uint32_t line = 0;
  std::uint32_t segment = 0;
  bool underrun = false;  // the buffer was empty: position held
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

  // Starts the RT thread. Where SCHED_FIFO or mlockall is not permitted it
  // runs anyway; warning() then says so.
  void start(const RtOptions& options = {});
  // Waits for the thread to finish (end of program or stop()).
  void join();
  // Asks the thread to end after the current period (holding position).
  void stop() noexcept { stop_requested_.store(true, std::memory_order_relaxed); }

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

  // Valid after join().
  [[nodiscard]] const LatencyHistogram& latency() const noexcept { return latency_; }
  [[nodiscard]] std::int64_t position_steps(int axis) const noexcept { return pos_steps_[axis]; }

 private:
  void run(const RtOptions& options) noexcept;
  void cycle(std::uint64_t period) noexcept;

  std::uint32_t period_ns_;
  PositionBuffer& buffer_;
  PulseSink& sink_;
  TraceRing* trace_;
  Dda dda_;
  PulseFrame frame_{};
  LatencyHistogram latency_{};
  std::array<std::int64_t, kAxisCount> pos_steps_{};
  bool end_seen_ = false;

  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> periods_{0};
  std::atomic<std::uint64_t> motion_periods_{0};
  std::atomic<std::uint64_t> underruns_{0};
  std::atomic<std::uint64_t> overruns_{0};
  std::atomic<std::uint64_t> trace_drops_{0};
  std::atomic<std::uint32_t> segment_{0};

  RtSchedule schedule_ = RtSchedule::Normal;
  std::string warning_;
  std::thread thread_;
};

}  // namespace lcnc::rt
