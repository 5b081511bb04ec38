// The control side of the RT kernel: what a control thread asks of it
// (commands, the override, the stream's begin and end) and what it reads
// back (state, fault, counters, positions), all through the kernel's
// KernelPort. RtKernel is one (its port is its own, or one it is given);
// `lasercncd --hal` holds a bare one over the port in the shared-memory
// segment whose RT side is the HAL component's kernel (rt/hal_block.h).
// Lock-free: any method may be called while the RT side runs.
#pragma once

#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "machine/machine_config.h"
#include "rt/feed_override.h"
#include "rt/kernel_port.h"

namespace lcnc::rt {

// The fault that ended motion, if any.
struct RtFault {
  ErrorCode code = ErrorCode::Ok;  // Ok: none (active false)
  int axis = -1;                   // axis index, −1 if none
  std::uint32_t line = 0;          // program line, 0 if none
  bool active = false;
};

class KernelControl {
 public:
  KernelControl(const MachineConfig& machine, KernelPort& port);

  [[nodiscard]] std::uint64_t log_drops() const noexcept {
    return port_.log_drops.load(std::memory_order_relaxed);
  }
  // A command for the RT thread, executed at the start of its next period.
  // From one control thread only (single producer). False if the ring is
  // full (16 pending commands).
  bool command(const RtCommand& c) noexcept {
    if (!port_.commands.try_push(c)) return false;
    port_.commands_pushed.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  // Every command pushed has been taken by the RT side, and what it did
  // (state, status, fault) is published. acquire pairs with the RT's
  // release store of commands_taken.
  [[nodiscard]] bool commands_taken() const noexcept {
    return port_.commands_taken.load(std::memory_order_acquire) >=
           port_.commands_pushed.load(std::memory_order_relaxed);
  }

  // The producer of the position buffer streams a job that is longer than
  // the buffer: while streaming, the kernel keeps a braking reserve in the
  // buffer and decelerates along the path when the fill drops below it
  // (rt/rt_kernel.h, step 5). stream_end() after the job's last entry is pushed (or
  // the producer gave up): the kernel then runs the buffer dry, and a
  // stopped job's flush completes.
  void stream_begin() noexcept { port_.streaming.store(true, std::memory_order_release); }
  void stream_end() noexcept { port_.streaming.store(false, std::memory_order_release); }
  // Laser output off from the next period on, whatever the job commands (a
  // lost or alarming laser source: the job then stops along the path with
  // the beam off; a run's kernel is not used again). From any thread.
  void laser_inhibit() noexcept { port_.laser_inhibit.store(true, std::memory_order_relaxed); }
  // Entries the kernel keeps in the buffer to brake from K to 0 along the
  // path at the override ramp: K²/(2ρT) plus a margin.
  [[nodiscard]] std::size_t braking_reserve(double k) const noexcept;

  [[nodiscard]] MachineState state() const noexcept { return port_.state.load(std::memory_order_acquire); }
  // The job holds at its M0/M1/M60 until Resume.
  [[nodiscard]] bool program_paused() const noexcept {
    return port_.program_pause.load(std::memory_order_relaxed);
  }
  // How many such pauses have begun (a run resumes each once).
  [[nodiscard]] std::uint32_t program_pauses() const noexcept {
    return port_.program_pauses.load(std::memory_order_relaxed);
  }
  // The last fault (code, axis, line), cleared by Reset/StartJob.
  [[nodiscard]] RtFault fault() const noexcept;
  // Axes whose position is known (homed, or known at start): bit per axis.
  [[nodiscard]] std::uint32_t homed_mask() const noexcept {
    return port_.homed.load(std::memory_order_relaxed);
  }
  // Jobs that have ended (at their end, by a stop or by an e-stop).
  [[nodiscard]] std::uint32_t jobs_ended() const noexcept {
    return port_.jobs_ended.load(std::memory_order_acquire);
  }
  // The last job ended ran to its end (not stopped, not e-stopped). Written
  // before jobs_ended() counts it: read after seeing that count.
  [[nodiscard]] bool last_job_completed() const noexcept {
    return port_.last_job_completed.load(std::memory_order_relaxed);
  }

  // The operator's feed override E, a fraction (1 = 100 %), from any
  // thread, lock-free. Clamped to 0 … machine.max_feed_override
  // (FeedOverrideRamp::clamp_target); 0 is a feed hold. The RT thread scales
  // the periods of what is planned (at K = min(1, E / the override an entry
  // is planned at), ramped: rt/feed_override.h); the planner plans for E
  // above 1 (app/planner_feed.h). Set before start(), the run begins at it
  // with no ramp. Default 1.
  void set_feed_override(double e) noexcept {
    // relaxed: a lone value, read by the RT thread's relaxed load in
    // period(); nothing else is published with it.
    port_.override_target.store(ramp_.clamp_target(e), std::memory_order_relaxed);
  }
  // The override asked for (clamped), which the planner plans for.
  [[nodiscard]] double feed_override_target() const noexcept {
    return port_.override_target.load(std::memory_order_relaxed);
  }
  // The override the machine runs at now: the period scale times the
  // override the running entries are planned at.
  [[nodiscard]] double feed_override() const noexcept { return port_.k_now.load(std::memory_order_relaxed); }
  [[nodiscard]] const FeedOverrideRamp& override_ramp() const noexcept { return ramp_; }

  [[nodiscard]] bool finished() const noexcept { return port_.finished.load(std::memory_order_acquire); }

  // Live counters (relaxed snapshots; exact after join()).
  [[nodiscard]] std::uint64_t periods() const noexcept {
    return port_.periods.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t motion_periods() const noexcept {
    return port_.motion_periods.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t underruns() const noexcept {
    return port_.underruns.load(std::memory_order_relaxed);
  }
  // Times the buffer fell below its braking reserve while streaming.
  [[nodiscard]] std::uint64_t starvations() const noexcept {
    return port_.starvations.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t overruns() const noexcept {
    return port_.overruns.load(std::memory_order_relaxed);
  }
  // Periods that were already due when the last one ended (catching up after
  // a stall): started at once, without a sleep, so without a wake-up latency.
  [[nodiscard]] std::uint64_t catch_up_periods() const noexcept {
    return port_.catch_up.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t trace_drops() const noexcept {
    return port_.trace_drops.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint32_t current_segment() const noexcept {
    return port_.segment.load(std::memory_order_relaxed);
  }
  // Machine time: Σ of the executed periods' lengths (T/K, T while held), and
  // the part of it with the laser on.
  [[nodiscard]] std::int64_t machine_time_ns() const noexcept {
    return port_.machine_time_ns.load(std::memory_order_relaxed);
  }
  [[nodiscard]] std::int64_t laser_on_ns() const noexcept {
    return port_.laser_on_ns.load(std::memory_order_relaxed);
  }
  // Periods held by the feed override (K < K_min).
  [[nodiscard]] std::uint64_t held_periods() const noexcept {
    return port_.held_periods.load(std::memory_order_relaxed);
  }

  // Commanded position, machine coordinates (steps); relaxed snapshot.
  [[nodiscard]] std::int64_t position_steps(int axis) const noexcept {
    return port_.pos_pub[axis].load(std::memory_order_relaxed);
  }
  // Net pulses emitted since start, per axis: the commanded motion plus the
  // change of the pitch correction (homing moves the coordinate, not the
  // pulses).
  [[nodiscard]] std::int64_t pulses_emitted(int axis) const noexcept {
    return port_.emitted_pub[axis].load(std::memory_order_relaxed);
  }

 protected:
  KernelPort& port_;
  FeedOverrideRamp ramp_;
  double period_s_;
  double brake_wait_s_ = 0.0;  // longest braking of an axis from vmax at amax
};

}  // namespace lcnc::rt
