#include "app/rt_text.h"

#include <algorithm>
#include <cstdio>

#include "rt/rt_log.h"

namespace lcnc::app {

std::string describe_fault(const rt::RtFault& f, const MachineConfig& machine) {
  std::string text(error_summary(f.code));
  if (f.axis >= 0 && f.axis < kAxisCount) {
    const AxisConfig& ax = machine.axes[f.axis];
    text += std::string(": axis ") + kAxisLetters[f.axis];
    char range[96];
    std::snprintf(range, sizeof range, " (travel %g … %g)", ax.min, ax.max);
    if (f.code == ErrorCode::RtSoftLimit || f.code == ErrorCode::RtHardLimit) text += range;
  }
  if (f.line > 0) text += " at line " + std::to_string(f.line);
  return text;
}

RtLogLine describe_rt_log(const rt::RtLogRecord& r, const MachineConfig& machine) {
  RtLogLine out;
  out.text = rt::rt_log_text(r.code);
  const std::string axis =
      r.axis >= 0 && r.axis < kAxisCount ? std::string(": axis ") + kAxisLetters[r.axis] : std::string();
  switch (r.code) {
    case rt::RtLogCode::UnderrunBegin:
      out.code = static_cast<std::uint16_t>(ErrorCode::RtUnderrun);
      out.warning = true;
      break;
    case rt::RtLogCode::UnderrunEnd:
      out.text += " after " + std::to_string(r.value) + " periods";
      out.warning = true;
      break;
    case rt::RtLogCode::HoldBegin:
    case rt::RtLogCode::HoldEnd:
    case rt::RtLogCode::StarveBegin:
    case rt::RtLogCode::StarveEnd: out.warning = true; break;
    case rt::RtLogCode::LateWakeup: {
      char ms[64];
      std::snprintf(ms, sizeof ms, " by %.3f ms", static_cast<double>(r.value) * 1e-6);
      out.text += ms;
      out.warning = true;
      break;
    }
    case rt::RtLogCode::StateChange:
      out.text = std::string("state: ") + state_name(static_cast<rt::MachineState>(r.value));
      break;
    case rt::RtLogCode::Fault: {
      rt::RtFault f;
      f.code = static_cast<ErrorCode>(r.value);
      f.axis = r.axis;
      f.line = r.line;
      f.active = true;
      out.code = static_cast<std::uint16_t>(r.value);
      out.text = "fault: " + describe_fault(f, machine);
      out.warning = true;
      break;
    }
    case rt::RtLogCode::JogShort: out.text += axis + " (" + std::to_string(r.value) + " steps short)"; break;
    case rt::RtLogCode::Homed: out.text += axis; break;
    case rt::RtLogCode::ProgramPause: out.text += " at line " + std::to_string(r.line); break;
    case rt::RtLogCode::InputWait: {
      static constexpr const char* kMode[] = {"", "to rise", "to fall", "high", "low"};
      out.text += " P" + std::to_string(r.value) + " " + kMode[std::clamp<int>(r.axis, 0, 4)] + " at line " +
                  std::to_string(r.line);
      break;
    }
    case rt::RtLogCode::InputWaitEnd:
      out.text += " (line " + std::to_string(r.line) + ", after " + std::to_string(r.value) + " periods)";
      break;
    case rt::RtLogCode::Refused:
      out.text += std::string(": ") + rt_command_name(static_cast<rt::RtCommandType>(r.value)) + axis;
      out.code = static_cast<std::uint16_t>(ErrorCode::RtRefused);
      out.warning = true;
      break;
  }
  return out;
}

const char* state_name(rt::MachineState s) {
  switch (s) {
    case rt::MachineState::Idle: return "idle";
    case rt::MachineState::Running: return "running";
    case rt::MachineState::FeedHold: return "feed hold";
    case rt::MachineState::Stopping: return "stopping";
    case rt::MachineState::EStop: return "e-stop";
    case rt::MachineState::Jog: return "jog";
    case rt::MachineState::Homing: return "homing";
  }
  return "?";
}

const char* rt_command_name(rt::RtCommandType t) {
  switch (t) {
    case rt::RtCommandType::StartJob: return "start";
    case rt::RtCommandType::Hold: return "hold";
    case rt::RtCommandType::Resume: return "resume";
    case rt::RtCommandType::Stop: return "stop";
    case rt::RtCommandType::EStop: return "e-stop";
    case rt::RtCommandType::Reset: return "reset";
    case rt::RtCommandType::Jog: return "jog";
    case rt::RtCommandType::Home: return "home";
  }
  return "?";
}

}  // namespace lcnc::app
