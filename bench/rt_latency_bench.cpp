// Wake-up latency of the RT thread: the project's RT loop (rt::RtKernel on
// the default machine, an empty position buffer — every period an underrun,
// holding position — and the simulated machine as pulse sink) runs for a
// given time at a given period under SCHED_FIFO, then prints
// kernel.latency(): how late after each absolute deadline clock_nanosleep
// returned, p50/p99/p99.9/max. The same measure cyclictest takes of its own
// bare loop (bench/rt_latency_vs_cyclictest.sh runs both back to back).
//
//   build/bench/rt_latency_bench --period-us 75 --seconds 10 [--priority 80]
//                                [--hist FILE] [--no-dma-latency] [--machine FILE]
//
// --hist writes the histogram in cyclictest's -h format. As cyclictest does,
// /dev/cpu_dma_latency is held at 0 during the run (no deep C-states),
// unless --no-dma-latency. Needs root (SCHED_FIFO, mlockall); without it the
// run is made and says it was not real-time. Results go to BENCHMARKS.md.
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>

#include "drivers/sim_machine.h"
#include "rt/rt_kernel.h"
#include "rt_bench_common.h"

int main(int argc, char** argv) {
  double period_us = 75.0, seconds = 10.0;
  int priority = 80;
  bool dma_latency = true;
  std::string hist_file, machine_file;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--period-us") {
      period_us = std::atof(lcnc::bench::arg_value(i, argc, argv));
    } else if (a == "--seconds") {
      seconds = std::atof(lcnc::bench::arg_value(i, argc, argv));
    } else if (a == "--priority") {
      priority = std::atoi(lcnc::bench::arg_value(i, argc, argv));
    } else if (a == "--hist") {
      hist_file = lcnc::bench::arg_value(i, argc, argv);
    } else if (a == "--machine") {
      machine_file = lcnc::bench::arg_value(i, argc, argv);
    } else if (a == "--no-dma-latency") {
      dma_latency = false;
    } else {
      std::fprintf(stderr,
                   "usage: rt_latency_bench [--period-us 75] [--seconds 10] [--priority 80] "
                   "[--hist FILE] [--no-dma-latency] [--machine FILE]\n");
      return 2;
    }
  }
  if (period_us < 5.0 || seconds <= 0.0) {
    std::fprintf(stderr, "rt_latency_bench: period ≥ 5 µs and a positive duration, please\n");
    return 2;
  }
  const auto period_ns = static_cast<std::uint32_t>(period_us * 1000.0 + 0.5);
  auto machine = lcnc::bench::load_machine(machine_file, period_ns);
  if (!machine) return 1;

  // Empty buffer: the kernel holds position every period (an underrun);
  // no trace, no log, no status: the loop's own cost only.
  auto buffer = std::make_unique<lcnc::rt::PositionBuffer>();
  const std::array<std::int64_t, lcnc::kAxisCount> start{};
  lcnc::drivers::SimMachine sim{start};
  auto kernel = std::make_unique<lcnc::rt::RtKernel>(*machine, *buffer, sim, nullptr, start);

  const lcnc::bench::DmaLatencyHold dma(dma_latency);
  lcnc::rt::RtOptions options;
  options.try_realtime = true;
  options.fifo_priority = priority;
  kernel->start(options);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until && !kernel->finished())
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool ended_early = kernel->finished();
  lcnc::bench::end_kernel(*kernel);
  kernel->join();

  const auto& lat = kernel->latency();
  std::printf(
      "rt_latency_bench: period %.1f us, %.1f s, %s priority %d, dma_latency %s, %llu periods "
      "(%llu expected), %llu overruns\n"
      "  %llu wake-ups, %llu catch-up periods (already due after a stall: no sleep, no wake-up)\n",
      period_us, seconds, kernel->schedule() == lcnc::rt::RtSchedule::Fifo ? "SCHED_FIFO" : "NOT real-time,",
      priority, dma.held() ? "0 us" : "not set", static_cast<unsigned long long>(kernel->periods()),
      static_cast<unsigned long long>(seconds * 1e6 / period_us),
      static_cast<unsigned long long>(kernel->overruns()), static_cast<unsigned long long>(lat.total()),
      static_cast<unsigned long long>(kernel->catch_up_periods()));
  if (!kernel->warning().empty()) std::printf("warning: %s\n", kernel->warning().c_str());
  lcnc::bench::print_quantiles("wake-up latency", lat);
  lcnc::bench::print_quantiles("compute time", kernel->compute_time());
  if (ended_early) {
    std::fprintf(stderr, "rt_latency_bench: the kernel ended by itself before the duration\n");
    return 1;
  }
  if (!hist_file.empty() && !lcnc::bench::write_histogram(hist_file, lat)) return 1;
  return kernel->schedule() == lcnc::rt::RtSchedule::Fifo ? 0 : 3;
}
