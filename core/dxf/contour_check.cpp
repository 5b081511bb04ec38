#include "dxf/contour_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>

#include "common/error.h"
#include "dxf/contour_chain.h"
#include "geom/plane.h"

namespace lcnc::dxf {
namespace {

struct ChordRef {
  std::uint32_t poly;
  std::uint32_t j;  // chord pts[j] → pts[j + 1 mod n]
};

using geom::cross;

// Lexicographic order of points, the order the sweep meets them in.
bool before(const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); }

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
  auto on = [](const Vec2& a, const Vec2& b, const Vec2& x) { return (x - a).dot(x - b) <= 0.0; };
  if (s1 == 0 && on(p0, p1, q0)) return q0;
  if (s2 == 0 && on(p0, p1, q1)) return q1;
  if (s3 == 0 && on(q0, q1, p0)) return p0;
  if (s4 == 0 && on(q0, q1, p1)) return p1;
  return std::nullopt;
}

// A chord as the sweep sees it: its left and right end (lexicographic).
struct Segment {
  Vec2 l, r;
  ChordRef ref;
};

// The sweep line stands at the event point `at` (tilted by an infinitesimal
// angle, so a vertical chord is crossed from its lower end up). Chords in the
// status are ordered by their height at the sweep; chords through one point
// by their direction beyond it.
struct SweepOrder {
  const std::vector<Segment>* segs;
  const Vec2* at;

  double height(const Segment& s) const {
    if (s.l.x() == s.r.x()) return std::clamp(at->y(), s.l.y(), s.r.y());
    if (at->x() <= s.l.x()) return s.l.y();
    if (at->x() >= s.r.x()) return s.r.y();
    return s.l.y() + (s.r.y() - s.l.y()) * ((at->x() - s.l.x()) / (s.r.x() - s.l.x()));
  }
  bool operator()(std::uint32_t a, std::uint32_t b) const {
    const Segment& sa = (*segs)[a];
    const Segment& sb = (*segs)[b];
    const double ya = height(sa), yb = height(sb);
    if (ya != yb) return ya < yb;
    const double c = cross(sa.r - sa.l, sb.r - sb.l);
    if (c != 0.0) return c > 0.0;  // b turns up from a
    return a < b;
  }
};

}  // namespace

Status check_crossings(const std::vector<Contour>& contours, const std::vector<Polyline>& lines,
                       const std::string& file) {
  auto crossing = [&](const ChordRef& r, const ChordRef& s, const Vec2& at, const char* how) -> Status {
    const Polyline& lr = lines[r.poly];
    const Polyline& ls = lines[s.poly];
    const std::string who = r.poly == s.poly
                                ? contours[r.poly].name() + " " + how + " itself"
                                : contours[r.poly].name() + " " + how + " " + contours[s.poly].name();
    return make_error(ErrorCode::DxfCrossing,
                      who + " at " + format_point(at) + " (the entity at DXF line " +
                          std::to_string(lr.src_line[r.j]) + " and the one at DXF line " +
                          std::to_string(ls.src_line[s.j]) +
                          "); expected contours that neither cross nor touch",
                      file, lr.src_line[r.j]);
  };
  auto neighbours = [&](const ChordRef& r, const ChordRef& s) {
    if (r.poly != s.poly) return false;
    const std::size_t n = lines[r.poly].size();
    return r.j == s.j || (r.j + 1) % n == s.j || (s.j + 1) % n == r.j;
  };

  // 1. A chord that turns straight back onto its predecessor overlaps it.
  std::size_t total = 0;
  for (std::uint32_t p = 0; p < lines.size(); ++p) {
    const Polyline& l = lines[p];
    const std::size_t n = l.size();
    total += n;
    for (std::uint32_t j = 0; j < n && n > 1; ++j) {
      const Vec2& prev = l.pts[(j + n - 1) % n];
      const Vec2& a = l.pts[j];
      const Vec2& b = l.pts[(j + 1) % n];
      const Vec2 d0 = a - prev, d1 = b - a;
      if (std::abs(cross(d0, d1)) <= 1e-12 * (d0.squaredNorm() + d1.squaredNorm()) && d0.dot(d1) < 0.0) {
        return crossing(ChordRef{p, static_cast<std::uint32_t>((j + n - 1) % n)}, ChordRef{p, j}, a,
                        "turns back onto");
      }
    }
  }

  // 2. A point two contours share, or one contour passes twice (a figure 8
  // pinched at a vertex): they touch there.
  {
    std::vector<ChordRef> at;
    at.reserve(total);
    for (std::uint32_t p = 0; p < lines.size(); ++p)
      for (std::uint32_t j = 0; j < lines[p].size(); ++j) at.push_back(ChordRef{p, j});
    auto pt = [&](const ChordRef& r) -> const Vec2& { return lines[r.poly].pts[r.j]; };
    std::sort(at.begin(), at.end(),
              [&](const ChordRef& u, const ChordRef& v) { return before(pt(u), pt(v)); });
    for (std::size_t i = 1; i < at.size(); ++i) {
      if (pt(at[i]) == pt(at[i - 1]) && !neighbours(at[i - 1], at[i]))
        return crossing(at[i - 1], at[i], pt(at[i]), "touches");
    }
  }

  // 3. Any two chords that cross, touch or overlap: a sweep from left to
  // right (Shamos and Hoey, "Geometric intersection problems", 1976). Of all
  // chords, only those next to each other along the sweep line can meet
  // first, so each chord is tested against its neighbours there when it
  // enters, and its two neighbours against each other when it leaves:
  // O(n log n) for n chords whatever their lengths.
  std::vector<Segment> segs;
  segs.reserve(total);
  for (std::uint32_t p = 0; p < lines.size(); ++p) {
    const Polyline& l = lines[p];
    const std::size_t n = l.size();
    for (std::uint32_t j = 0; j < n && n > 1; ++j) {
      const Vec2& a = l.pts[j];
      const Vec2& b = l.pts[(j + 1) % n];
      if (a == b) continue;  // no chord: its point is a vertex, checked above
      segs.push_back(before(a, b) ? Segment{a, b, ChordRef{p, j}} : Segment{b, a, ChordRef{p, j}});
    }
  }
  // Events: a chord enters at its left end (0) and leaves at its right end
  // (1); at one point all entries come first, so chords that only touch
  // there are in the status together.
  struct Event {
    std::uint32_t seg;
    bool leaves;
  };
  std::vector<Event> events;
  events.reserve(2 * segs.size());
  for (std::uint32_t i = 0; i < segs.size(); ++i) {
    events.push_back(Event{i, false});
    events.push_back(Event{i, true});
  }
  auto where = [&](const Event& e) -> const Vec2& { return e.leaves ? segs[e.seg].r : segs[e.seg].l; };
  std::sort(events.begin(), events.end(), [&](const Event& u, const Event& v) {
    const Vec2& a = where(u);
    const Vec2& b = where(v);
    if (a != b) return before(a, b);
    if (u.leaves != v.leaves) return !u.leaves;
    return u.seg < v.seg;
  });

  Vec2 sweep_at = Vec2::Zero();
  using Status_ = std::set<std::uint32_t, SweepOrder>;
  Status_ status(SweepOrder{&segs, &sweep_at});
  std::vector<Status_::iterator> place(segs.size(), status.end());
  auto test = [&](Status_::iterator u, Status_::iterator v) -> Status {
    if (u == status.end() || v == status.end()) return {};
    const Segment& a = segs[*u];
    const Segment& b = segs[*v];
    if (neighbours(a.ref, b.ref)) return {};
    if (const std::optional<Vec2> m = meet(a.l, a.r, b.l, b.r)) {
      return crossing(a.ref, b.ref, *m, "crosses");
    }
    return {};
  };
  for (const Event& e : events) {
    sweep_at = where(e);
    if (!e.leaves) {
      const auto it = status.insert(e.seg).first;
      place[e.seg] = it;
      if (it != status.begin())
        if (Status s = test(std::prev(it), it); !s) return s;
      if (Status s = test(it, std::next(it)); !s) return s;
    } else {
      const auto it = place[e.seg];
      const auto above = std::next(it);
      if (it != status.begin())
        if (Status s = test(std::prev(it), above); !s) return s;
      status.erase(it);
    }
  }
  return {};
}

}  // namespace lcnc::dxf
