#include "rt/axis_move.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace lcnc::rt {

void AxisMove::start(std::int64_t distance_steps, double vmax, double amax, double period_s) noexcept {
  dir_ = distance_steps < 0 ? -1 : 1;
  total_ = std::llabs(distance_steps);
  left_ = static_cast<double>(total_);
  v_ = 0.0;
  vmax_ = std::abs(vmax);
  amax_ = std::abs(amax);
  period_s_ = period_s;
  travelled_ = 0.0;
  emitted_ = 0;
  unbounded_ = false;
  active_ = total_ > 0 && vmax_ > 0.0 && amax_ > 0.0;
}

void AxisMove::start_velocity(double velocity, double amax, double period_s) noexcept {
  start(0, velocity, amax, period_s);
  dir_ = velocity < 0 ? -1 : 1;
  unbounded_ = true;
  active_ = vmax_ > 0.0 && amax_ > 0.0;
}

void AxisMove::stop() noexcept {
  if (!active_) return;
  // The braking distance from v at a, rounded up to whole steps from where
  // the move stands, so that it ends on a step.
  const double brake = v_ * v_ / (2.0 * amax_);
  const double end = std::ceil(travelled_ + brake);
  total_ = static_cast<std::int64_t>(end);
  left_ = end - travelled_;
  unbounded_ = false;
  if (left_ <= 0.0 && emitted_ == total_) active_ = false;
}

std::int32_t AxisMove::next() noexcept {
  if (!active_) return 0;
  const double t = period_s_;
  double v = std::min(vmax_, v_ + amax_ * t);
  if (!unbounded_) v = std::min(v, std::sqrt(2.0 * amax_ * left_));
  // Never slower than braking at a would make it (the profile's floor), and
  // at least enough to finish a last fraction of a step.
  v = std::max(v, v_ - amax_ * t);
  double ds = v * t;
  if (!unbounded_ && ds >= left_) {
    ds = left_;
    v = 0.0;
    active_ = false;
  }
  v_ = v;
  left_ -= ds;
  travelled_ += ds;
  const std::int64_t whole = active_ ? static_cast<std::int64_t>(std::floor(travelled_ + 0.5)) : total_;
  const auto out = static_cast<std::int32_t>(whole - emitted_);
  emitted_ = whole;
  return dir_ * out;
}

}  // namespace lcnc::rt
