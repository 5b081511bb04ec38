// Peak per-axis velocity and acceleration of a sampled motion, from the
// commanded poses one period apart: v_k = (p_k − p_{k−1})/T,
// a_k = (v_k − v_{k−1})/T.
#pragma once

#include <array>

#include "geom/pose.h"

namespace lcnc {

class MotionStats {
 public:
  MotionStats(double period_s, const Pose& start) : period_s_(period_s), prev_(start) {}

  void add(const Pose& p) {
    const Pose v = (p - prev_) / period_s_;
    const Pose a = (v - prev_v_) / period_s_;
    for (int i = 0; i < kAxisCount; ++i) {
      peak_v_[i] = std::max(peak_v_[i], std::abs(v[i]));
      peak_a_[i] = std::max(peak_a_[i], std::abs(a[i]));
    }
    prev_ = p;
    prev_v_ = v;
  }
  // Coming to rest after the last sample counts as one more period.
  void finish() { add(prev_); }

  [[nodiscard]] const std::array<double, kAxisCount>& peak_velocity() const { return peak_v_; }
  [[nodiscard]] const std::array<double, kAxisCount>& peak_acceleration() const { return peak_a_; }

 private:
  double period_s_;
  Pose prev_;
  Pose prev_v_ = Pose::Zero();
  std::array<double, kAxisCount> peak_v_{};
  std::array<double, kAxisCount> peak_a_{};
};

}  // namespace lcnc
