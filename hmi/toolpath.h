// The toolpath as the controller will run it, for the program screen: the
// program checked whole, then planned by the same planner the daemon runs
// (arc blends, look-ahead, coarse interpolation: core/plan/planner.h), and
// its period samples thinned to what a screen can show — a point kept where
// the path has moved kMinStepMm, the speed changed by kSpeedStep of the
// peak, the laser switched or the tool axis turned kMinTurnDeg. Qt-free; runs on a worker thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/result.h"
#include "geom/pose.h"
#include "machine/machine_config.h"

namespace lcnc::hmi {

inline constexpr double kMinStepMm = 0.05;
inline constexpr double kSpeedStep = 0.02;
inline constexpr double kMinTurnDeg = 1.0;

struct ToolpathPoint {
  Vec3 at = Vec3::Zero();  // mm, machine
  double speed = 0.0;      // mm/s (path speed)
  bool laser = false;
  bool rapid = false;  // G0 (else a feed move, or a dwell)
  std::uint32_t line = 0;
  Vec3 axis = Vec3::UnitZ();  // the tool axis (A tilt, C rotary)
};

struct Toolpath {
  std::vector<ToolpathPoint> points;
  double time_s = 0.0;
  double peak_speed = 0.0;
  double length_mm = 0.0;
  std::uint64_t periods = 0;
  std::uint32_t lines = 0;
  bool tilted = false;  // some point's tool axis is not +Z (a 5-axis program)
};

// `progress(fraction)` now and then (any thread); `cancel` checked as it goes.
[[nodiscard]] Result<Toolpath> plan_toolpath(const std::string& program, const MachineConfig& machine,
                                             const Pose& start,
                                             const std::function<void(double)>& progress = {},
                                             const std::atomic<bool>* cancel = nullptr);

}  // namespace lcnc::hmi
