#include "path/travel_check.h"

#include <cmath>
#include <cstdio>

#include "path/segment_geometry.h"

namespace lcnc {

TravelCheck::TravelCheck(const MachineConfig& machine, std::string file, std::string what)
    : machine_(machine), file_(std::move(file)), what_(std::move(what)) {}

Status TravelCheck::reach(const Pose& p, std::uint32_t line) {
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& ax = machine_.axes[i];
    if (!ax.present) {
      if (std::abs(p[i]) > 1e-9)
        return make_error(ErrorCode::GcodeNoSuchAxis,
                          what_ + " " + std::to_string(line) + " needs axis " + kAxisLetters[i] +
                              ", which the machine lacks",
                          file_, line);
      continue;
    }
    if (!ax.wrap && (p[i] < ax.min - 1e-9 || p[i] > ax.max + 1e-9)) {
      char msg[200];
      std::snprintf(msg, sizeof msg, "%s %u: axis %c would reach %.4f, outside its travel %g … %g",
                    what_.c_str(), line, kAxisLetters[i], p[i], ax.min, ax.max);
      return make_error(ErrorCode::GcodeBeyondTravel, msg, file_, line);
    }
  }
  sum_.min = first_ ? p : Pose(sum_.min.cwiseMin(p));
  sum_.max = first_ ? p : Pose(sum_.max.cwiseMax(p));
  first_ = false;
  return {};
}

Status TravelCheck::add(const Segment& s) {
  ++sum_.segments;
  if (Status st = reach(s.start, s.line); !st) return st;
  if (s.kind == MotionKind::Dwell) return {};
  const SegmentGeometry geo(s);
  const double len = geo.length();
  sum_.path_length_mm += len;
  if (s.kind != MotionKind::Rapid) sum_.feed_length_mm += len;
  if (s.kind == MotionKind::Arc) {
    const int n = 64 * static_cast<int>(1 + s.extra_turns);
    for (int k = 1; k < n; ++k)
      if (Status st = reach(geo.at(len * k / n), s.line); !st) return st;
  }
  return reach(s.end, s.line);
}

}  // namespace lcnc
