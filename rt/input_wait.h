// M66 in the RT kernel: a job holds at the entry that asks (a dwell's
// entry, the machine at rest) until one of the program's digital inputs does
// what the entry's mode asks, or until the entry's timeout runs out. The
// timeout is counted in periods, so it lasts the same machine time on the
// wall clock and on the simulated one. RT path: no allocation, no syscall.
#pragma once

#include <cmath>
#include <cstdint>

namespace lcnc::rt {

class InputWait {
 public:
  // What the input must do (PeriodIncrement::wait_mode): 1 rise, 2 fall,
  // 3 be high, 4 (and anything else) be low.
  enum class Outcome : std::uint8_t { Waiting, Met, TimedOut };

  // Begins a wait on input `input` (bit of `digital_in`, the inputs' levels
  // now) for at most timeout_s (at least one period).
  void arm(std::int8_t input, std::uint8_t mode, double timeout_s, std::uint32_t period_ns,
           std::uint8_t digital_in) noexcept {
    input_ = input;
    mode_ = mode;
    prev_ = level(digital_in);
    const double periods = std::ceil(timeout_s * 1e9 / static_cast<double>(period_ns));
    left_ = periods < 1.0 ? 1 : static_cast<std::uint64_t>(periods);
    periods_ = 0;
    active_ = true;
  }
  // One period's inputs. Met or TimedOut end the wait.
  [[nodiscard]] Outcome check(std::uint8_t digital_in) noexcept {
    const bool now = level(digital_in);
    bool met = false;
    switch (mode_) {
      case 1: met = !prev_ && now; break;
      case 2: met = prev_ && !now; break;
      case 3: met = now; break;
      default: met = !now; break;
    }
    prev_ = now;
    ++periods_;
    if (met) {
      active_ = false;
      return Outcome::Met;
    }
    if (--left_ == 0) {
      active_ = false;
      return Outcome::TimedOut;
    }
    return Outcome::Waiting;
  }
  void cancel() noexcept { active_ = false; }

  [[nodiscard]] bool active() const noexcept { return active_; }
  [[nodiscard]] std::int8_t input() const noexcept { return input_; }
  [[nodiscard]] std::uint8_t mode() const noexcept { return mode_; }
  // Periods the wait has lasted.
  [[nodiscard]] std::uint64_t periods() const noexcept { return periods_; }

 private:
  [[nodiscard]] bool level(std::uint8_t digital_in) const noexcept {
    return ((digital_in >> input_) & 1u) != 0;
  }

  bool active_ = false;
  std::int8_t input_ = -1;
  std::uint8_t mode_ = 0;
  bool prev_ = false;  // the input's level the period before
  std::uint64_t left_ = 0;
  std::uint64_t periods_ = 0;
};

}  // namespace lcnc::rt
