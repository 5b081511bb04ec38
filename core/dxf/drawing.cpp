#include "dxf/drawing.h"

#include <cmath>

namespace lcnc::dxf {

Edge make_line(const Vec2& a, const Vec2& b) {
  Edge e;
  e.kind = EdgeKind::Line;
  e.a = a;
  e.b = b;
  return e;
}

Edge make_arc(const Vec2& center, double radius, double start_rad, double sweep_rad) {
  Edge e;
  e.kind = EdgeKind::Arc;
  e.center = center;
  e.radius = radius;
  e.start_rad = start_rad;
  e.sweep_rad = sweep_rad;
  e.a = center + radius * Vec2(std::cos(start_rad), std::sin(start_rad));
  const double end = start_rad + sweep_rad;
  e.b = center + radius * Vec2(std::cos(end), std::sin(end));
  return e;
}

Edge make_spline(std::shared_ptr<const SplineCurve> c) {
  Edge e;
  e.kind = EdgeKind::Spline;
  e.a = c->start();
  e.b = c->end();
  e.spline = std::move(c);
  return e;
}

double edge_length(const Edge& e) {
  switch (e.kind) {
    case EdgeKind::Line: return (e.b - e.a).norm();
    case EdgeKind::Arc: return e.radius * std::abs(e.sweep_rad);
    case EdgeKind::Spline: return e.spline->length();
  }
  return 0.0;
}

Vec2 edge_point(const Edge& e, double s) {
  const double len = edge_length(e);
  if (len <= 0.0) return e.a;
  if (e.kind == EdgeKind::Spline) return e.spline->at_length(e.spline_reversed ? len - s : s);
  const double f = s / len;
  if (e.kind == EdgeKind::Line) return e.a + f * (e.b - e.a);
  const double ang = e.start_rad + f * e.sweep_rad;
  return e.center + e.radius * Vec2(std::cos(ang), std::sin(ang));
}

Edge reversed(const Edge& e) {
  Edge r = e;
  r.a = e.b;
  r.b = e.a;
  if (e.kind == EdgeKind::Spline) r.spline_reversed = !e.spline_reversed;
  if (e.kind == EdgeKind::Arc) {
    r.start_rad = e.start_rad + e.sweep_rad;
    r.sweep_rad = -e.sweep_rad;
  }
  return r;
}

const char* entity_name(EntityKind k) noexcept {
  switch (k) {
    case EntityKind::Line: return "LINE";
    case EntityKind::Arc: return "ARC";
    case EntityKind::Circle: return "CIRCLE";
    case EntityKind::LwPolyline: return "LWPOLYLINE";
    case EntityKind::Polyline: return "POLYLINE";
    case EntityKind::Spline: return "SPLINE";
  }
  return "?";
}

double Contour::length() const {
  double l = 0.0;
  for (const Edge& e : edges) l += edge_length(e);
  return l;
}

std::string Contour::name() const {
  std::string s = "contour " + std::to_string(index) + " (" + entity_name(first_kind) + " at DXF line " +
                  std::to_string(first_line);
  if (!layer.empty()) s += ", layer " + layer;
  if (!block.empty()) s += ", block " + block;
  return s + ")";
}

}  // namespace lcnc::dxf
