#include "plan/ramp_room.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcnc {

RampRoomMeter::RampRoomMeter(const MachineConfig& machine, const Pose& start)
    : inv_period_(1.0 / machine.period_s()), p1_(start), p2_(start) {
  for (int i = 0; i < kAxisCount; ++i) {
    present_[i] = machine.axes[i].present;
    amax_[i] = machine.axes[i].max_acceleration;
  }
}

RampRoom RampRoomMeter::next(const Pose& pose) noexcept {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Below this speed (units/s) an axis is at rest: the ramp's share v·dK/dt
  // is nothing there (a tenth of a micrometre per second).
  constexpr double kRest = 1e-4;
  double r0 = kInf, down = 0.0, up = 0.0;
  for (int i = 0; i < kAxisCount; ++i) {
    if (!present_[i]) continue;
    const double v_before = (p1_[i] - p2_[i]) * inv_period_;
    const double v_now = (pose[i] - p1_[i]) * inv_period_;
    const double a = (v_now - v_before) * inv_period_;
    const double v = std::max(std::abs(v_before), std::abs(v_now));
    if (v < kRest) continue;
    r0 = std::min(r0, amax_[i] / v);
    const double r = std::abs(a) / amax_[i];  // the share of its acceleration the plan uses
    // a reversal (v changes sign) counts both ways
    if (a * v_before < 0.0 || a * v_now < 0.0) down = std::max(down, r);
    if (a * v_before > 0.0 || a * v_now > 0.0) up = std::max(up, r);
  }
  p2_ = p1_;
  p1_ = pose;
  RampRoom room;
  room.r0 = static_cast<float>(r0);
  // rounded up: the bound r0 − K²·r1 must not come out larger than exact
  room.down = std::nextafter(static_cast<float>(down), std::numeric_limits<float>::infinity());
  room.up = std::nextafter(static_cast<float>(up), std::numeric_limits<float>::infinity());
  if (static_cast<double>(room.r0) > r0)
    room.r0 = std::nextafter(room.r0, 0.0f);
  return room;
}

}  // namespace lcnc
