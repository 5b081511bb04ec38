// Contour deviation of an executed path from the programmed one: for each
// executed point, the distance (X Y Z, mm) to the nearest programmed segment
// around the one the point was executed for. The programmed segments come
// from an independent reading of the program (a SegmentSource), so the
// measurement checks the output against the input it was made from.
//
// It also checks each point against the tolerance in effect: G64 P (the
// machine's default where P is not given) for blended segments, none for
// G61/G61.1 (exact path), never less than the rounding of a point to steps
// (half a step on each of X Y Z). A point is judged against the largest
// tolerance of the segments it is compared with: a blend between two
// segments may use either's.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include "path/segment_geometry.h"
#include "path/segment_source.h"

namespace lcnc {

class DeviationMeter {
 public:
  // Points are compared with segments index−kWindowBack … index+kWindowAhead.
  // The planner merges up to 16 program lines into one (G64 Q) and a blend
  // arc, indexed by the run after its corner, may reach half-way back into
  // the run before it: 16 + 16 + 2 covers both.
  static constexpr std::uint32_t kWindowBack = 34;
  static constexpr std::uint32_t kWindowAhead = 1;
  // Floating-point slack on the tolerance (the distance computation's own
  // rounding), far below a step.
  static constexpr double kDeviationSlackMm = 1e-9;

  // default_tolerance_mm: G64 without P (MachineConfig::path_tolerance_mm);
  // rounding_mm: the distance a point's rounding to steps may add.
  // extra_mm: added to every point's tolerance (under tool-centre-point
  // control, the tip's own tolerance on the joint lines it becomes).
  explicit DeviationMeter(SegmentSource source, double default_tolerance_mm = 0.0, double rounding_mm = 0.0,
                          double extra_mm = 0.0)
      : source_(std::move(source)),
        default_tolerance_mm_(default_tolerance_mm),
        rounding_mm_(rounding_mm),
        extra_mm_(extra_mm) {}

  // Adds an executed point that belongs to segment `index`; returns its deviation.
  double add(const Vec3& point, std::uint32_t index);
  // The same for a point known by its program line only (the tool tip under
  // tool-centre-point control, whose joint segments are not the program's):
  // compared with the last segment of that line and those around it.
  double add_at_line(const Vec3& point, std::uint32_t line);

  // Where programmed segment `index` ends (X Y Z, mm), while it is in the
  // window (the segments around the last point added); nothing otherwise.
  [[nodiscard]] std::optional<Vec3> end_of(std::uint32_t index) const;
  [[nodiscard]] double max_mm() const noexcept { return max_; }
  [[nodiscard]] std::uint64_t points() const noexcept { return points_; }
  // The worst point beyond its tolerance: by how much (mm; 0 when every
  // point kept it), the tolerance it had and the program line.
  [[nodiscard]] double excess_mm() const noexcept { return excess_; }
  [[nodiscard]] double excess_tolerance_mm() const noexcept { return excess_tolerance_; }
  [[nodiscard]] std::uint32_t excess_line() const noexcept { return excess_line_; }

 private:
  struct Entry {
    std::uint32_t index;
    SegmentGeometry geo;
    double tolerance_mm;
    std::uint32_t line;
  };
  bool load_next();  // one more segment into the window; false at the end

  SegmentSource source_;
  double default_tolerance_mm_;
  double rounding_mm_;
  double extra_mm_;
  double excess_ = 0.0, excess_tolerance_ = 0.0;
  std::uint32_t excess_line_ = 0;
  std::deque<Entry> window_;
  std::uint32_t loaded_ = 0;  // segments read from the source so far
  bool source_done_ = false;
  double max_ = 0.0;
  std::uint64_t points_ = 0;
};

}  // namespace lcnc
