// What a job's motion adds up to, summed while it is checked before it runs
// (a program's moves, a drilling job's segments): counts, lengths and the
// boxes it reaches.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "common/error.h"
#include "geom/pose.h"

namespace lcnc {

struct MotionSummary {
  std::uint64_t segments = 0;
  std::uint32_t lines = 0;
  double path_length_mm = 0.0;  // X Y Z path length of all moves (rapids included)
  double feed_length_mm = 0.0;  // of feed moves (G1 G2 G3) only
  Pose min = Pose::Zero();      // bounding box of all positions reached
  Pose max = Pose::Zero();
  // bounding box of the feed moves (G1 G2 G3): min > max when there are none
  Pose feed_min = Pose::Constant(std::numeric_limits<double>::infinity());
  Pose feed_max = Pose::Constant(-std::numeric_limits<double>::infinity());
  std::vector<Diagnostic> warnings;
};

}  // namespace lcnc
