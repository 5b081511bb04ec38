// The RT kernel's period step: commands, inputs, the period's motion, limits,
// DDA and send, accounting and status (steps 2–9 of rt/rt_kernel.h).
#include "rt/rt_kernel.h"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace lcnc::rt {

RtKernel::RtKernel(const MachineConfig& machine, PositionBuffer& buffer, PulseSink& sink, TraceRing* trace,
                   const std::array<std::int64_t, kAxisCount>& start_steps, KernelPort* port)
    : KernelControl(machine, port != nullptr ? *port : own_port_),
      period_ns_(machine.period_ns),
      mover_(machine, ramp_.rate_per_s()),
      buffer_(buffer),
      sink_(sink),
      trace_(trace),
      dda_(machine.dda),
      pos_steps_(start_steps) {
  port_.override_target.store(ramp_.clamp_target(1.0), std::memory_order_relaxed);
  max_pulses_ = machine.dda.max_pulses();
  comp_.reserve(kAxisCount);
  for (int i = 0; i < kAxisCount; ++i) {
    comp_.emplace_back(machine.axes[i]);
    comp_now_[i] = comp_[i].correction_steps(start_steps[i]);
  }
  std::uint32_t known = 0;
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine.axes[i];
    port_.pos_pub[i].store(start_steps[i], std::memory_order_relaxed);
    units_per_step_[i] = 1.0 / (ax.present ? ax.steps_per_unit : 1.0);
    if (ax.present) known |= 1u << i;
  }
  axes_mask_ = known;
  // The simulated machine's position is known at power-on.
  port_.homed.store(known, std::memory_order_relaxed);
}

RtKernel::~RtKernel() {
  shutdown();
  join();
}

void RtKernel::begin(const RtOptions& options) noexcept {
  options_ = options;
  // The run begins at the override already asked for, with no ramp.
  begin_at_override();
  state_now_ = options.start_running ? MachineState::Running : MachineState::Idle;
  port_.state.store(state_now_, std::memory_order_release);
  if (!options.start_homed) port_.homed.store(0, std::memory_order_relaxed);
  // requests made before the kernel ran are not this run's
  if (estop_word_ != nullptr) estop_seen_ = estop_word_->load(std::memory_order_acquire);
}

void RtKernel::end_periods() noexcept {
  publish_status(true);
  if (options_.on_loop_exit) options_.on_loop_exit();
  // release pairs with finished()'s acquire: counters and positions written
  // above are visible to a thread that sees finished.
  port_.finished.store(true, std::memory_order_release);
}

bool RtKernel::period(std::int64_t wake_ns, std::int64_t late) noexcept {
  const RtOptions& options = options_;
  // 3–4. commands and inputs
  take_commands();
  take_inputs();
  // 5. the period's motion
  Motion m;
  if (on_path_state()) {
    path_motion(m);
  } else if (state_now_ == MachineState::Jog || state_now_ == MachineState::Homing) {
    axis_motion(m);
  }
  if (flushing_) flush_some();
  // 6. limits
  guard_limits(m);
  const double length_ns = m.nominal ? static_cast<double>(period_ns_) : period_ns_ / k_;
  if (late >= 0) {
    // woken after the period's end: an overrun
    if (static_cast<double>(late) > length_ns) port_.overruns.fetch_add(1, std::memory_order_relaxed);
    // a stall makes the periods after it late too, catching up: log the
    // streak once, where it starts
    if (late > kLateLogNs && !late_streak_) log(RtLogCode::LateWakeup, late);
    late_streak_ = static_cast<double>(late) > length_ns;
  }
  // 7–8. the period's work
  machine_ns_ += length_ns;
  cycle(m, length_ns, std::llround(machine_ns_));
  port_.periods.store(++period_, std::memory_order_relaxed);
  publish_status(false);
  timespec done{};
  clock_gettime(CLOCK_MONOTONIC, &done);
  compute_.add(to_ns(done) - wake_ns);
  if (job_end_pending_) {
    // a one-shot run ends in the mode its last entry left (Running)
    if (options.exit_at_end) {
      job_ended(true);
      return false;
    }
    transition(KernelEvent::JobEnd);
  }
  // a one-shot run ends once a stop or an e-stop has settled
  if (options.exit_at_end && job_aborted_ && !flushing_) return false;
  // 9. ramp K toward the next period's target: the operator's override
  // over what the next entry is planned at, eq. (0) of feed_override.h,
  // as fast as that entry's room allows. relaxed pairs with
  // set_feed_override()'s relaxed store: only the value is read.
  double target = port_.override_target.load(std::memory_order_relaxed);
  RampRoom room;  // jogs, homing: the ramp's own rate
  if (on_path_state()) {
    if (const PeriodIncrement* next = buffer_.front()) {
      k_plan_ = next->k_plan;
      room = next->ramp;
      target = path_target(target, next->feed_control);
    } else {
      room = m.inc.ramp;  // none queued: the last entry's
      target = path_target(target, m.inc.feed_control);
    }
  } else {
    k_plan_ = 1.0f;  // jogs and homing are not planned
  }
  if (state_now_ == MachineState::FeedHold || state_now_ == MachineState::Stopping || starving_) target = 0.0;
  k_ = ramp_.step(k_, ramp_.period_scale(target, k_plan_), length_ns * 1e-9, room);
  port_.k_now.store(k_ * k_plan_, std::memory_order_relaxed);
  return true;
}

// The override target for a path entry, by its M48 … M53 switches
// (PeriodIncrement::feed_control): the operator's e, or 1 where the program
// turned the override off; times the adaptive-feed input where it turned
// adaptive feed on; 0 while the feed-hold input is on, unless turned off.
double RtKernel::path_target(double e, std::uint8_t feed_control) const noexcept {
  if ((feed_control & kFeedOverrideOff) != 0 && e > 0.0) e = 1.0;
  if ((feed_control & kAdaptiveFeed) != 0) {
    const double a = inputs_.adaptive_feed;
    e *= a > 0.0 ? std::min(1.0, a) : 0.0;  // NaN and below 0: stand still
  }
  if ((feed_control & kFeedHoldInputOff) == 0 && inputs_.feed_hold) e = 0.0;
  return e;
}

void RtKernel::begin_at_override() noexcept {
  const PeriodIncrement* first = buffer_.front();
  k_plan_ = first != nullptr ? first->k_plan : 1.0f;
  double e = port_.override_target.load(std::memory_order_relaxed);
  if (first != nullptr) e = path_target(e, first->feed_control);
  k_ = e > 0.0 ? ramp_.period_scale(e, k_plan_) : 0.0;
  port_.k_now.store(k_ * k_plan_, std::memory_order_relaxed);
}

void RtKernel::log(RtLogCode code, std::int64_t value, int axis, std::uint32_t line) noexcept {
  if (log_ == nullptr) return;
  if (!log_->try_push(RtLogRecord{period_, code, static_cast<std::int8_t>(axis), line, value}))
    port_.log_drops.fetch_add(1, std::memory_order_relaxed);
}

void RtKernel::take_commands() noexcept {
  // The e-stop word: acquire pairs with ShmClient::request_estop's release
  // add. One load per period; a changed count is an e-stop now, however
  // many requests it counts.
  if (estop_word_ != nullptr) {
    const std::uint32_t n = estop_word_->load(std::memory_order_acquire);
    if (n != estop_seen_) {
      estop_seen_ = n;
      enter_estop(ErrorCode::RtEstop, -1, line_);
    }
  }
  // Every command of the period is taken in the state the period began in,
  // but none moves the machine after an e-stop among them.
  const MachineState s = state_now_;
  RtCommand c;
  std::uint64_t taken = 0;
  while (port_.commands.try_pop(c)) {
    if (!take_command(c, s)) log(RtLogCode::Refused, static_cast<std::int64_t>(c.type), c.axis);
    ++taken;
  }
  // release: what the commands changed (state, status) is seen with the count
  if (taken != 0) port_.commands_taken.fetch_add(taken, std::memory_order_release);
  // a Reset leaves the e-stop once the aborted job's entries are flushed
  if (reset_pending_ && transition(KernelEvent::Reset)) reset_pending_ = false;
}

bool RtKernel::take_command(const RtCommand& c, MachineState s) noexcept {
  // Every command but the e-stop and the stop needs the mode the period
  // began in: none acts on a change made earlier in the same period.
  const bool unchanged = s == state_now_;
  switch (c.type) {
    case RtCommandType::EStop: enter_estop(ErrorCode::RtEstop, -1, line_); return true;
    case RtCommandType::Stop:
      begin_stop(ErrorCode::Ok, -1, 0);  // the operator's: no fault
      return true;
    case RtCommandType::Reset:
      if (unchanged && s == MachineState::EStop) reset_pending_ = true;
      return true;
    case RtCommandType::Hold:
      if (unchanged) transition(KernelEvent::Hold);
      return true;
    case RtCommandType::Resume:
      if (unchanged) transition(KernelEvent::Resume);  // an M66 waits for its input
      return true;
    case RtCommandType::StartJob: return unchanged && transition(KernelEvent::Start);
    case RtCommandType::Jog: return unchanged && start_jog(c.axis, c.value);
    case RtCommandType::Home: return unchanged && start_home(c.axis);
  }
  return true;
}

bool RtKernel::start_jog(int axis, double distance) noexcept {
  if (!takes(KernelEvent::Jog) || axis < 0 || axis >= kAxisCount || !mover_.limits(axis).present)
    return false;
  const std::int64_t target = pos_steps_[axis] + std::llround(distance / units_per_step_[axis]);
  const bool homed = ((port_.homed.load(std::memory_order_relaxed) >> axis) & 1u) != 0;
  const std::int64_t short_by = mover_.start_jog(axis, pos_steps_[axis], target, homed, period_s_);
  if (short_by != 0) log(RtLogCode::JogShort, short_by, axis);
  return transition(KernelEvent::Jog);
}

bool RtKernel::start_home(int axis) noexcept {
  if (!takes(KernelEvent::Home) || axis < 0 || axis >= kAxisCount || !mover_.limits(axis).present ||
      !mover_.can_home(axis))
    return false;
  port_.homed.fetch_and(~(1u << axis), std::memory_order_relaxed);
  mover_.start_home(axis, inputs_.home[axis], period_s_);
  return transition(KernelEvent::Home);
}

void RtKernel::take_inputs() noexcept {
  inputs_ = sink_.read_inputs();
  if (state_now_ == MachineState::EStop) return;
  if (inputs_.estop) {
    enter_estop(ErrorCode::RtEstop, -1, line_);
  } else if (inputs_.amp_fault) {
    enter_estop(ErrorCode::RtAmpFault, -1, line_);
  } else if (inputs_.following_error_axis >= 0) {
    enter_estop(ErrorCode::RtFollowingError, inputs_.following_error_axis, line_);
  } else if (wait_.active()) {
    // M66: the input came (the job goes on), or the time is up (a stop, at
    // rest already, with the fault)
    switch (wait_.check(inputs_.digital_in)) {
      case InputWait::Outcome::Waiting: break;
      case InputWait::Outcome::Met:
        log(RtLogCode::InputWaitEnd, static_cast<std::int64_t>(wait_.periods()), -1, line_);
        transition(KernelEvent::InputCame);
        break;
      case InputWait::Outcome::TimedOut: begin_stop(ErrorCode::RtInputTimeout, -1, line_); break;
    }
  } else if (hold_cause_ == HoldCause::ProgramPause && pause_left_ > 0 && --pause_left_ == 0) {
    // an unattended pause's time is up: as a resume
    transition(KernelEvent::PauseUp);
  }
}

void RtKernel::path_motion(Motion& m) noexcept {
  m.on_path = true;
  // the buffer's braking reserve while a producer streams
  const bool streaming = port_.streaming.load(std::memory_order_acquire);
  const std::size_t fill = buffer_.size();
  const bool stopping = state_now_ == MachineState::Stopping;
  if (!stopping && streaming && !starving_ && fill < braking_reserve(k_)) {
    starving_ = true;
    port_.starvations.fetch_add(1, std::memory_order_relaxed);
    log(RtLogCode::StarveBegin, static_cast<std::int64_t>(fill), -1, line_);
  } else if (starving_ && (!streaming || fill >= refill_level())) {
    starving_ = false;
    log(RtLogCode::StarveEnd, static_cast<std::int64_t>(fill), -1, line_);
  }
  // held → none (zero increments, laser off, not an underrun); else one
  // PeriodIncrement; empty while the job runs → underrun: hold position
  m.held = ramp_.holds(k_);
  if (m.held) {
    port_.held_periods.fetch_add(1, std::memory_order_relaxed);
    // at rest on the path while stopping: discard the rest of the job
    transition(KernelEvent::AtRest);
  } else if (buffer_.try_pop(m.inc)) {
    port_.motion_periods.fetch_add(1, std::memory_order_relaxed);
    port_.segment.store(m.inc.segment, std::memory_order_relaxed);
    port_.line.store(m.inc.line, std::memory_order_relaxed);
    line_ = m.inc.line;
    job_end_pending_ = m.inc.end_of_program;
    take_entry_holds(m.inc);
  } else {
    m.underrun = true;
    port_.underruns.fetch_add(1, std::memory_order_relaxed);
  }
  // this period's length: T/K; T while held, and for a dwell, whose time is
  // a process parameter (a pierce) that the override must not change
  m.nominal = m.held || (!m.underrun && m.inc.kind == MotionKind::Dwell);
  // state changes worth a log line
  if (m.underrun && underrun_since_ == 0) {
    underrun_since_ = period_ + 1;
    log(RtLogCode::UnderrunBegin, static_cast<std::int64_t>(period_));
  } else if (!m.underrun && !m.held && underrun_since_ != 0) {
    log(RtLogCode::UnderrunEnd, static_cast<std::int64_t>(period_ + 1 - underrun_since_));
    underrun_since_ = 0;
  }
  if (m.held != was_held_) log(m.held ? RtLogCode::HoldBegin : RtLogCode::HoldEnd, 0);
  was_held_ = m.held;
}

void RtKernel::take_entry_holds(const PeriodIncrement& inc) noexcept {
  // M0/M1/M60: the job is at rest here (a dwell's entry): held until a resume
  if (inc.pause && transition(KernelEvent::ProgramPause)) log(RtLogCode::ProgramPause, 0, -1, line_);
  // M66: the same hold, until the input does as asked or the time is up
  // (armed before the transition: the status that shows the hold names
  // the input)
  if (inc.wait_input >= 0 && takes(KernelEvent::InputWait)) {
    wait_.arm(inc.wait_input, inc.wait_mode, static_cast<double>(inc.wait_timeout_s), period_ns_,
              inputs_.digital_in);
    transition(KernelEvent::InputWait);
    log(RtLogCode::InputWait, wait_.input(), wait_.mode(), line_);
  }
}

void RtKernel::axis_motion(Motion& m) noexcept {
  const int a = mover_.axis();
  if (a < 0) return;
  const AxisMover::Step step = mover_.next(inputs_, pos_steps_[a]);
  m.inc.steps[a] = step.steps;
  switch (step.event) {
    case AxisMover::Event::None: break;
    case AxisMover::Event::SearchFailed: set_fault(ErrorCode::RtHoming, a, 0); break;
    case AxisMover::Event::Homed:
      pos_steps_[a] = step.rebased;
      port_.pos_pub[a].store(pos_steps_[a], std::memory_order_relaxed);
      comp_now_[a] = comp_[a].correction_steps(pos_steps_[a]);  // a coordinate, not a move
      port_.homed.fetch_or(1u << a, std::memory_order_relaxed);
      log(RtLogCode::Homed, mover_.limits(a).home_steps, a);
      transition(KernelEvent::MoveDone);
      break;
    case AxisMover::Event::Done: transition(KernelEvent::MoveDone); break;
  }
}

void RtKernel::flush_some() noexcept {
  // An aborted job's entries, a bounded number per period (the RT thread is
  // the buffer's only consumer). Done once the producer has stopped and the
  // buffer is empty.
  PeriodIncrement dropped;
  for (int i = 0; i < 512 && buffer_.try_pop(dropped); ++i) {
  }
  if (!port_.streaming.load(std::memory_order_acquire) && buffer_.empty()) flushing_ = false;
}

void RtKernel::guard_limits(Motion& m) noexcept {
  const std::uint32_t homed = port_.homed.load(std::memory_order_relaxed);
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int32_t s = m.inc.steps[i];
    if (s == 0) continue;
    // hard limit switch in the direction of motion: e-stop, this period
    if ((s < 0 && inputs_.limit_min[i]) || (s > 0 && inputs_.limit_max[i])) {
      enter_estop(ErrorCode::RtHardLimit, i, line_);
      m = Motion{};
      return;
    }
    if (!((homed >> i) & 1u)) continue;
    const AxisMover::AxisLimits& l = mover_.limits(i);
    const std::int64_t next = pos_steps_[i] + s;
    if (next < l.min_steps || next > l.max_steps) {
      // this entry would cross the soft limit: not executed; e-stop. (The
      // planner thread checks its increments before they are queued and
      // stops the job short of the limit along the path; this is the last
      // line of defence.)
      enter_estop(ErrorCode::RtSoftLimit, i, m.on_path ? m.inc.line : line_);
      m = Motion{};
      return;
    }
  }
}

void RtKernel::cycle(const Motion& m, double length_ns, std::int64_t end_ns) noexcept {
  // 7. pitch compensation, DDA and the pulse sink; M4 power follows the
  // actual speed, K times the planned one, up to the programmed power; off
  // unless on the path
  std::array<std::int32_t, kAxisCount> out = m.inc.steps;
  for (int i = 0; i < kAxisCount; ++i) {
    std::int64_t n = m.inc.steps[i] + owed_[i];
    if (!comp_[i].empty()) {
      const std::int64_t c = comp_[i].correction_steps(pos_steps_[i] + m.inc.steps[i]);
      n += c - comp_now_[i];
      comp_now_[i] = c;
    }
    const std::int64_t sent = std::clamp(n, -max_pulses_, max_pulses_);
    owed_[i] = n - sent;
    out[i] = static_cast<std::int32_t>(sent);
  }
  dda_.run_period(out, frame_);
  float power = m.on_path ? m.inc.power_pct : 0.0f;
  if (m.on_path && m.inc.power_cap_pct > 0.0f)
    power = std::min(m.inc.power_cap_pct, power * static_cast<float>(k_));
  if (port_.laser_inhibit.load(std::memory_order_relaxed)) power = 0.0f;
  frame_.power_pct = power;
  frame_.outputs = m.on_path ? m.inc.outputs : std::uint16_t{0};
  frame_.analog = m.on_path ? m.inc.analog : std::array<float, kAnalogOutputs>{};
  power_now_ = power;
  sink_.send(frame_);
  // 8. position, machine time, trace
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t n = frame_.axes[i].count;
    const std::int64_t pulses = frame_.axes[i].negative ? -n : n;
    const std::int64_t d = m.inc.steps[i];
    if (pulses != 0) {
      emitted_[i] += pulses;
      port_.emitted_pub[i].store(emitted_[i], std::memory_order_relaxed);
    }
    if (d == 0) continue;
    pos_steps_[i] += d;
    port_.pos_pub[i].store(pos_steps_[i], std::memory_order_relaxed);
    if (i == mover_.axis()) mover_.travelled(d);
  }
  port_.machine_time_ns.store(end_ns, std::memory_order_relaxed);
  if (power > 0.0f) {
    laser_on_exact_ns_ += length_ns;
    port_.laser_on_ns.store(std::llround(laser_on_exact_ns_), std::memory_order_relaxed);
  }
  if (trace_ != nullptr) {
    TraceRecord rec;
    rec.period = period_;
    rec.t_ns = end_ns;
    rec.pos_steps = pos_steps_;
    rec.feed_override = k_;
    rec.power_pct = power;
    rec.line = m.on_path ? m.inc.line : line_;
    rec.segment = m.inc.segment;
    rec.underrun = m.underrun;
    rec.held = m.held;
    rec.on_path = m.on_path && !m.held && !m.underrun;
    if (!trace_->try_push(rec)) port_.trace_drops.fetch_add(1, std::memory_order_relaxed);
  }
}

void RtKernel::publish_status(bool force) noexcept {
  if (!status_.due(period_, force)) return;
  shm::Status st;
  st.state = state_now_;
  st.fault = port_.fault_code.load(std::memory_order_relaxed);
  st.fault_axis = port_.fault_axis.load(std::memory_order_relaxed);
  st.line = line_;
  st.periods = period_;
  st.underruns = port_.underruns.load(std::memory_order_relaxed);
  st.starvations = port_.starvations.load(std::memory_order_relaxed);
  st.homed_mask = port_.homed.load(std::memory_order_relaxed);
  st.axes_mask = axes_mask_;
  for (int i = 0; i < kAxisCount; ++i) {
    st.pos_steps[i] = pos_steps_[i];
    st.pos[i] = static_cast<double>(pos_steps_[i]) * units_per_step_[i];
  }
  st.feed_override = k_ * k_plan_;
  st.feed_override_target = port_.override_target.load(std::memory_order_relaxed);
  st.machine_time_s = static_cast<double>(port_.machine_time_ns.load(std::memory_order_relaxed)) * 1e-9;
  st.buffer_fill = static_cast<std::uint32_t>(buffer_.size());
  st.power_pct = power_now_;
  st.outputs = frame_.outputs;
  st.program_pause = port_.program_pause.load(std::memory_order_relaxed);
  st.input_wait = wait_.active() ? wait_.input() : std::int8_t{-1};
  status_.publish(st, latency_, period_, force);
}

}  // namespace lcnc::rt
