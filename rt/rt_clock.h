// What the RT kernel's periods follow: the wall clock or the simulated clock.
#pragma once

#include <cstdint>
#include <ctime>

namespace lcnc::rt {

// What the kernel's periods follow.
//   Wall       each period starts at its deadline on CLOCK_MONOTONIC (the
//              machine; the real-time path, its latency measured).
//   Simulated  the simulated clock: each period starts as soon as the last
//              is done and the producer has kept the buffer above twice its
//              braking reserve (or has ended its stream), i.e. a planner
//              that is never late, and the readers of the trace and log
//              rings have room for it, so nothing is dropped. Machine time
//              still advances by T/K a period: the same periods, positions,
//              pulses and report as on the wall clock, in as much wall time
//              as the computer needs (cycle-time estimates, the tests of
//              what a job does, soak runs). Load on the computer makes it
//              slower, never different. Waiting yields the CPU: this is not
//              the real-time path, and the latency histogram stays empty.
//   SimulatedPaced  the simulated clock held to the wall clock's pace: as
//              Simulated, each period waits for the producer and the rings'
//              readers, and besides never starts before its deadline on
//              CLOCK_MONOTONIC; one that starts late (a wait, a loaded
//              computer) moves the later deadlines by as much instead of
//              catching up. Machine time then runs at wall time or slower,
//              never faster, with the same periods, positions and report:
//              a daemon whose commands (hold, resume, single block) come in
//              the operator's time, on a computer that cannot keep real
//              time (`lasercncd --simulated-clock`, the daemon's tests).
enum class RtClock : std::uint8_t { Wall, Simulated, SimulatedPaced };

// Whether a clock is the simulated one (paced or not).
[[nodiscard]] constexpr bool is_simulated(RtClock c) noexcept { return c != RtClock::Wall; }

inline constexpr std::int64_t kNsPerS = 1'000'000'000;

// CLOCK_MONOTONIC readings as ns, and back (absolute deadlines).
[[nodiscard]] inline std::int64_t to_ns(const timespec& t) noexcept { return t.tv_sec * kNsPerS + t.tv_nsec; }
[[nodiscard]] inline timespec to_timespec(std::int64_t ns) noexcept {
  return timespec{static_cast<time_t>(ns / kNsPerS), static_cast<long>(ns % kNsPerS)};
}

}  // namespace lcnc::rt
