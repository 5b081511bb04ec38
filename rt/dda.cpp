#include "rt/dda.h"

namespace lcnc::rt {

Dda::Dda(const DdaConfig& config)
    : n_cap_(config.capacity),
      max_pulses_(config.max_pulses()),
      ticks_(static_cast<std::size_t>(kAxisCount) * config.max_pulses()) {
  acc_.fill(n_cap_ / 2);  // preset half capacity: pulses centred in the period
}

void Dda::run_period(const std::array<std::int32_t, kAxisCount>& steps,
                     PulseFrame& frame) noexcept {
  frame.ticks_per_period = n_cap_;
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int32_t s = steps[i];
    std::uint32_t n = static_cast<std::uint32_t>(s < 0 ? -s : s);
    if (n > max_pulses_) n = max_pulses_;  // the planner guarantees |s| ≤ max; never overrun storage
    std::uint32_t* out = ticks_.data() + static_cast<std::size_t>(i) * max_pulses_;
    if (n > 0) {
      // t_j = ceil(need_j / n) − 1 with need_j = (j+1)·N − acc0: one
      // division per axis, then need_{j+1} = need_j + N adds q = N / n to
      // the quotient and r = N % n to the remainder, carrying.
      const std::uint32_t q = n_cap_ / n, r = n_cap_ % n;
      const std::uint32_t x0 = n_cap_ - acc_[i] + n - 1;  // need_0 + n − 1
      std::uint32_t a = x0 / n, b = x0 % n;
      for (std::uint32_t j = 0; j < n; ++j) {
        out[j] = a - 1;
        a += q;
        b += r;
        if (b >= n) {
          b -= n;
          ++a;
        }
      }
    }
    // acc is unchanged over a whole period (exactly n overflows of N).
    frame.axes[i] = AxisPulses{n, s < 0, out};
  }
}

void Dda::reference_period(std::uint32_t capacity, std::uint32_t& acc, std::uint32_t n,
                           std::vector<std::uint32_t>& ticks) {
  for (std::uint32_t t = 0; t < capacity; ++t) {
    acc += n;
    if (acc >= capacity) {
      ticks.push_back(t);
      acc -= capacity;
    }
  }
}

}  // namespace lcnc::rt
