// The kernel's status in the shared-memory block's seqlock (shm::Status),
// for the daemon, the CLI and the HMI: every kStatusEvery periods and on
// every state change — often enough for a screen, seldom enough that the
// readers' retries never matter. RT path: a copy under the seqlock, nothing
// else.
#pragma once

#include <cstdint>

#include "rt/latency_histogram.h"
#include "rt/seqlock.h"
#include "rt/shm_interface.h"

namespace lcnc::rt {

// Status publication period (periods): ~5 ms at 75 µs.
inline constexpr std::uint64_t kStatusEvery = 64;

class StatusPublisher {
 public:
  // Where it publishes; null: nowhere (then nothing is ever due).
  void attach(Seqlock<shm::Status>* target) noexcept { target_ = target; }
  // Whether period `period` publishes: forced (a state change, the start,
  // the end), or kStatusEvery periods since the last.
  [[nodiscard]] bool due(std::uint64_t period, bool force) noexcept {
    if (target_ == nullptr || (!force && period - last_ < kStatusEvery)) return false;
    last_ = period;
    return true;
  }
  // Publishes `st` with the wake-up latency's quantiles, refreshed once
  // every 64 publications (they scan the histogram) and when forced.
  void publish(shm::Status& st, const LatencyHistogram& latency, std::uint64_t period, bool force) noexcept {
    if (force || (period / kStatusEvery) % 64 == 0) {
      p50_ = latency.quantile_us(0.50);
      p99_ = latency.quantile_us(0.99);
    }
    st.latency_p50_us = static_cast<float>(p50_);
    st.latency_p99_us = static_cast<float>(p99_);
    st.latency_max_us = static_cast<float>(static_cast<double>(latency.max_ns()) / 1000.0);
    target_->store(st);
  }

 private:
  Seqlock<shm::Status>* target_ = nullptr;
  std::uint64_t last_ = 0;
  double p50_ = 0.0, p99_ = 0.0;
};

}  // namespace lcnc::rt
