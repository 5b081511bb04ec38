// The RT kernel's test rig: a small machine, the kernel on the simulated
// machine with its rings, and the helpers the kernel's tests share.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "drivers/sim_machine.h"
#include "rt/rt_kernel.h"

namespace lcnc::rt::test {

// X, Y, Z of min … max mm, 1 µm steps, vmax 500 mm/s and amax 50 000 mm/s²:
// amax/vmax = 100 /s, so the override ramps at ρ_max = 50 /s (100 % ↔ hold
// in 20 ms) and a short run sees many ramps and holds. Home switches at the
// minimum, searched at 50 mm/s and latched at 5 mm/s; overrides up to 150 %.
inline MachineConfig rt_machine(double min = 0.0, double max = 100.0) {
  MachineConfig m;
  m.period_ns = 75'000;
  m.max_feed_override = 1.5;
  m.dda = DdaConfig{8, 300};
  for (int i = 0; i < 3; ++i) {
    AxisConfig& a = m.axes[i];
    a.present = true;
    a.axis = static_cast<Axis>(i);
    a.min = min;
    a.max = max;
    a.max_velocity = 500;
    a.max_acceleration = 50000;
    a.steps_per_unit = 1000;
    a.home_position = min;
    a.home_search_velocity = -50.0;
    a.home_latch_velocity = 5.0;
  }
  return m;
}

// An entry that moves X by n steps on `line`, the laser at `power` %.
inline PeriodIncrement step_x(std::int32_t n, std::uint32_t line = 1, float power = 50.0f) {
  PeriodIncrement inc;
  inc.steps[0] = n;
  inc.line = line;
  inc.power_pct = power;
  return inc;
}

// Polls `pred` until it holds; false after `timeout`, which only bounds a
// failure.
inline bool wait_for(const std::function<bool()>& pred,
                     std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

inline std::vector<RtLogRecord> drain_log(RtLogRing& ring) {
  std::vector<RtLogRecord> out;
  RtLogRecord r;
  while (ring.try_pop(r)) out.push_back(r);
  return out;
}

// The kernel on the simulated machine (wired as a real one: hard limits
// beyond the soft ones, a home switch per axis), its position buffer, trace
// and log. The rings are the test's to read, or — read_in_background() — a
// reader thread's, as a daemon has them, so that they never fill however
// long a loaded computer keeps the test from reading them; drain() and
// logs() then hand over what it read.
struct KernelRig {
  MachineConfig m;
  std::array<std::int64_t, kAxisCount> start{};
  std::unique_ptr<PositionBuffer> buffer = std::make_unique<PositionBuffer>();
  std::unique_ptr<TraceRing> trace = std::make_unique<TraceRing>();
  std::unique_ptr<RtLogRing> log = std::make_unique<RtLogRing>();
  std::unique_ptr<drivers::SimMachine> sim;
  std::unique_ptr<RtKernel> kernel;
  std::vector<TraceRecord> records;  // the trace so far, after drain()

  // raw: where the simulated machine's switches sit off the positions the
  // kernel believes (steps, per axis): a machine just switched on.
  explicit KernelRig(std::array<std::int64_t, kAxisCount> at = {}, MachineConfig config = rt_machine(),
                     std::array<std::int64_t, kAxisCount> raw = {},
                     std::array<PitchTable, kAxisCount> pitch_error = {})
      : m(std::move(config)), start(at) {
    sim = std::make_unique<drivers::SimMachine>(start, drivers::wired_switches(m, raw), pitch_error);
    kernel = std::make_unique<RtKernel>(m, *buffer, *sim, trace.get(), start);
    kernel->set_log(log.get());  // every test runs with the RT log on
  }
  ~KernelRig() {
    if (reader_.joinable()) {
      stop_reading_ = true;
      reader_.join();
    }
  }
  KernelRig(const KernelRig&) = delete;
  KernelRig& operator=(const KernelRig&) = delete;

  void read_in_background() {
    reader_ = std::thread([this] {
      while (!stop_reading_.load()) {
        {
          std::lock_guard lock(read_mutex_);
          pull();
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
  }
  // The daemon's way: the thread stays, Idle between jobs.
  static RtOptions idle_between_jobs() {
    RtOptions o;
    o.try_realtime = false;
    o.exit_at_end = false;
    o.start_running = false;
    return o;
  }
  void start_idle() { kernel->start(idle_between_jobs()); }
  // Driven period by period from the test's own thread, as a HAL thread
  // drives it: begin_stepped(), then step() runs periods.
  void begin_stepped() { kernel->begin(idle_between_jobs()); }
  void step(int periods = 1) {
    for (int i = 0; i < periods; ++i) {
      const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch())
                                   .count();
      ASSERT_TRUE(kernel->period(now, -1));
    }
  }
  void send(RtCommandType t, int axis = 0, double value = 0.0) {
    ASSERT_TRUE(kernel->command(RtCommand{t, static_cast<std::int8_t>(axis), value}));
  }
  // The trace read so far, appended to `records`.
  void drain() {
    std::lock_guard lock(read_mutex_);
    pull();
    records.insert(records.end(), read_trace_.begin(), read_trace_.end());
    read_trace_.clear();
  }
  // The log read so far (each record once).
  std::vector<RtLogRecord> logs() {
    std::lock_guard lock(read_mutex_);
    pull();
    std::vector<RtLogRecord> out;
    out.swap(read_log_);
    return out;
  }
  // Length of the i-th traced period, s.
  [[nodiscard]] double length(std::size_t i) const {
    const TraceRecord& r = records[i];
    return r.held ? m.period_s() : m.period_s() / r.feed_override;
  }
  // Speed of axis 0 in each period of the trace, steps per second.
  [[nodiscard]] std::vector<double> speeds() const {
    std::vector<double> v;
    std::int64_t prev = start[0];
    for (std::size_t i = 0; i < records.size(); ++i) {
      v.push_back(static_cast<double>(records[i].pos_steps[0] - prev) / length(i));
      prev = records[i].pos_steps[0];
    }
    return v;
  }

 private:
  // The rings' records into the read buffers (the reader thread and the
  // test take turns under read_mutex_: one consumer at a time).
  void pull() {
    TraceRecord t;
    while (trace->try_pop(t)) read_trace_.push_back(t);
    RtLogRecord l;
    while (log->try_pop(l)) read_log_.push_back(l);
  }

  std::mutex read_mutex_;
  std::vector<TraceRecord> read_trace_;
  std::vector<RtLogRecord> read_log_;
  std::atomic<bool> stop_reading_{false};
  std::thread reader_;
};

}  // namespace lcnc::rt::test
