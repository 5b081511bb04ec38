// Programs built in code for the planner's tests: a source over a vector of
// segments, and random lines and arcs meeting at corners.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <random>
#include <vector>

#include "path/segment.h"
#include "path/segment_source.h"

namespace lcnc::testing {

// The segments of `segs` one at a time, from index i (advanced as read).
inline SegmentSource from(const std::vector<Segment>& segs, std::size_t& i) {
  return [&segs, &i](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  };
}

// n moves in XY from `at`, each 0.2–5.2 mm in a random direction at 30–180
// mm/s, made by line(from, to, feed); every second one turned into an arc
// through the same end points (radius 1.05–4.05 × half its chord, on
// either side, either way round).
inline std::vector<Segment> random_lines_and_arcs(
    std::mt19937_64& rng, Pose at, int n,
    const std::function<Segment(const Pose&, const Pose&, double)>& line) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Segment> segs;
  for (int k = 0; k < n; ++k) {
    const double len = 0.2 + 5.0 * u(rng);
    const double ang = 2 * 3.14159265 * u(rng);
    Pose to = at;
    to[0] += len * std::cos(ang);
    to[1] += len * std::sin(ang);
    Segment s = line(at, to, 30 + 150 * u(rng));
    if (k % 2 == 1) {
      const Vec3 a = at.head<3>(), b = to.head<3>(), mid = 0.5 * (a + b);
      const double r = 0.5 * len * (1.05 + 3 * u(rng));
      const Vec3 nrm = Vec3(-(b - a).y(), (b - a).x(), 0).normalized();
      const double h = std::sqrt(r * r - 0.25 * len * len) * (u(rng) < 0.5 ? 1 : -1);
      s.kind = MotionKind::Arc;
      s.plane = Plane::XY;
      s.center = mid + h * nrm;
      s.clockwise = u(rng) < 0.5;
    }
    segs.push_back(s);
    at = to;
  }
  return segs;
}

}  // namespace lcnc::testing
