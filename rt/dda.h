// DDA fine interpolation (docs/design.md §5.4, Chi, Wu and Cui (2020) §3.1), bit-exact with hdl/.
//
// Per axis an accumulator of capacity N, preset to N/2 at start and carried
// across periods. On each of the N clock ticks of a period: acc += n; when
// acc ≥ N a pulse is emitted on that tick and acc −= N. Since acc stays in
// [0, N), every period emits exactly n pulses, spread evenly.
//
// Closed form used here (O(n) per axis instead of O(N)): the j-th pulse
// (j = 0 … n−1) falls on the first tick t with acc0 + (t+1)·n ≥ (j+1)·N:
//   t_j = ceil(((j+1)·N − acc0) / n) − 1,
// and acc_end = acc0 + N·n − N·n = acc0: a full period leaves the
// accumulator unchanged; only the tick positions depend on it. The
// numerators grow by N from one pulse to the next, so after one division per
// axis each t_j follows from the last by adding N / n and carrying N % n.
// Since the accumulator ends every period where it began (N/2), a period's
// ticks depend on n alone: up to kTabulatedMaxPulses (every preset of 10
// bits or less: ≤ 2 MB) they are tabulated once in the constructor and a
// period only looks them up; wider presets compute them per period.
// reference_period() runs the tick loop itself; tests hold the two equal.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "machine/machine_config.h"
#include "machine/pulse_sink.h"

namespace lcnc::rt {

class Dda {
 public:
  // Tabulated when max pulses ≤ this (Σ n ≤ 523,776 ticks).
  static constexpr std::uint32_t kTabulatedMaxPulses = 1023;

  // Allocates the tick storage (the table, or max pulses per axis) once, here.
  explicit Dda(const DdaConfig& config);

  // One period for all axes; fills `frame` (ticks point into this Dda's
  // storage, valid until the next call). steps[i] must satisfy |steps| ≤ max.
  void run_period(const std::array<std::int32_t, kAxisCount>& steps, PulseFrame& frame) noexcept;

  // Every axis's accumulator, at the end of any period: the N/2 it is
  // preset to (a whole period leaves it unchanged, see above).
  [[nodiscard]] std::uint32_t accumulator() const noexcept { return n_cap_ / 2; }
  [[nodiscard]] std::uint32_t capacity() const noexcept { return n_cap_; }

  // The tick-by-tick definition, for tests and for cross-checking hdl/.
  // Appends the pulse ticks of one period with magnitude n to `ticks`.
  static void reference_period(std::uint32_t capacity, std::uint32_t& acc, std::uint32_t n,
                               std::vector<std::uint32_t>& ticks);

 private:
  std::uint32_t n_cap_;
  std::uint32_t max_pulses_;
  std::vector<std::uint32_t> first_;  // tabulated: n's ticks start at ticks_[first_[n]]; else empty
  std::vector<std::uint32_t> ticks_;  // the table, or kAxisCount × max_pulses_ to compute into
};

}  // namespace lcnc::rt
