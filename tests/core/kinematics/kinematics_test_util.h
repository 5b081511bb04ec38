// Helpers the kinematics tests share.
#pragma once

#include <cmath>

#include "geom/pose.h"

namespace lcnc::testing {

// The joints X Y Z A C (B = 0).
inline Pose joints(double x, double y, double z, double a, double c) {
  Pose p = Pose::Zero();
  p << x, y, z, a, 0.0, c;
  return p;
}

// C of the end that makes the great circle from (30°, 0°) pass the pole at
// δ: tan δ = tan 30° · sin(Δ/2) with Δ = 180° − ΔC.
inline double end_c_for_pole_distance(double delta_deg) {
  return 180.0 - 2.0 * std::asin(std::tan(delta_deg * kRadPerDeg) / std::tan(30.0 * kRadPerDeg)) / kRadPerDeg;
}

}  // namespace lcnc::testing
