// Logging from the RT thread (docs/design.md §2): the RT path may not log, so it
// pushes fixed records into a lock-free ring; a normal thread drains them
// into the log (spdlog, in app/) and, in the daemon, into the shared-memory
// event ring. A full ring drops the record and counts it: the RT thread never
// waits.
#pragma once

#include <cstdint>

#include "rt/spsc_ring.h"

namespace lcnc::rt {

enum class RtLogCode : std::uint16_t {
  UnderrunBegin,  // value: periods so far
  UnderrunEnd,    // value: periods the underrun lasted
  HoldBegin,      // feed hold reached (K below K_min)
  HoldEnd,        // motion resumed
  LateWakeup,     // value: ns late (beyond kLateLogNs; once per streak of late periods)
  StateChange,    // value: the new shm::MachineState
  Fault,          // value: ErrorCode; axis and line where it applies
  StarveBegin,    // buffer below its braking reserve: decelerating along the path
  StarveEnd,      // buffer refilled: back to the operator's override
  JogShort,       // axis: a jog clamped at a soft limit; value: steps not moved
  Homed,          // axis; value: machine position given to the switch, steps
  Refused,        // value: the RtCommandType refused in this state
  ProgramPause,   // line: the M0/M1/M60 the job holds at until resumed
  InputWait,      // line: the M66 the job holds at; value: the input; axis: its mode (1 … 4)
  InputWaitEnd,   // line: the M66; value: the periods it waited
};

// Wake-ups later than this are logged one by one; all are counted.
inline constexpr std::int64_t kLateLogNs = 1'000'000;

struct RtLogRecord {
  std::uint64_t period = 0;
  RtLogCode code = RtLogCode::UnderrunBegin;
  std::int8_t axis = -1;   // axis index, −1 if none
  std::uint32_t line = 0;  // program line, 0 if none
  std::int64_t value = 0;
};

using RtLogRing = SpscRing<RtLogRecord, 1024>;

// Fixed text of a code, for the draining thread.
[[nodiscard]] constexpr const char* rt_log_text(RtLogCode code) noexcept {
  switch (code) {
    case RtLogCode::UnderrunBegin: return "position buffer underrun: holding position";
    case RtLogCode::UnderrunEnd: return "position buffer refilled: motion continues";
    case RtLogCode::HoldBegin: return "feed hold: stopped";
    case RtLogCode::HoldEnd: return "feed hold released: motion continues";
    case RtLogCode::LateWakeup: return "RT thread woke late";
    case RtLogCode::StateChange: return "machine state";
    case RtLogCode::Fault: return "fault";
    case RtLogCode::StarveBegin: return "position buffer low: decelerating along the path";
    case RtLogCode::StarveEnd: return "position buffer refilled: back to speed";
    case RtLogCode::JogShort: return "jog stopped short at the soft limit";
    case RtLogCode::Homed: return "axis homed";
    case RtLogCode::Refused: return "command refused in this state";
    case RtLogCode::ProgramPause: return "program pause (M0/M1/M60): waiting for resume";
    case RtLogCode::InputWait: return "M66: waiting for input";
    case RtLogCode::InputWaitEnd: return "M66: the input came, the job goes on";
  }
  return "unknown RT event";
}

}  // namespace lcnc::rt
