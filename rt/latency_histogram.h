// Wake-up latency of the RT thread: how late after its absolute deadline
// clock_nanosleep returned (and, with finer buckets, the period's compute
// time). kBuckets fixed-width buckets (1 µs unless given) plus an overflow
// bucket; written by the RT thread only (no atomics needed while it
// runs; read after it has stopped, or copied under the status seqlock).
#pragma once

#include <array>
#include <cstdint>

namespace lcnc::rt {

class LatencyHistogram {
 public:
  static constexpr std::uint32_t kBuckets = 2000;  // 0 … 1999 buckets, then overflow

  explicit LatencyHistogram(std::uint32_t bucket_ns = 1000) noexcept : bucket_ns_(bucket_ns) {}

  void add(std::int64_t latency_ns) noexcept {
    if (latency_ns < 0) latency_ns = 0;
    const std::uint64_t b = static_cast<std::uint64_t>(latency_ns) / bucket_ns_;
    ++counts_[b < kBuckets ? b : kBuckets];
    ++total_;
    if (latency_ns > max_ns_) max_ns_ = latency_ns;
  }

  [[nodiscard]] std::uint64_t total() const noexcept { return total_; }
  [[nodiscard]] std::int64_t max_ns() const noexcept { return max_ns_; }
  [[nodiscard]] std::uint32_t bucket_ns() const noexcept { return bucket_ns_; }
  // Upper edge (µs) of the bucket holding quantile q ∈ [0, 1].
  [[nodiscard]] double quantile_us(double q) const noexcept {
    if (total_ == 0) return 0.0;
    const auto rank = static_cast<std::uint64_t>(q * static_cast<double>(total_ - 1)) + 1;
    std::uint64_t seen = 0;
    for (std::uint32_t b = 0; b <= kBuckets; ++b) {
      seen += counts_[b];
      if (seen >= rank)
        return b < kBuckets ? (b + 1.0) * bucket_ns_ / 1000.0 : static_cast<double>(max_ns_) / 1000.0;
    }
    return static_cast<double>(max_ns_) / 1000.0;
  }
  [[nodiscard]] const std::array<std::uint64_t, kBuckets + 1>& counts() const noexcept { return counts_; }

 private:
  std::uint32_t bucket_ns_;
  std::array<std::uint64_t, kBuckets + 1> counts_{};
  std::uint64_t total_ = 0;
  std::int64_t max_ns_ = 0;
};

}  // namespace lcnc::rt
