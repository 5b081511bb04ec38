#include "cut/contour_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cut/cut_tolerances.h"
#include "geom/plane.h"

namespace lcnc::cut {
namespace {

using geom::point_segment;

// Deepest halving of a spline edge (2^16 chords).
constexpr int kMaxSplineDepth = 16;

// Appends the points of (s0, s1] of a spline edge.
void spline_points(const dxf::Edge& e, double s0, const Vec2& p0, double s1, const Vec2& p1, double tol,
                   int depth, std::vector<Vec2>& out) {
  const double sm = 0.5 * (s0 + s1);
  const Vec2 pm = dxf::edge_point(e, sm);
  if (depth < kMaxSplineDepth && (depth < 2 || point_segment(pm, p0, p1) > tol)) {
    spline_points(e, s0, p0, sm, pm, tol, depth + 1, out);
    spline_points(e, sm, pm, s1, p1, tol, depth + 1, out);
    return;
  }
  out.push_back(p1);
}

}  // namespace

dxf::Polyline contour_polygon(const dxf::Contour& c, double chord_tol_mm) {
  dxf::Polyline pl;
  pl.contour = c.index;
  for (const dxf::Edge& e : c.edges) {
    std::vector<Vec2> pts;  // the edge's points after its start
    if (e.kind == dxf::EdgeKind::Line) {
      pts.push_back(e.b);
    } else if (e.kind == dxf::EdgeKind::Arc) {
      const double phi = 2.0 * std::acos(std::max(-1.0, 1.0 - chord_tol_mm / e.radius));
      const auto n =
          static_cast<std::size_t>(std::max(1.0, std::ceil(std::abs(e.sweep_rad) / std::max(phi, 1e-9))));
      for (std::size_t k = 1; k < n; ++k) {
        const double a = e.start_rad + e.sweep_rad * static_cast<double>(k) / static_cast<double>(n);
        pts.push_back(e.center + e.radius * Vec2(std::cos(a), std::sin(a)));
      }
      pts.push_back(e.b);
    } else {
      spline_points(e, 0.0, e.a, dxf::edge_length(e), e.b, chord_tol_mm, 0, pts);
      pts.back() = e.b;  // the chained end, exactly
    }
    for (const Vec2& p : pts) {
      if (!pl.pts.empty() && (p - pl.pts.back()).norm() <= 1e-9) continue;
      pl.pts.push_back(p);
      pl.src_line.push_back(e.line);
    }
  }
  // The last point closes onto the first (the contour is closed).
  if (pl.pts.size() > 1 && (pl.pts.back() - pl.pts.front()).norm() <= 1e-6) {
    pl.pts.pop_back();
    pl.src_line.pop_back();
  }
  pl.length_mm = c.length();
  return pl;
}

double signed_area(const std::vector<Vec2>& poly) {
  double a = 0.0;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    a += poly[j].x() * poly[i].y() - poly[i].x() * poly[j].y();
  }
  return 0.5 * a;
}

bool inside(const Vec2& p, const std::vector<Vec2>& poly) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

double distance_to(const Vec2& p, const std::vector<Vec2>& poly) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    d = std::min(d, point_segment(p, poly[j], poly[i]));
  }
  return d;
}

}  // namespace lcnc::cut
