// The RT kernel's modes: which events each takes and what a transition
// does (the table atop rt/rt_kernel.h). On the RT thread only.
#include "rt/rt_kernel.h"

namespace lcnc::rt {

bool RtKernel::takes(KernelEvent e) const noexcept {
  const MachineState s = state_now_;
  switch (e) {
    case KernelEvent::Start:
    case KernelEvent::Jog:
    case KernelEvent::Home: return s == MachineState::Idle && !flushing_;
    case KernelEvent::Hold: return s == MachineState::Running;
    case KernelEvent::ProgramPause:
    case KernelEvent::InputWait: return s == MachineState::Running || s == MachineState::FeedHold;
    case KernelEvent::Resume:
      return s == MachineState::FeedHold &&
             (hold_cause_ == HoldCause::Operator || hold_cause_ == HoldCause::ProgramPause);
    case KernelEvent::InputCame: return s == MachineState::FeedHold && hold_cause_ == HoldCause::InputWait;
    case KernelEvent::PauseUp: return s == MachineState::FeedHold && hold_cause_ == HoldCause::ProgramPause;
    case KernelEvent::Stop: return on_path_state() || s == MachineState::Jog || s == MachineState::Homing;
    case KernelEvent::AtRest: return s == MachineState::Stopping;
    case KernelEvent::JobEnd: return on_path_state();
    case KernelEvent::MoveDone: return s == MachineState::Jog || s == MachineState::Homing;
    case KernelEvent::EStop: return true;
    case KernelEvent::Reset: return s == MachineState::EStop && !flushing_;
  }
  return false;
}

bool RtKernel::transition(KernelEvent e) noexcept {
  if (!takes(e)) return false;
  switch (e) {
    case KernelEvent::Start:
      port_.fault_code.store(0, std::memory_order_release);
      starving_ = job_aborted_ = job_end_pending_ = false;
      // a job starts at rest: at the operator's override, no ramp
      begin_at_override();
      enter(MachineState::Running);
      break;
    case KernelEvent::Jog: enter(MachineState::Jog); break;
    case KernelEvent::Home: enter(MachineState::Homing); break;
    case KernelEvent::Hold: enter(MachineState::FeedHold, HoldCause::Operator); break;
    case KernelEvent::ProgramPause:
      // the job is at rest here (a dwell's entry): K to 0 at once, not
      // ramped, so the next entry's motion never starts; the flags before
      // the state, so the status that shows the hold says why
      k_ = 0.0;
      pause_left_ = options_.program_pause_periods;
      port_.program_pause.store(true, std::memory_order_relaxed);
      port_.program_pauses.fetch_add(1, std::memory_order_relaxed);
      enter(MachineState::FeedHold, HoldCause::ProgramPause);
      break;
    case KernelEvent::InputWait:  // armed by the caller (take_entry_holds) before
      k_ = 0.0;
      enter(MachineState::FeedHold, HoldCause::InputWait);
      break;
    case KernelEvent::Resume:
    case KernelEvent::InputCame:
    case KernelEvent::PauseUp: enter(MachineState::Running); break;
    case KernelEvent::Stop:
      if (on_path_state()) {
        enter(MachineState::Stopping);
      } else {
        mover_.stop();
      }
      break;
    case KernelEvent::AtRest:
      job_ended(false);
      enter(MachineState::Idle);
      break;
    case KernelEvent::JobEnd:
      job_ended(true);
      enter(MachineState::Idle);
      break;
    case KernelEvent::MoveDone: enter(MachineState::Idle); break;
    case KernelEvent::EStop:
      // The job's remaining entries are discarded; nothing moves from this
      // period on.
      if (on_path_state()) job_ended(false);
      starving_ = false;
      mover_.cancel();
      reset_pending_ = false;
      enter(MachineState::EStop);
      break;
    case KernelEvent::Reset:
      port_.fault_code.store(0, std::memory_order_release);
      enter(MachineState::Idle);
      break;
  }
  return true;
}

void RtKernel::enter(MachineState s, HoldCause cause) noexcept {
  if (s == MachineState::FeedHold) hold_cause_ = cause;  // before the status below
  if (s == state_now_) return;
  if (state_now_ == MachineState::FeedHold) {  // resumed, stopped or e-stopped
    hold_cause_ = HoldCause::None;
    wait_.cancel();  // an M66 ended: the input, a stop
    port_.program_pause.store(false, std::memory_order_relaxed);
  }
  state_now_ = s;
  port_.state.store(s, std::memory_order_release);
  log(RtLogCode::StateChange, static_cast<std::int64_t>(s));
  publish_status(true);
}

void RtKernel::job_ended(bool completed) noexcept {
  if (!completed) {
    flushing_ = true;
    job_aborted_ = true;
  }
  job_end_pending_ = false;
  port_.last_job_completed.store(completed, std::memory_order_relaxed);
  // release: the flag above is seen with the count
  port_.jobs_ended.fetch_add(1, std::memory_order_release);
}

void RtKernel::set_fault(ErrorCode code, int axis, std::uint32_t line) noexcept {
  // the first fault stands until Reset or StartJob
  if (port_.fault_code.load(std::memory_order_relaxed) != 0) return;
  port_.fault_axis.store(static_cast<std::int8_t>(axis), std::memory_order_relaxed);
  port_.fault_line.store(line, std::memory_order_relaxed);
  port_.fault_code.store(static_cast<std::uint16_t>(code), std::memory_order_release);
  log(RtLogCode::Fault, static_cast<std::int64_t>(code), axis, line);
}

void RtKernel::enter_estop(ErrorCode code, int axis, std::uint32_t line) noexcept {
  set_fault(code, axis, line);
  transition(KernelEvent::EStop);
}

void RtKernel::begin_stop(ErrorCode code, int axis, std::uint32_t line) noexcept {
  if (code != ErrorCode::Ok) set_fault(code, axis, line);
  transition(KernelEvent::Stop);
}

}  // namespace lcnc::rt
