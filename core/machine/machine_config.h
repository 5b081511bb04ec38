// The machine: axes with travel and limits, RT period, DDA preset, laser and
// work offsets. Loaded from TOML (share/machines/default.toml) and validated
// on load; every error names the key, the value and the allowed range.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "common/result.h"
#include "geom/pose.h"

namespace lcnc {

struct AxisConfig {
  bool present = false;
  Axis axis = Axis::X;
  double min = 0.0;               // mm or deg (machine coordinates)
  double max = 0.0;               // mm or deg
  double max_velocity = 0.0;      // mm/s or deg/s
  double max_acceleration = 0.0;  // mm/s² or deg/s²
  double steps_per_unit = 1000.0; // steps per mm or per degree
  bool wrap = false;              // rotary, continuous: position kept in [min, max)
};

// DDA fine interpolation preset (DESIGN §5.4). The period is capacity ticks of
// the DDA clock, so clock_hz = capacity / period.
struct DdaConfig {
  std::uint32_t magnitude_bits = 4;  // pulses per period: 0 .. 2^bits - 1
  std::uint32_t capacity = 30;       // N: clock ticks per period

  [[nodiscard]] std::uint32_t max_pulses() const noexcept {
    return (1u << magnitude_bits) - 1u;
  }
};

struct LaserConfig {
  double s_max = 100.0;  // S word value meaning 100 % power
};

inline constexpr int kWorkOffsetCount = 6;  // G54 .. G59

struct MachineConfig {
  std::string name = "default";
  std::uint32_t period_ns = 75'000;
  double path_tolerance_mm = 0.01;  // default G64 P when P is not given
  // Highest feed override K (DESIGN §5.5). Override scales the RT period to
  // T/K, so speed scales by K and acceleration by K²: the planner plans for
  // v ≤ vmax/K_max and a ≤ amax/K_max² so that any K ≤ K_max stays within the
  // axis limits.
  double max_feed_override = 1.0;
  DdaConfig dda{};
  LaserConfig laser{};
  std::array<AxisConfig, kAxisCount> axes{};
  std::array<Pose, kWorkOffsetCount> work_offsets{};  // G54..G59, machine coords of work zero

  [[nodiscard]] const AxisConfig& axis(Axis a) const { return axes[index(a)]; }
  [[nodiscard]] AxisConfig& axis(Axis a) { return axes[index(a)]; }
  [[nodiscard]] double period_s() const noexcept { return period_ns * 1e-9; }
  [[nodiscard]] double dda_clock_hz() const noexcept { return dda.capacity / period_s(); }
};

// Validates the whole config (ranges and consistency, e.g. that an axis at its
// max velocity needs no more pulses per period than the DDA preset gives).
[[nodiscard]] Status validate(const MachineConfig& config, const std::string& file = {});

// Loads and validates a TOML machine config.
[[nodiscard]] Result<MachineConfig> load_machine_config(const std::string& path);
[[nodiscard]] Result<MachineConfig> parse_machine_config(std::string_view toml_text,
                                                         const std::string& source_name);

}  // namespace lcnc
