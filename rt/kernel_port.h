// What the RT side of the kernel and its control side share: the commands
// to the RT, and everything the RT publishes (state, fault, homed axes,
// counters, the override it runs at). Only atomics and a lock-free ring, no
// pointer: the port lives in the process beside its RtKernel (lasercnc run,
// the tests, lasercncd) or in a shared-memory segment, where another
// process's kernel — the HAL component's, driven by a HAL thread — is the
// RT side.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <type_traits>

#include "geom/pose.h"
#include "rt/shm_interface.h"
#include "rt/spsc_ring.h"

namespace lcnc::rt {

using shm::MachineState;

// What the control thread asks of the kernel (rt::RtKernel::command).
enum class RtCommandType : std::uint8_t {
  StartJob,  // Idle → Running: the position buffer holds (the start of) a job
  Hold,      // feed hold: ramp to 0 along the path and hold
  Resume,    // release a feed hold
  Stop,      // ramp to rest along the path, discard the rest of the job → Idle
  EStop,     // this period: no more motion, laser off; the job is discarded
  Reset,     // EStop → Idle
  Jog,       // Idle: move `axis` by `value` (mm or deg) at its jog speed
  Home,      // Idle: home `axis` (search, back off, latch)
};
struct RtCommand {
  RtCommandType type = RtCommandType::Stop;
  std::int8_t axis = 0;
  double value = 0.0;
};
using RtCommandRing = SpscRing<RtCommand, 16>;

struct KernelPort {
  RtCommandRing commands;
  // Commands pushed (control side) and taken (RT side, counted after the
  // period's commands changed state and status): the control side knows a
  // command's effect is visible once taken reaches what it pushed.
  std::atomic<std::uint64_t> commands_pushed{0};
  std::atomic<std::uint64_t> commands_taken{0};
  std::atomic<bool> shutdown_requested{false};
  std::atomic<bool> streaming{false};
  // laser_inhibit(): relaxed on both sides — one flag, read once a period,
  // ordering nothing else.
  std::atomic<bool> laser_inhibit{false};
  std::atomic<MachineState> state{MachineState::Idle};
  // Held by the program's M0/M1/M60 (state FeedHold) until a resume. Written
  // by the RT before the state it goes with; relaxed: a flag read on its own.
  std::atomic<bool> program_pause{false};
  // Program pauses begun since start (relaxed: a count read on its own).
  std::atomic<std::uint32_t> program_pauses{0};
  std::atomic<std::uint32_t> homed{0};
  std::atomic<std::uint16_t> fault_code{0};
  std::atomic<std::int8_t> fault_axis{-1};
  std::atomic<std::uint32_t> fault_line{0};
  std::atomic<std::uint64_t> starvations{0};
  std::atomic<std::uint32_t> jobs_ended{0};
  // relaxed: ordered by jobs_ended's release increment after it
  std::atomic<bool> last_job_completed{false};
  std::array<std::atomic<std::int64_t>, kAxisCount> pos_pub{};
  std::array<std::atomic<std::int64_t>, kAxisCount> emitted_pub{};
  std::atomic<bool> finished{false};
  std::atomic<std::uint64_t> periods{0};
  std::atomic<std::uint64_t> motion_periods{0};
  std::atomic<std::uint64_t> underruns{0};
  std::atomic<std::uint64_t> overruns{0};
  std::atomic<std::uint64_t> catch_up{0};
  std::atomic<std::uint64_t> trace_drops{0};
  std::atomic<std::uint64_t> log_drops{0};
  std::atomic<std::uint32_t> segment{0};  // of the last path entry taken
  std::atomic<std::uint32_t> line{0};     // its program line
  // The operator's override E, a fraction: set_feed_override()'s relaxed store pairs with
  // the RT's relaxed load (a lone value, nothing published with it).
  std::atomic<double> override_target{1.0};
  // Like the counters: written by the RT side only, relaxed snapshots.
  std::atomic<double> k_now{1.0};
  std::atomic<std::int64_t> machine_time_ns{0};
  std::atomic<std::int64_t> laser_on_ns{0};
  std::atomic<std::uint64_t> held_periods{0};
  static_assert(std::atomic<double>::is_always_lock_free);
  static_assert(std::atomic<std::int64_t>::is_always_lock_free);
};
static_assert(std::is_standard_layout_v<KernelPort>);

}  // namespace lcnc::rt
