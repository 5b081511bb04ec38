#include "rt/dda.h"

namespace lcnc::rt {

namespace {

// The ticks of one period of magnitude n from accumulator acc0 (closed form,
// see dda.h): one division, then add-and-carry per pulse.
void period_ticks(std::uint32_t capacity, std::uint32_t acc0, std::uint32_t n, std::uint32_t* out) noexcept {
  if (n == 0) return;
  // t_j = ceil(need_j / n) − 1 with need_j = (j+1)·N − acc0: need_{j+1} =
  // need_j + N adds q = N / n to the quotient and r = N % n to the remainder.
  const std::uint32_t q = capacity / n, r = capacity % n;
  const std::uint32_t x0 = capacity - acc0 + n - 1;  // need_0 + n − 1
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

}  // namespace

Dda::Dda(const DdaConfig& config) : n_cap_(config.capacity), max_pulses_(config.max_pulses()) {
  // The accumulators are preset to half capacity: pulses centred in the period.
  if (max_pulses_ <= kTabulatedMaxPulses) {
    // Every axis starts at N/2 and a whole period leaves it there, so a
    // period's ticks depend on n alone: the table of every n, here, once.
    first_.resize(max_pulses_ + 2);
    for (std::uint32_t n = 0; n <= max_pulses_; ++n) first_[n + 1] = first_[n] + n;
    ticks_.resize(first_.back());
    for (std::uint32_t n = 1; n <= max_pulses_; ++n)
      period_ticks(n_cap_, n_cap_ / 2, n, ticks_.data() + first_[n]);
  } else {
    ticks_.resize(static_cast<std::size_t>(kAxisCount) * max_pulses_);
  }
}

void Dda::run_period(const std::array<std::int32_t, kAxisCount>& steps, PulseFrame& frame) noexcept {
  frame.ticks_per_period = n_cap_;
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int32_t s = steps[i];
    std::uint32_t n = static_cast<std::uint32_t>(s < 0 ? -s : s);
    if (n > max_pulses_) n = max_pulses_;  // the planner guarantees |s| ≤ max; never overrun storage
    const std::uint32_t* ticks;
    if (!first_.empty()) {
      ticks = ticks_.data() + first_[n];
    } else {
      std::uint32_t* out = ticks_.data() + static_cast<std::size_t>(i) * max_pulses_;
      period_ticks(n_cap_, accumulator(), n, out);
      ticks = out;
    }
    // acc is unchanged over a whole period (exactly n overflows of N).
    frame.axes[i] = AxisPulses{n, s < 0, ticks};
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
