// The RT kernel's thread driver: the thread's creation and scheduling, and
// the clock loop that calls period() — to its absolute deadlines on the wall
// clock, or as soon as the producer and the rings' readers allow on the
// simulated clock (rt/rt_clock.h).
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include "rt/rt_kernel.h"

namespace lcnc::rt {

void RtKernel::start(const RtOptions& options) {
  warning_.clear();
  schedule_ = RtSchedule::Normal;
  // The thread's creation below orders begin()'s writes before its first read.
  begin(options);
  if (!options.try_realtime) {
    warning_ = "real-time scheduling not requested: normal scheduling";
  } else if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    warning_ = std::string("mlockall failed (") + std::strerror(errno) + "): memory may page; ";
  }
  thread_ = std::thread([this] { run(options_); });
  // From here the RT thread runs: the warning string may still grow below
  // (on this thread, before anyone reads it), nothing else is touched.
  if (options.try_realtime) {
    sched_param sp{};
    sp.sched_priority = options.fifo_priority;
    const int rc = pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &sp);
    if (rc == 0) {
      schedule_ = RtSchedule::Fifo;
    } else {
      warning_ += std::string("SCHED_FIFO not permitted (") + std::strerror(rc) +
                  "): the RT thread runs with normal scheduling and its latency is not bounded";
    }
  }
}

void RtKernel::join() {
  if (thread_.joinable()) thread_.join();
}

void RtKernel::run(const RtOptions& options) noexcept {
  // Timer slack (50 µs by default for normal threads) would delay every
  // wake-up; SCHED_FIFO threads have none, the fallback should not either.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  if (options.on_loop_enter) options.on_loop_enter();
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  // The first period starts one nominal period from now (or at the epoch
  // given); after that each deadline is t0 + machine time so far, rounded
  // once (no drift).
  std::int64_t t0 = options.epoch_ns > 0 ? options.epoch_ns : to_ns(now) + period_ns_;
  publish_status(true);
  const bool simulated = is_simulated(options.clock);
  const bool paced = options.clock != RtClock::Simulated;  // sleeps to its deadlines
  while (!port_.shutdown_requested.load(std::memory_order_relaxed)) {
    // 1. sleep to the absolute deadline
    if (simulated) wait_simulated();
    std::int64_t deadline = t0 + std::llround(machine_ns_);
    // a period already due (catching up after a stall) starts at once: on a
    // VM the sleep call alone can cost ~20 µs, which a 25 µs period cannot
    // afford while it catches up
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (options.clock == RtClock::SimulatedPaced && to_ns(now) > deadline) {
      // late: the later deadlines move by as much (no catching up)
      t0 += to_ns(now) - deadline;
      deadline = to_ns(now);
    }
    const bool slept = paced && to_ns(now) < deadline;
    if (slept) {
      const timespec until = to_timespec(deadline);
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) == EINTR) {
      }
      clock_gettime(CLOCK_MONOTONIC, &now);
    }
    // 2. wake-up latency: how late the scheduler woke the thread after its
    // deadline (as cyclictest measures it). A period that was already due
    // — the machine catching up after a stall — is no wake-up: it is counted
    // apart, and the stall once, in the wake-up that ended it. The simulated
    // clock measures none (-1: not measured).
    const std::int64_t late = simulated ? -1 : to_ns(now) - deadline;
    if (!simulated) {
      if (slept) {
        latency_.add(late);
      } else {
        port_.catch_up.fetch_add(1, std::memory_order_relaxed);
      }
    }
    if (!period(to_ns(now), late)) break;
  }
  end_periods();
}

std::size_t RtKernel::refill_level() const noexcept {
  return std::min(kPositionBufferCapacity - 1, 2 * braking_reserve(1.0));
}

void RtKernel::wait_simulated() const noexcept {
  const std::size_t enough = refill_level();
  // Room a period may need: one trace record; a few log records (a state
  // change, an underrun, a fault) — kLogRoom is far more than one period logs.
  constexpr std::size_t kLogRoom = 16;
  const auto behind = [&] {
    if (port_.streaming.load(std::memory_order_acquire) && buffer_.size() < enough) return true;
    if (trace_ != nullptr && trace_->size() >= TraceRing::kCapacity) return true;
    return log_ != nullptr && log_->size() + kLogRoom > RtLogRing::kCapacity;
  };
  // A planner that keeps up refills within a few yields; one that needs
  // longer (a dense program, a loaded computer) is waited for with short
  // clock sleeps, so the simulated machine never holds a core spinning while
  // the threads it waits for want it.
  constexpr int kYields = 64;
  constexpr timespec kNap{0, 50'000};
  for (int n = 0; !port_.shutdown_requested.load(std::memory_order_relaxed) && behind(); ++n) {
    if (n < kYields) {
      sched_yield();
    } else {
      clock_nanosleep(CLOCK_MONOTONIC, 0, &kNap, nullptr);
    }
  }
}

}  // namespace lcnc::rt
