// Contour deviation of an executed path from the programmed one: for each
// executed point, the distance (X Y Z, mm) to the nearest programmed segment
// around the one the point was executed for. The programmed segments come
// from an independent reading of the program (a SegmentSource), so the
// measurement checks the output against the input it was made from.
#pragma once

#include <cstdint>
#include <deque>

#include "path/segment_geometry.h"
#include "plan/planned_segment.h"

namespace lcnc {

class DeviationMeter {
 public:
  // Points are compared with segments index−kWindowBack … index+kWindowAhead.
  // The planner merges up to 16 program lines into one (G64 Q) and a blend
  // arc, indexed by the run after its corner, may reach half-way back into
  // the run before it: 16 + 16 + 2 covers both.
  static constexpr std::uint32_t kWindowBack = 34;
  static constexpr std::uint32_t kWindowAhead = 1;

  explicit DeviationMeter(SegmentSource source) : source_(std::move(source)) {}

  // Adds an executed point that belongs to segment `index`; returns its deviation.
  double add(const Vec3& point, std::uint32_t index);

  [[nodiscard]] double max_mm() const noexcept { return max_; }
  [[nodiscard]] std::uint64_t points() const noexcept { return points_; }

 private:
  struct Entry {
    std::uint32_t index;
    SegmentGeometry geo;
  };
  SegmentSource source_;
  std::deque<Entry> window_;
  std::uint32_t loaded_ = 0;  // segments read from the source so far
  bool source_done_ = false;
  double max_ = 0.0;
  std::uint64_t points_ = 0;
};

}  // namespace lcnc
