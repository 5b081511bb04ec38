// A machine built in code for planner tests (no TOML involved).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>

#include "machine/machine_config.h"

namespace lcnc::testing {

// Step positions with X at x and every other axis at 0.
inline std::array<std::int64_t, kAxisCount> at_x(std::int64_t x) {
  std::array<std::int64_t, kAxisCount> s{};
  s[0] = x;
  return s;
}

inline MachineConfig test_machine(double vmax = 500.0, double amax = 5000.0) {
  MachineConfig m;
  m.period_ns = 75'000;
  m.dda = DdaConfig{8, 300};
  const double travel[3] = {1000.0, 450.0, 500.0};
  for (int i = 0; i < 3; ++i) {
    AxisConfig& a = m.axes[i];
    a.present = true;
    a.axis = static_cast<Axis>(i);
    a.min = 0.0;
    a.max = travel[i];
    a.max_velocity = vmax;
    a.max_acceleration = amax;
    a.steps_per_unit = 1000.0;
  }
  AxisConfig& c = m.axis(Axis::C);
  c.present = true;
  c.axis = Axis::C;
  c.min = 0.0;
  c.max = 360.0;
  c.wrap = true;
  c.max_velocity = 360.0;
  c.max_acceleration = 3600.0;
  c.steps_per_unit = 1000.0;
  return m;
}

// The shipped default machine (share/machines/default.toml), with
// tool-centre-point control on or off.
inline MachineConfig shipped_machine(bool tcp) {
  Result<MachineConfig> m =
      load_machine_config(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
  EXPECT_TRUE(static_cast<bool>(m)) << m.error().to_string();
  MachineConfig out = *m;
  out.tcp.enabled = tcp;
  return out;
}

}  // namespace lcnc::testing
