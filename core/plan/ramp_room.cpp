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
  // The room at K = 0 (min_i r_i) and at K = 1 for a falling and a rising K
  // (min_i r_i·(1 − f_i)); the chord between them is the bound (header).
  double at0 = kInf, down1 = kInf, up1 = kInf;
  for (int i = 0; i < kAxisCount; ++i) {
    if (!present_[i]) continue;
    const double v_before = (p1_[i] - p2_[i]) * inv_period_;
    const double v_now = (pose[i] - p1_[i]) * inv_period_;
    const double a = (v_now - v_before) * inv_period_;
    const double v = std::max(std::abs(v_before), std::abs(v_now));
    if (v < kRest) continue;
    const double r = amax_[i] / v;
    const double f = std::abs(a) / amax_[i];  // the share of its acceleration the plan uses
    at0 = std::min(at0, r);
    // a reversal (v changes sign) counts both ways
    const bool brakes = a * v_before < 0.0 || a * v_now < 0.0;
    const bool speeds_up = a * v_before > 0.0 || a * v_now > 0.0;
    down1 = std::min(down1, brakes ? r * (1.0 - f) : r);
    up1 = std::min(up1, speeds_up ? r * (1.0 - f) : r);
  }
  p2_ = p1_;
  p1_ = pose;
  RampRoom room;
  if (!std::isfinite(at0)) return room;  // nothing moves: no bound
  // r0 rounded down and the shares rounded up: the stored chord lies below
  // the exact one at K = 0 and K = 1, so below it everywhere.
  room.r0 = static_cast<float>(at0);
  if (static_cast<double>(room.r0) > at0) room.r0 = std::nextafter(room.r0, 0.0f);
  const double r0 = room.r0;
  const auto share = [r0](double at1) {
    const double f = std::max(0.0, 1.0 - at1 / r0);
    float g = static_cast<float>(f);
    if (static_cast<double>(g) < f) g = std::nextafter(g, std::numeric_limits<float>::infinity());
    return g;
  };
  room.down = share(down1);
  room.up = share(up1);
  return room;
}

}  // namespace lcnc
