// A 2D drawing as the DXF reader hands it on: every supported entity turned
// into a chain of edges (lines and circular arcs) in drawing coordinates, mm,
// blocks already inserted: lines, circular arcs (bulged polyline segments
// too) and splines (sampled at exact arc lengths, spline_curve.h).
//
// Edge geometry (a point at arc length s, length, reversal) is here too: the
// chaining, discretization and checks all walk the same edges.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dxf/spline_curve.h"

namespace lcnc::dxf {

// The DXF entity kinds the reader takes (what an error names).
enum class EntityKind : std::uint8_t { Line, Arc, Circle, LwPolyline, Polyline, Spline };
[[nodiscard]] const char* entity_name(EntityKind k) noexcept;

enum class EdgeKind : std::uint8_t { Line, Arc, Spline };

// A line a → b, or an arc about `center` of `radius` from angle `start_rad`
// through the signed `sweep_rad` (> 0 counter-clockwise). `a` and `b` are the
// arc's end points too (kept so that chained ends match exactly).
struct Edge {
  EdgeKind kind = EdgeKind::Line;
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
  double start_rad = 0.0;
  double sweep_rad = 0.0;
  std::shared_ptr<const SplineCurve> spline;
  bool spline_reversed = false;
  // The entity it came from (for messages): its kind and DXF line.
  EntityKind source = EntityKind::Line;
  std::uint32_t line = 0;
};

[[nodiscard]] Edge make_line(const Vec2& a, const Vec2& b);
[[nodiscard]] Edge make_arc(const Vec2& center, double radius, double start_rad, double sweep_rad);
[[nodiscard]] Edge make_spline(std::shared_ptr<const SplineCurve> c);
[[nodiscard]] double edge_length(const Edge& e);
// The point at arc length s ∈ [0, edge_length(e)] from a.
[[nodiscard]] Vec2 edge_point(const Edge& e, double s);
// The same edge traversed b → a.
[[nodiscard]] Edge reversed(const Edge& e);

// One source entity: its edges run head to tail from the entity's start to
// its end. `closed` when it is a contour by itself (circle, closed polyline
// or spline). Where it came from, for error messages.
struct Entity {
  EntityKind kind = EntityKind::Line;
  std::vector<Edge> edges;
  bool closed = false;
  std::uint32_t line = 0;  // DXF line of the entity's "0 / TYPE" pair (1-based)
  std::string layer;
  std::string block;  // the block it was inserted from; empty in ENTITIES

  [[nodiscard]] Vec2 start() const { return edges.front().a; }
  [[nodiscard]] Vec2 end() const { return edges.back().b; }
};

struct Drawing {
  std::string file;
  std::vector<Entity> entities;
  double unit_mm = 1.0;  // mm per drawing unit ($INSUNITS), already applied
  std::string units;     // "mm", "inch", ... ("unitless, read as mm" when unset)
  // False when neither the caller nor $INSUNITS named a length unit (absent
  // or 0, unitless): the drawing was read as mm by assumption.
  bool units_known = true;
};

// One closed contour: entities chained head to tail, each possibly reversed,
// the last one ending where the first one starts. `index` is 1-based, in the
// order the contours were found (drawing order of their first entity).
struct Contour {
  std::uint32_t index = 0;
  std::vector<Edge> edges;
  // The first entity (for messages: "contour 2 (LINE at line 40, layer CUT)").
  EntityKind first_kind = EntityKind::Line;
  std::uint32_t first_line = 0;
  std::string layer;
  std::string block;

  [[nodiscard]] double length() const;
  // "contour 2 (LINE at DXF line 40, layer CUT)"
  [[nodiscard]] std::string name() const;
};

}  // namespace lcnc::dxf
