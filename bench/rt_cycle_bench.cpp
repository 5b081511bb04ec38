// Compute time of the RT cycle with all 6 axes moving: rt::RtKernel at 75 µs
// under SCHED_FIFO on the default machine (B axis added, travel widened so
// the soft-limit checks — which still run every period — never stop the
// run), the simulated machine as pulse sink and a trace ring drained as
// lasercnc does. A producer thread keeps the position buffer filled with
// PeriodIncrements whose steps vary on every axis, near the DDA's maximum
// pulses per period (255 with the default 8-bit preset), so the DDA computes
// ~1,400 pulse ticks a period. After ≥ 200,000 periods it prints
// kernel.compute_time() — wake-up to end of the cycle (commands, inputs,
// pop, limits, DDA for every axis, emit, trace, status), 10 ns buckets —
// p50/p99/p99.9/max, and checks that the pulses sent equal the steps
// commanded.
//
//   build/bench/rt_cycle_bench [--periods 200000] [--period-us 75]
//                              [--steps MIN MAX] [--priority 80] [--seed 1]
//
// Steps: on each axis, blocks of 8 periods forward then the same magnitudes
// backward (axes out of phase), each magnitude uniform in [MIN, MAX]
// (default: max pulses − 55 … max pulses). --steps 20 38 is the default
// machine's top speed (500 mm/s × 75 µs × 1000 steps/mm = 37.5 steps).
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include "drivers/sim_machine.h"
#include "rt/rt_kernel.h"
#include "rt_bench_common.h"

namespace {

using lcnc::kAxisCount;
using lcnc::PeriodIncrement;

// The increments of the run, one call per period, in order.
class IncrementSource {
 public:
  IncrementSource(std::uint64_t periods, std::int32_t min_steps, std::int32_t max_steps, std::uint32_t seed)
      : periods_(periods), rng_(seed), mag_(min_steps, max_steps) {
    for (auto& axis : mags_)
      for (auto& m : axis) m = mag_(rng_);
  }

  [[nodiscard]] bool done() const { return k_ == periods_; }

  PeriodIncrement next() {
    PeriodIncrement inc;
    for (int a = 0; a < kAxisCount; ++a) {
      // 16-period cycle per axis, phase-shifted by 3 periods per axis:
      // 8 forward (new magnitudes at the start), the same 8 backward.
      const std::uint64_t idx = (k_ + 3 * static_cast<std::uint64_t>(a)) % 16;
      auto& m = mags_[static_cast<std::size_t>(a)];
      if (idx == 0)
        for (auto& v : m) v = mag_(rng_);
      inc.steps[a] = idx < 8 ? m[idx] : -m[15 - idx];
      commanded_[static_cast<std::size_t>(a)] += std::abs(inc.steps[a]);
    }
    inc.power_pct = 50.0f;
    inc.line = static_cast<std::uint32_t>(k_ / 100 + 1);
    inc.segment = static_cast<std::uint32_t>(k_ / 100);
    inc.end_of_program = ++k_ == periods_;
    return inc;
  }

  // Σ|steps| per axis of the increments handed out.
  [[nodiscard]] const std::array<std::uint64_t, kAxisCount>& commanded() const { return commanded_; }

 private:
  std::uint64_t periods_;
  std::uint64_t k_ = 0;
  std::mt19937 rng_;
  std::uniform_int_distribution<std::int32_t> mag_;
  std::array<std::array<std::int32_t, 8>, kAxisCount> mags_{};
  std::array<std::uint64_t, kAxisCount> commanded_{};
};

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t periods = 200'000;
  double period_us = 75.0;
  int priority = 80;
  std::uint32_t seed = 1;
  std::int32_t steps_min = -1, steps_max = -1;
  std::string machine_file;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--periods") {
      periods = std::strtoull(lcnc::bench::arg_value(i, argc, argv), nullptr, 10);
    } else if (a == "--period-us") {
      period_us = std::atof(lcnc::bench::arg_value(i, argc, argv));
    } else if (a == "--priority") {
      priority = std::atoi(lcnc::bench::arg_value(i, argc, argv));
    } else if (a == "--seed") {
      seed = static_cast<std::uint32_t>(std::atoi(lcnc::bench::arg_value(i, argc, argv)));
    } else if (a == "--steps") {
      steps_min = std::atoi(lcnc::bench::arg_value(i, argc, argv));
      steps_max = std::atoi(lcnc::bench::arg_value(i, argc, argv));
    } else if (a == "--machine") {
      machine_file = lcnc::bench::arg_value(i, argc, argv);
    } else {
      std::fprintf(stderr,
                   "usage: rt_cycle_bench [--periods 200000] [--period-us 75] [--steps MIN MAX] "
                   "[--priority 80] [--seed 1] [--machine FILE]\n");
      return 2;
    }
  }
  const auto period_ns = static_cast<std::uint32_t>(period_us * 1000.0 + 0.5);
  auto machine = lcnc::bench::load_machine(machine_file, period_ns);
  if (!machine) return 1;
  const auto max_pulses = static_cast<std::int32_t>(machine->dda.max_pulses());
  if (steps_max < 0) {
    steps_max = max_pulses;
    steps_min = std::max(0, max_pulses - 55);
  }
  if (periods < 1 || steps_min < 0 || steps_min > steps_max || steps_max > max_pulses) {
    std::fprintf(stderr, "rt_cycle_bench: need 0 ≤ MIN ≤ MAX ≤ %d (the DDA's max pulses)\n", max_pulses);
    return 2;
  }
  // All six axes present, travel wide enough that no soft limit is near.
  for (int a = 0; a < kAxisCount; ++a) {
    lcnc::AxisConfig& ax = machine->axes[static_cast<std::size_t>(a)];
    if (!ax.present) {
      ax = machine->axis(lcnc::Axis::A);
      ax.axis = static_cast<lcnc::Axis>(a);
    }
    ax.wrap = false;
    ax.min = -1e6;
    ax.max = 1e6;
  }

  auto buffer = std::make_unique<lcnc::rt::PositionBuffer>();
  auto trace = std::make_unique<lcnc::rt::TraceRing>();
  const std::array<std::int64_t, kAxisCount> start{};
  lcnc::drivers::SimMachine sim{start};
  auto kernel = std::make_unique<lcnc::rt::RtKernel>(*machine, *buffer, sim, trace.get(), start);
  IncrementSource source(periods, steps_min, steps_max, seed);

  // The buffer starts full; the producer tops it up every millisecond (13
  // periods) and drains the trace, as lasercnc's planner thread does.
  while (!source.done() && buffer->size() < lcnc::rt::kPositionBufferCapacity) {
    if (!buffer->try_push(source.next())) break;
  }
  const lcnc::bench::DmaLatencyHold dma(true);
  lcnc::rt::RtOptions options;
  options.try_realtime = true;
  options.fifo_priority = priority;
  const auto t0 = std::chrono::steady_clock::now();
  kernel->start(options);
  std::uint64_t traced = 0;
  PeriodIncrement pending{};
  bool has_pending = false;
  while (!kernel->finished()) {
    while (!source.done() || has_pending) {
      if (!has_pending) {
        pending = source.next();
        has_pending = true;
      }
      if (!buffer->try_push(pending)) break;
      has_pending = false;
    }
    lcnc::rt::TraceRecord rec;
    while (trace->try_pop(rec)) ++traced;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  kernel->join();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  lcnc::rt::TraceRecord rec;
  while (trace->try_pop(rec)) ++traced;

  std::printf(
      "rt_cycle_bench: period %.1f us, %s priority %d, %llu periods in %.1f s, "
      "steps per axis and period %d..%d (DDA max %d, capacity %u)\n",
      period_us, kernel->schedule() == lcnc::rt::RtSchedule::Fifo ? "SCHED_FIFO" : "NOT real-time,", priority,
      static_cast<unsigned long long>(kernel->periods()), wall_s, steps_min, steps_max, max_pulses,
      machine->dda.capacity);
  if (!kernel->warning().empty()) std::printf("warning: %s\n", kernel->warning().c_str());
  lcnc::bench::print_quantiles("compute time", kernel->compute_time());
  lcnc::bench::print_quantiles("wake-up latency", kernel->latency());
  std::uint64_t pulses = 0;
  bool exact = true;
  for (int a = 0; a < kAxisCount; ++a) {
    pulses += sim.pulses(a);
    exact = exact && sim.pulses(a) == source.commanded()[static_cast<std::size_t>(a)];
  }
  std::printf(
      "pulses: %llu on 6 axes (%.0f per period), %s the steps commanded; bad frames %llu, "
      "underruns %llu, overruns %llu, trace %llu records (%llu dropped)\n",
      static_cast<unsigned long long>(pulses),
      static_cast<double>(pulses) / static_cast<double>(std::max<std::uint64_t>(1, kernel->periods())),
      exact ? "equal to" : "NOT EQUAL to", static_cast<unsigned long long>(sim.bad_frames()),
      static_cast<unsigned long long>(kernel->underruns()),
      static_cast<unsigned long long>(kernel->overruns()), static_cast<unsigned long long>(traced),
      static_cast<unsigned long long>(kernel->trace_drops()));
  if (!exact || sim.bad_frames() != 0 || kernel->periods() != periods) return 3;
  return kernel->schedule() == lcnc::rt::RtSchedule::Fifo ? 0 : 3;
}
