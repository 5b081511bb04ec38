#include "rt/shm_command.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "geom/pose.h"
#include "machine/feed_override_percent.h"

namespace lcnc::shm {
namespace {

Diagnostic refused(const std::string& why) { return make_error(ErrorCode::RtRefused, why); }

std::string axis_text(std::uint8_t axis) {
  return axis < kAxisCount ? std::string(1, kAxisLetters[axis]) : std::to_string(axis);
}

bool has_axis(std::uint8_t axis, std::uint32_t mask) { return axis < kAxisCount && ((mask >> axis) & 1u); }

}  // namespace

lcnc::Status check_command_frame(const Command& c, const CommandLimits& limits) {
  if (static_cast<std::uint8_t>(c.type) >= static_cast<std::uint8_t>(CommandType::Count))
    return refused("bad command frame: type " + std::to_string(static_cast<int>(c.type)) + " unknown");
  switch (c.type) {
    case CommandType::Load:
      if (std::memchr(c.text, '\0', sizeof c.text) == nullptr)
        return refused("bad command frame: load path not terminated");
      return {};
    case CommandType::Mdi:
      if (std::memchr(c.text, '\0', sizeof c.text) == nullptr)
        return refused("bad command frame: MDI text not terminated");
      for (const char ch : std::string_view(c.text))
        if ((static_cast<unsigned char>(ch) < 0x20 && ch != '\t') || ch == 0x7f)
          return refused("mdi refused: one line of G-code, without control characters");
      return {};
    case CommandType::Start:
      if (!std::isfinite(c.value) || c.value < 0.0 || c.value > 4e9 || c.value != std::floor(c.value))
        return refused("start refused: the start line is not a line number");
      if ((c.axis & ~kStartFlags) != 0) return refused("bad command frame: unknown start flags");
      return {};
    case CommandType::Override:
      if (const Result<double> e = check_override(c.value, kMinLiveOverridePct, limits.max_override,
                                                  ErrorCode::RtRefused, "override");
          !e)
        return e.error();
      return {};
    case CommandType::Jog:
      if (!has_axis(c.axis, limits.axes_mask)) return refused("jog refused: no axis " + axis_text(c.axis));
      if (!std::isfinite(c.value) || std::abs(c.value) > limits.max_jog)
        return refused("jog refused: distance not a number or out of range");
      return {};
    case CommandType::Home:
      if (!has_axis(c.axis, limits.axes_mask)) return refused("home refused: no axis " + axis_text(c.axis));
      return {};
    default: return {};
  }
}

}  // namespace lcnc::shm
