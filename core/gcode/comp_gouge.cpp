#include "gcode/comp_gouge.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geom/plane.h"
#include "geom/pose.h"

namespace lcnc::gcode {
namespace {

using V = Eigen::Vector2d;
// The most chords an arc is measured by (arc to arc only).
constexpr int kMaxChords = 4096;

using geom::cross;
using geom::point_segment;

bool within_sweep(const PlanePiece& arc, double angle) {
  if (std::abs(arc.sweep) >= kTwoPi) return true;
  double rel = arc.sweep >= 0.0 ? angle - arc.start : arc.start - angle;
  rel = std::fmod(rel, kTwoPi);
  if (rel < 0.0) rel += kTwoPi;
  return rel <= std::abs(arc.sweep) + 1e-12;
}

double point_arc(const V& p, const PlanePiece& arc) {
  const V d = p - arc.c;
  const double n = d.norm();
  if (n == 0.0) return arc.radius;
  if (within_sweep(arc, std::atan2(d.y(), d.x()))) return std::abs(n - arc.radius);
  return std::min((p - arc.a).norm(), (p - arc.b).norm());
}

bool segments_meet(const V& a, const V& b, const V& c, const V& d) {
  const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);
  const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && point_segment(c, a, b) == 0.0) || (o2 == 0 && point_segment(d, a, b) == 0.0);
}

double segment_segment(const V& a, const V& b, const V& c, const V& d) {
  if (segments_meet(a, b, c, d)) return 0.0;
  return std::min(
      {point_segment(a, c, d), point_segment(b, c, d), point_segment(c, a, b), point_segment(d, a, b)});
}

// Exact: the least distance is at an end of either, where the segment
// crosses the arc, or along the radius through the segment's point nearest
// the centre (the segment outside the circle there).
double segment_arc(const V& p0, const V& p1, const PlanePiece& arc) {
  double best = std::min(
      {point_arc(p0, arc), point_arc(p1, arc), point_segment(arc.a, p0, p1), point_segment(arc.b, p0, p1)});
  const V d = p1 - p0;
  const double dd = d.squaredNorm();
  if (dd == 0.0) return best;
  const V q = p0 + std::clamp((arc.c - p0).dot(d) / dd, 0.0, 1.0) * d;
  const V qc = q - arc.c;
  if (qc.norm() >= arc.radius) {
    if (within_sweep(arc, std::atan2(qc.y(), qc.x()))) best = std::min(best, qc.norm() - arc.radius);
    return best;
  }
  const V f = p0 - arc.c;
  const double bq = 2.0 * d.dot(f), cq = f.squaredNorm() - arc.radius * arc.radius;
  const double disc = bq * bq - 4.0 * dd * cq;
  if (disc < 0.0) return best;
  for (const double t : {(-bq - std::sqrt(disc)) / (2.0 * dd), (-bq + std::sqrt(disc)) / (2.0 * dd)}) {
    if (t < 0.0 || t > 1.0) continue;
    const V x = p0 + t * d - arc.c;
    if (within_sweep(arc, std::atan2(x.y(), x.x()))) return 0.0;
  }
  return best;
}

double box_distance(const Eigen::AlignedBox2d& p, const Eigen::AlignedBox2d& q) {
  const double dx = std::max({0.0, q.min().x() - p.max().x(), p.min().x() - q.max().x()});
  const double dy = std::max({0.0, q.min().y() - p.max().y(), p.min().y() - q.max().y()});
  return std::hypot(dx, dy);
}

template <class Pieces>
std::optional<GougeWindow::Gouge> nearest_below(const PlanePiece& p, const Pieces& others,
                                                double min_distance, double chord_tol, bool p_is_cut) {
  for (const PlanePiece& o : others) {
    if (box_distance(p.box, o.box) >= min_distance) continue;
    const PlanePiece& cut = p_is_cut ? p : o;
    const PlanePiece& programmed = p_is_cut ? o : p;
    if (cut.meets(programmed)) continue;
    const double d = piece_distance(cut, programmed, chord_tol);
    if (d < min_distance) return GougeWindow::Gouge{cut, programmed, d};
  }
  return std::nullopt;
}

}  // namespace

PlanePiece PlanePiece::straight(const V& a, const V& b, std::uint32_t line) {
  PlanePiece p;
  p.a = a;
  p.b = b;
  p.line = line;
  p.box.extend(a);
  p.box.extend(b);
  return p;
}

PlanePiece PlanePiece::circular(const V& a, const V& b, const V& c, double sweep, std::uint32_t line) {
  PlanePiece p;
  p.a = a;
  p.b = b;
  p.arc = true;
  p.c = c;
  p.radius = (a - c).norm();
  p.start = std::atan2(a.y() - c.y(), a.x() - c.x());
  p.sweep = sweep;
  p.line = line;
  p.box.extend(c - V(p.radius, p.radius));
  p.box.extend(c + V(p.radius, p.radius));
  return p;
}

double piece_distance(const PlanePiece& p, const PlanePiece& q, double chord_tol) {
  if (!p.arc && !q.arc) return segment_segment(p.a, p.b, q.a, q.b);
  if (!p.arc) return segment_arc(p.a, p.b, q);
  if (!q.arc) return segment_arc(q.a, q.b, p);
  // arc to arc: p as chords no farther than chord_tol inside it
  const double step = p.radius > chord_tol ? 2.0 * std::acos(1.0 - chord_tol / p.radius) : kTwoPi;
  const int n = std::clamp(static_cast<int>(std::ceil(std::abs(p.sweep) / step)), 1, kMaxChords);
  double best = 1e300;
  V from = p.a;
  for (int k = 1; k <= n; ++k) {
    const double t = p.start + p.sweep * static_cast<double>(k) / n;
    const V to = k == n ? p.b : V(p.c + p.radius * V(std::cos(t), std::sin(t)));
    best = std::min(best, segment_arc(from, to, q));
    from = to;
  }
  return best;
}

std::optional<GougeWindow::Gouge> GougeWindow::add(const PlanePiece& p, bool cut, double min_distance,
                                                   double chord_tol) {
  auto g = nearest_below(p, cut ? programmed_ : cut_, min_distance, chord_tol, cut);
  std::deque<PlanePiece>& into = cut ? cut_ : programmed_;
  into.push_back(p);
  if (into.size() > kGougeWindow) into.pop_front();
  return g;
}

}  // namespace lcnc::gcode
