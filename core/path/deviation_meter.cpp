#include "path/deviation_meter.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcnc {

bool DeviationMeter::load_next() {
  Segment seg;
  if (source_done_ || source_(seg) != SourceStatus::Item) {
    source_done_ = true;
    return false;
  }
  const double tol = seg.path_mode != PathMode::Blend ? 0.0
                     : seg.blend_tolerance_mm > 0.0   ? seg.blend_tolerance_mm
                                                      : default_tolerance_mm_;
  window_.push_back(Entry{loaded_++, SegmentGeometry(seg), tol, seg.line});
  return true;
}

double DeviationMeter::add_at_line(const Vec3& point, std::uint32_t line) {
  while (window_.empty() || window_.back().line <= line) {
    if (!load_next()) break;
  }
  std::uint32_t index = 0;
  for (auto e = window_.rbegin(); e != window_.rend(); ++e) {
    if (e->line <= line) {
      index = e->index;
      break;
    }
  }
  return add(point, index);
}

double DeviationMeter::add(const Vec3& point, std::uint32_t index) {
  const std::uint64_t want = static_cast<std::uint64_t>(index) + kWindowAhead + 1;
  while (loaded_ < want) {
    if (!load_next()) break;
  }
  const std::uint32_t low = index > kWindowBack ? index - kWindowBack : 0;
  while (!window_.empty() && window_.front().index < low) window_.pop_front();
  // the point's own segment first: the others need only be searched
  // where they could be nearer (SegmentGeometry::distance_xyz's bound)
  double best = std::numeric_limits<double>::infinity();
  for (const Entry& e : window_) {
    if (e.index == index) {
      best = e.geo.distance_xyz(point);
      break;
    }
  }
  double tol = 0.0;
  std::uint32_t line = 0;
  for (const Entry& e : window_) {
    if (e.index > index + kWindowAhead) break;
    best = std::min(best, e.geo.distance_xyz(point, best));
    tol = std::max(tol, e.tolerance_mm);
    if (e.index <= index) line = e.line;
  }
  if (!std::isfinite(best)) best = 0.0;  // no programmed segment: nothing to compare
  const double allowed = std::max(tol, rounding_mm_) + extra_mm_ + kDeviationSlackMm;
  if (best - allowed > excess_) {
    excess_ = best - allowed;
    excess_tolerance_ = allowed;
    excess_line_ = line;
  }
  max_ = std::max(max_, best);
  ++points_;
  return best;
}

std::optional<Vec3> DeviationMeter::end_of(std::uint32_t index) const {
  for (const Entry& e : window_)
    if (e.index == index) return e.geo.at(e.geo.length()).head<3>();
  return std::nullopt;
}

}  // namespace lcnc
