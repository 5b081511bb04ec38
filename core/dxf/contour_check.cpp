#include "dxf/contour_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "dxf/contour_chain.h"
#include "common/error.h"

namespace lcnc::dxf {
namespace {

struct ChordRef {
  std::uint32_t poly;
  std::uint32_t j;  // chord pts[j] → pts[j + 1 mod n]
};

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Where the chords p0p1 and q0q1 meet (cross, touch or overlap), if they do.
std::optional<Vec2> meet(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  if (std::max(p0.x(), p1.x()) < std::min(q0.x(), q1.x()) ||
      std::max(q0.x(), q1.x()) < std::min(p0.x(), p1.x()) ||
      std::max(p0.y(), p1.y()) < std::min(q0.y(), q1.y()) ||
      std::max(q0.y(), q1.y()) < std::min(p0.y(), p1.y())) {
    return std::nullopt;
  }
  const Vec2 dp = p1 - p0, dq = q1 - q0;
  // Orientation values below this count as zero (collinear): relative to the
  // chord lengths, far below anything a µm grid can tell apart.
  const double eps = 1e-12 * (dp.squaredNorm() + dq.squaredNorm());
  const double o1 = cross(dp, q0 - p0), o2 = cross(dp, q1 - p0);
  const double o3 = cross(dq, p0 - q0), o4 = cross(dq, p1 - q0);
  auto sgn = [eps](double v) { return v > eps ? 1 : (v < -eps ? -1 : 0); };
  const int s1 = sgn(o1), s2 = sgn(o2), s3 = sgn(o3), s4 = sgn(o4);
  if (s1 * s2 < 0 && s3 * s4 < 0) return p0 + (o3 / (o3 - o4)) * dp;
  // Touching or collinear: an end point of one chord on the other.
  auto on = [](const Vec2& a, const Vec2& b, const Vec2& x) {
    return (x - a).dot(x - b) <= 0.0;
  };
  if (s1 == 0 && on(p0, p1, q0)) return q0;
  if (s2 == 0 && on(p0, p1, q1)) return q1;
  if (s3 == 0 && on(q0, q1, p0)) return p0;
  if (s4 == 0 && on(q0, q1, p1)) return p1;
  return std::nullopt;
}

}  // namespace

Status check_crossings(const std::vector<Contour>& contours, const std::vector<Polyline>& lines,
                       const std::string& file) {
  double longest = 0.0;
  for (const Polyline& l : lines) longest = std::max(longest, l.step_mm);
  if (longest <= 0.0) return {};
  const double cell = 4.0 * longest;

  auto chord = [&](const ChordRef& r, Vec2& a, Vec2& b) {
    const Polyline& l = lines[r.poly];
    a = l.pts[r.j];
    b = l.pts[(r.j + 1) % l.size()];
  };
  auto crossing = [&](const ChordRef& r, const ChordRef& s, const Vec2& at,
                      const char* how) -> Status {
    const Polyline& lr = lines[r.poly];
    const Polyline& ls = lines[s.poly];
    const std::string who =
        r.poly == s.poly ? contours[r.poly].name() + " " + how + " itself"
                         : contours[r.poly].name() + " " + how + " " + contours[s.poly].name();
    return make_error(ErrorCode::DxfCrossing,
                      who + " at " + format_point(at) + " (the entity at DXF line " +
                          std::to_string(lr.src_line[r.j]) + " and the one at DXF line " +
                          std::to_string(ls.src_line[s.j]) +
                          "); expected contours that neither cross nor touch",
                      file, lr.src_line[r.j]);
  };

  // (cell key, chord) for every cell a chord's bounding box covers.
  std::vector<std::pair<std::uint64_t, ChordRef>> cells;
  std::size_t total = 0;
  for (const Polyline& l : lines) total += l.size();
  cells.reserve(total + total / 2);
  for (std::uint32_t p = 0; p < lines.size(); ++p) {
    const Polyline& l = lines[p];
    const std::size_t n = l.size();
    for (std::uint32_t j = 0; j < n; ++j) {
      const Vec2& a = l.pts[j];
      const Vec2& b = l.pts[(j + 1) % n];
      // A chord that turns straight back onto its predecessor overlaps it.
      const Vec2& prev = l.pts[(j + n - 1) % n];
      const Vec2 d0 = a - prev, d1 = b - a;
      if (std::abs(cross(d0, d1)) <= 1e-12 * (d0.squaredNorm() + d1.squaredNorm()) &&
          d0.dot(d1) < 0.0) {
        return crossing(ChordRef{p, static_cast<std::uint32_t>((j + n - 1) % n)}, ChordRef{p, j},
                        a, "turns back onto");
      }
      const auto x0 = static_cast<std::int64_t>(std::floor(std::min(a.x(), b.x()) / cell));
      const auto x1 = static_cast<std::int64_t>(std::floor(std::max(a.x(), b.x()) / cell));
      const auto y0 = static_cast<std::int64_t>(std::floor(std::min(a.y(), b.y()) / cell));
      const auto y1 = static_cast<std::int64_t>(std::floor(std::max(a.y(), b.y()) / cell));
      for (std::int64_t x = x0; x <= x1; ++x) {
        for (std::int64_t y = y0; y <= y1; ++y) {
          const std::uint64_t key =
              (static_cast<std::uint64_t>(x) << 32) ^ static_cast<std::uint32_t>(y);
          cells.emplace_back(key, ChordRef{p, j});
        }
      }
    }
  }
  std::sort(cells.begin(), cells.end(), [](const auto& u, const auto& v) {
    if (u.first != v.first) return u.first < v.first;
    if (u.second.poly != v.second.poly) return u.second.poly < v.second.poly;
    return u.second.j < v.second.j;
  });

  for (std::size_t lo = 0; lo < cells.size();) {
    std::size_t hi = lo + 1;
    while (hi < cells.size() && cells[hi].first == cells[lo].first) ++hi;
    for (std::size_t u = lo; u < hi; ++u) {
      const ChordRef r = cells[u].second;
      Vec2 a0, a1;
      chord(r, a0, a1);
      for (std::size_t v = u + 1; v < hi; ++v) {
        const ChordRef s = cells[v].second;
        if (r.poly == s.poly) {
          const std::size_t n = lines[r.poly].size();
          if ((r.j + 1) % n == s.j || (s.j + 1) % n == r.j) continue;  // neighbours
        }
        Vec2 b0, b1;
        chord(s, b0, b1);
        if (const std::optional<Vec2> at = meet(a0, a1, b0, b1)) {
          return crossing(r, s, *at, "crosses");
        }
      }
    }
    lo = hi;
  }
  return {};
}

}  // namespace lcnc::dxf
