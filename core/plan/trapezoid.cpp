#include "plan/trapezoid.h"

#include <algorithm>
#include <cmath>

#include "plan/tolerances.h"

namespace lcnc {

void Trapezoid::set(double length, double accel, double decel, double v0, double v_target, double v1) {
  Trapezoid& p = *this;  // (the parameters bear the members' names)
  p.length = length;
  p.accel = accel;
  p.decel = decel;
  p.v0 = v0;
  p.v1 = v1;
  if (length <= plan::kMinSegmentLength || accel <= 0.0 || decel <= 0.0) {
    p.vc = p.t_acc = p.t_cruise = p.t_dec = p.s_acc = p.s_cruise = 0.0;
    return;  // nothing to move
  }
  // A move with length never takes no time: a target speed at (or below)
  // standing still crawls at kMinVelocity. Taking it as "nothing to move"
  // would drop the move while its end still counts, and the next move would
  // start from there: a jump of the whole length. (The G-code check refuses
  // such feeds; this keeps segments built in code safe too.)
  if (!(v_target > plan::kMinVelocity)) v_target = plan::kMinVelocity;
  // min(v_target, sqrt(peak²)), the root taken only when the target is out
  // of reach (sqrt(fl(v²)) = v exactly: the same result either way)
  const double peak2 = peak_sqr(length, accel, decel, v0, v1);
  p.vc = v_target * v_target <= peak2 ? v_target : std::sqrt(peak2);
  p.vc = std::max({p.vc, v0, v1});
  p.t_acc = (p.vc - v0) / accel;
  p.t_dec = (p.vc - v1) / decel;
  // (vc² − v0²)/2a = t_acc·(vc + v0)/2: the mean speed over the time
  p.s_acc = p.t_acc * (p.vc + v0) * 0.5;
  const double s_dec = p.t_dec * (p.vc + v1) * 0.5;
  p.s_cruise = std::max(0.0, length - p.s_acc - s_dec);
  p.t_cruise = p.vc > 0.0 ? p.s_cruise / p.vc : 0.0;
}

Trapezoid Trapezoid::hold(double duration_s) {
  Trapezoid p;
  p.t_cruise = std::max(0.0, duration_s);
  return p;
}

}  // namespace lcnc
