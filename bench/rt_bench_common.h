// What rt_latency_bench and rt_cycle_bench share: the machine they run, the
// RT environment cyclictest sets up too (/dev/cpu_dma_latency), ending the
// kernel, and printing a LatencyHistogram — as quantiles, and as a
// cyclictest-style histogram file so that bench/rt_latency_vs_cyclictest.sh
// reads both tools' figures with one parser.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>

#include "machine/machine_config.h"
#include "rt/latency_histogram.h"
#include "rt/rt_kernel.h"

namespace lcnc::bench {

// share/machines/default.toml (or `file`) at the given period.
inline std::optional<MachineConfig> load_machine(const std::string& file, std::uint32_t period_ns) {
  auto m = load_machine_config(file.empty() ? std::string(LCNC_SHARE_DIR) + "/machines/default.toml" : file);
  if (!m) {
    std::fprintf(stderr, "%s\n", m.error().to_string().c_str());
    return std::nullopt;
  }
  m->period_ns = period_ns;
  return *m;
}

// Ends the RT thread after its current period. The kernel's API is being
// extended (stop() became shutdown()); accept either until it settles.
template <typename Kernel>
void end_kernel(Kernel& kernel) {
  if constexpr (requires { kernel.shutdown(); }) {
    kernel.shutdown();
  } else {
    kernel.stop();
  }
}

// Asks the CPU to leave no deep idle state while held (writes 0 µs to
// /dev/cpu_dma_latency, as cyclictest does by default): a fair comparison
// with cyclictest, and what a real-time deployment does. Needs root.
class DmaLatencyHold {
 public:
  explicit DmaLatencyHold(bool enable) {
    if (!enable) return;
    fd_ = open("/dev/cpu_dma_latency", O_RDWR);
    const std::int32_t zero = 0;
    if (fd_ >= 0 && write(fd_, &zero, sizeof zero) != static_cast<ssize_t>(sizeof zero)) {
      close(fd_);
      fd_ = -1;
    }
  }
  ~DmaLatencyHold() {
    if (fd_ >= 0) close(fd_);
  }
  DmaLatencyHold(const DmaLatencyHold&) = delete;
  DmaLatencyHold& operator=(const DmaLatencyHold&) = delete;
  [[nodiscard]] bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// "name: p50 … p99 … p99.9 … max … µs (N samples)". Quantiles are the upper
// edge of their bucket (LatencyHistogram::quantile_us).
inline void print_quantiles(const char* name, const rt::LatencyHistogram& h) {
  std::printf("%s: p50 %.2f  p99 %.2f  p99.9 %.2f  max %.2f us  (%llu samples, %u ns buckets)\n", name,
              h.quantile_us(0.5), h.quantile_us(0.99), h.quantile_us(0.999),
              static_cast<double>(h.max_ns()) / 1000.0, static_cast<unsigned long long>(h.total()),
              h.bucket_ns());
}

// The histogram in cyclictest's -h format: "%06d %06llu" per bucket (the
// bucket's lower edge in bucket units), then the summary lines cyclictest
// prints (Total counts the buckets only, as cyclictest's does; Max in whole
// µs, truncated like cyclictest's). 1 µs buckets read as cyclictest's.
inline bool write_histogram(const std::string& path, const rt::LatencyHistogram& h) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "cannot write %s: %s\n", path.c_str(), std::strerror(errno));
    return false;
  }
  const auto& counts = h.counts();
  std::uint64_t in_buckets = 0;
  std::fprintf(f, "# LaserCNC RtKernel histogram, %u ns buckets\n# Histogram\n", h.bucket_ns());
  for (std::uint32_t b = 0; b < rt::LatencyHistogram::kBuckets; ++b) {
    std::fprintf(f, "%06u %06llu\n", b, static_cast<unsigned long long>(counts[b]));
    in_buckets += counts[b];
  }
  std::fprintf(f, "# Total: %09llu\n", static_cast<unsigned long long>(in_buckets));
  std::fprintf(f, "# Max Latencies: %05lld\n", static_cast<long long>(h.max_ns() / 1000));
  std::fprintf(f, "# Histogram Overflows: %05llu\n",
               static_cast<unsigned long long>(counts[rt::LatencyHistogram::kBuckets]));
  return std::fclose(f) == 0;
}

// --name value / --flag parsing for the two benches.
inline const char* arg_value(int& i, int argc, char** argv) {
  if (i + 1 >= argc) {
    std::fprintf(stderr, "%s needs a value\n", argv[i]);
    std::exit(2);
  }
  return argv[++i];
}

}  // namespace lcnc::bench
