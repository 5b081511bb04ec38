#include "dxf/dxf_reader.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include <dl_creationadapter.h>
#include <dl_dxf.h>
#include <Eigen/Dense>

#include "common/error.h"
#include "dxf/dxf_scan.h"
#include "dxf/dxf_tolerances.h"
#include "dxf/spline_curve.h"

namespace lcnc::dxf {
namespace {

constexpr double kPi = std::numbers::pi;

// x ↦ m·x + t.
struct Affine {
  Eigen::Matrix2d m = Eigen::Matrix2d::Identity();
  Vec2 t = Vec2::Zero();

  [[nodiscard]] Vec2 operator()(const Vec2& p) const { return m * p + t; }
  [[nodiscard]] Affine then(const Affine& outer) const {  // outer ∘ this
    return Affine{outer.m * m, outer.m * t + outer.t};
  }
};

// An entity before its block is placed: edges in block coordinates, or a
// spline still as control points (the curve is made after the placement:
// NURBS are affine-invariant, so mapping the control points maps the curve).
struct RawEntity {
  EntityKind kind = EntityKind::Line;
  std::uint32_t line = 0;
  std::string layer;
  std::vector<Edge> edges;
  std::optional<SplineData> spline;
  bool closed = false;
};

struct RawInsert {
  std::string name;
  std::uint32_t line = 0;
  Affine ocs;  // the insert's object coordinate system (mirror for extrusion −Z)
  Vec2 ip = Vec2::Zero();
  double sx = 1.0, sy = 1.0, angle_deg = 0.0;
  int cols = 1, rows = 1;
  double col_sp = 0.0, row_sp = 0.0;
};

struct Container {
  Vec2 base = Vec2::Zero();
  std::vector<RawEntity> entities;
  std::vector<RawInsert> inserts;
  std::vector<std::pair<bool, std::size_t>> order;  // (is_insert, index) in file order
};

// Polyline vertex in the OCS, bulge of the segment that starts here.
struct PolyVertex {
  Vec2 p;
  double bulge;
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::uint32_t next_line(const std::vector<std::uint32_t>& lines, std::size_t& i) {
  return i < lines.size() ? lines[i++] : 0;
}

// Edges of a polyline segment p0 → p1 with bulge b = tan(θ/4), θ the signed
// included angle (> 0 counter-clockwise). Centre = midpoint +
// (1 − b²)/(4b) · perp(p1 − p0): on the left of the chord for b > 0.
void polyline_segment(const Vec2& p0, const Vec2& p1, double bulge, std::vector<Edge>& out) {
  const Vec2 d = p1 - p0;
  if (d.norm() <= kMinEdgeMm) return;
  if (std::abs(bulge) < 1e-12) {
    out.push_back(make_line(p0, p1));
    return;
  }
  const Vec2 perp(-d.y(), d.x());
  const Vec2 c = 0.5 * (p0 + p1) + (1.0 - bulge * bulge) / (4.0 * bulge) * perp;
  const double sweep = 4.0 * std::atan(bulge);
  Edge e = make_arc(c, (p0 - c).norm(), std::atan2(p0.y() - c.y(), p0.x() - c.x()), sweep);
  e.a = p0;  // exact ends, so consecutive segments meet exactly
  e.b = p1;
  out.push_back(e);
}

class Collector final : public DL_CreationAdapter {
 public:
  Collector(const ScanResult& scan, const std::string& file) : scan_(scan), file_(file) {}

  std::optional<Diagnostic> error;
  Container top;
  std::map<std::string, Container> blocks;
  std::vector<std::string> degenerate;  // entities of zero length, not cut

  void finish() { flush(); }

  void addBlock(const DL_BlockData& d) override {
    flush();
    cur_ = &blocks[d.name];
    *cur_ = Container{};
    cur_->base = Vec2(d.bpx, d.bpy);
  }
  void endBlock() override {
    flush();
    cur_ = &top;
  }

  void addLine(const DL_LineData& d) override {
    flush();
    RawEntity e = start(EntityKind::Line, next_line(scan_.line_lines, i_line_));
    const Vec2 a(d.x1, d.y1), b(d.x2, d.y2);
    if ((b - a).norm() > kMinEdgeMm) e.edges.push_back(make_line(a, b));
    push(std::move(e));
  }

  void addArc(const DL_ArcData& d) override {
    flush();
    RawEntity e = start(EntityKind::Arc, next_line(scan_.arc_lines, i_arc_));
    const std::optional<bool> mirror = ocs_mirror(e);
    if (!mirror) return;
    if (!(d.radius > 0.0)) {
      fail(e.line, "ARC with radius " + std::to_string(d.radius) + "; expected a radius > 0");
      return;
    }
    double a1 = d.angle1 * kPi / 180.0;
    double sweep = std::fmod(d.angle2 - d.angle1, 360.0);
    if (sweep <= 0.0) sweep += 360.0;  // DXF arcs run counter-clockwise angle1 → angle2
    sweep *= kPi / 180.0;
    Vec2 c(d.cx, d.cy);
    if (*mirror) {  // OCS x = −X: angles θ ↦ π − θ, direction reversed
      c.x() = -c.x();
      a1 = kPi - a1;
      sweep = -sweep;
    }
    e.edges.push_back(make_arc(c, d.radius, a1, sweep));
    push(std::move(e));
  }

  void addCircle(const DL_CircleData& d) override {
    flush();
    RawEntity e = start(EntityKind::Circle, next_line(scan_.circle_lines, i_circle_));
    const std::optional<bool> mirror = ocs_mirror(e);
    if (!mirror) return;
    if (!(d.radius > 0.0)) {
      fail(e.line, "CIRCLE with radius " + std::to_string(d.radius) + "; expected a radius > 0");
      return;
    }
    const Vec2 c(*mirror ? -d.cx : d.cx, d.cy);
    e.edges.push_back(make_arc(c, d.radius, 0.0, *mirror ? -2.0 * kPi : 2.0 * kPi));
    e.edges.back().b = e.edges.back().a;  // closes exactly
    e.closed = true;
    push(std::move(e));
  }

  void addPolyline(const DL_PolylineData& d) override {
    flush();
    const std::size_t k = i_poly_;
    const bool lw = k < scan_.poly_is_lw.size() && scan_.poly_is_lw[k];
    RawEntity e =
        start(lw ? EntityKind::LwPolyline : EntityKind::Polyline, next_line(scan_.poly_lines, i_poly_));
    const std::optional<bool> mirror = ocs_mirror(e);
    if (!mirror) return;
    if (!lw && (d.flags & (16 | 64)) != 0) {
      fail(e.line, "POLYLINE is a polygon mesh or polyface (flag 16/64); expected a 2D polyline");
      return;
    }
    if (!lw && (d.flags & 4) != 0) {
      fail(e.line, "POLYLINE is spline-fit (flag 4); expected a plain polyline (or a SPLINE)");
      return;
    }
    e.closed = (d.flags & 1) != 0;
    poly_mirror_ = *mirror;
    poly_ = std::move(e);
    poly_vertices_.clear();
  }

  void addVertex(const DL_VertexData& d) override {
    if (!poly_) return;
    Vec2 p(d.x, d.y);
    double bulge = d.bulge;
    if (poly_mirror_) {
      p.x() = -p.x();
      bulge = -bulge;
    }
    if (!std::isfinite(bulge) || std::abs(bulge) > kMaxBulge) {
      fail(poly_->line, std::string(entity_name(poly_->kind)) + " vertex " +
                            std::to_string(poly_vertices_.size() + 1) + " has bulge " + number(d.bulge) +
                            "; expected a bulge within ±" + number(kMaxBulge) +
                            " (tan of a quarter of the arc's angle)");
      return;
    }
    poly_vertices_.push_back(PolyVertex{p, bulge});
  }

  void addSpline(const DL_SplineData& d) override {
    flush();
    RawEntity e = start(EntityKind::Spline, next_line(scan_.spline_lines, i_spline_));
    SplineData s;
    s.degree = static_cast<int>(d.degree);
    // dxflib leaves an absent tangent (codes 12/22, 13/23) at 0, 0.
    const Vec2 t0(d.tangentStartX, d.tangentStartY), t1(d.tangentEndX, d.tangentEndY);
    if (t0.norm() > 0.0) s.start_tangent = t0;
    if (t1.norm() > 0.0) s.end_tangent = t1;
    e.spline = std::move(s);
    e.closed = (d.flags & 1) != 0;
    spline_ = std::move(e);
  }
  void addControlPoint(const DL_ControlPointData& d) override {
    if (!spline_) return;
    spline_->spline->control.emplace_back(d.x, d.y);
    spline_->spline->weights.push_back(d.w);
  }
  void addFitPoint(const DL_FitPointData& d) override {
    if (spline_) spline_->spline->fit.emplace_back(d.x, d.y);
  }
  void addKnot(const DL_KnotData& d) override {
    if (spline_) spline_->spline->knots.push_back(d.k);
  }

  void addInsert(const DL_InsertData& d) override {
    flush();
    RawInsert in;
    in.line = next_line(scan_.insert_lines, i_insert_);
    RawEntity probe = start(EntityKind::Line, in.line);
    const std::optional<bool> mirror = ocs_mirror(probe);
    if (!mirror) return;
    if (*mirror) in.ocs.m(0, 0) = -1.0;
    in.name = d.name;
    in.ip = Vec2(d.ipx, d.ipy);
    in.sx = d.sx;
    in.sy = d.sy;
    in.angle_deg = d.angle;
    in.cols = std::max(d.cols, 1);
    in.rows = std::max(d.rows, 1);
    in.col_sp = d.colSp;
    in.row_sp = d.rowSp;
    if (static_cast<std::size_t>(in.cols) * static_cast<std::size_t>(in.rows) > kMaxInsertCopies) {
      fail(in.line, "INSERT of " + in.name + " asks for " + std::to_string(in.cols) + " × " +
                        std::to_string(in.rows) + " copies; expected at most " +
                        std::to_string(kMaxInsertCopies));
      return;
    }
    if (in.sx == 0.0 || in.sy == 0.0) {
      fail(in.line, "INSERT of " + in.name + " with a zero scale; expected non-zero X and Y scales");
      return;
    }
    cur_->order.emplace_back(true, cur_->inserts.size());
    cur_->inserts.push_back(std::move(in));
  }

  void endSequence() override { flush(); }

 private:
  RawEntity start(EntityKind kind, std::uint32_t line) {
    RawEntity e;
    e.kind = kind;
    e.line = line;
    e.layer = attributes.getLayer();
    return e;
  }

  void fail(std::uint32_t line, std::string msg) {
    if (!error) error = make_error(ErrorCode::DxfUnsupported, std::move(msg), file_, line);
  }

  // The entity's extrusion direction: +Z → false, −Z → true (mirrored OCS),
  // anything else → error (not in the XY plane).
  std::optional<bool> ocs_mirror(const RawEntity& e) {
    const double* n = getExtrusion()->getDirection();
    if (std::abs(n[0]) <= kExtrusionTol && std::abs(n[1]) <= kExtrusionTol) {
      if (n[2] > 0.0) return false;
      if (n[2] < 0.0) return true;
    }
    fail(e.line, std::string(entity_name(e.kind)) + " lies outside the XY plane (extrusion " +
                     std::to_string(n[0]) + ", " + std::to_string(n[1]) + ", " + std::to_string(n[2]) +
                     "); expected 0, 0, ±1");
    return std::nullopt;
  }

  void push(RawEntity e) {
    if (e.edges.empty() && !e.spline) {  // zero length: nothing to cut, but said
      degenerate.push_back(std::string(entity_name(e.kind)) + " at DXF line " + std::to_string(e.line));
      return;
    }
    for (Edge& ed : e.edges) {
      ed.source = e.kind;
      ed.line = e.line;
    }
    cur_->order.emplace_back(false, cur_->entities.size());
    cur_->entities.push_back(std::move(e));
  }

  // Completes the polyline or spline whose parts dxflib delivered one by one.
  void flush() {
    if (poly_) {
      RawEntity e = std::move(*poly_);
      poly_.reset();
      const std::size_t n = poly_vertices_.size();
      for (std::size_t i = 0; i + 1 < n; ++i) {
        polyline_segment(poly_vertices_[i].p, poly_vertices_[i + 1].p, poly_vertices_[i].bulge, e.edges);
      }
      if (e.closed && n >= 2) {
        polyline_segment(poly_vertices_[n - 1].p, poly_vertices_[0].p, poly_vertices_[n - 1].bulge, e.edges);
      }
      push(std::move(e));
    }
    if (spline_) {
      RawEntity e = std::move(*spline_);
      spline_.reset();
      bool unit = true;
      for (double w : e.spline->weights) unit = unit && w == 1.0;
      if (unit) e.spline->weights.clear();
      push(std::move(e));
    }
  }

  const ScanResult& scan_;
  const std::string& file_;
  Container* cur_ = &top;
  std::size_t i_line_ = 0, i_arc_ = 0, i_circle_ = 0, i_poly_ = 0, i_spline_ = 0, i_insert_ = 0;
  std::optional<RawEntity> poly_;
  bool poly_mirror_ = false;
  std::vector<PolyVertex> poly_vertices_;
  std::optional<RawEntity> spline_;
};

// Places the entities of `c` through `xf` into the drawing, inserts recursively.
class Expander {
 public:
  Expander(const std::map<std::string, Container>& blocks, const std::string& file, Drawing& out)
      : blocks_(blocks), file_(file), out_(out) {}

  // Before anything is placed: every INSERT names a block, no block inserts
  // itself, nesting stays under kMaxBlockDepth and the INSERTs place at
  // most kMaxPlacedEntities in all — counted per block once, so a drawing
  // whose nested arrays multiply into millions of copies is refused at once
  // instead of worked through (found by fuzzing: 16 levels of 2 × 2 arrays
  // of a spline took minutes under the sanitizers).
  Status check(const Container& top) {
    double placed = 0.0;
    for (const RawInsert& in : top.inserts) {
      Result<double> c = count(in, 1, "");
      if (!c) return c.error();
      placed += *c;
      if (placed > static_cast<double>(kMaxPlacedEntities)) {
        return make_error(ErrorCode::DxfUnsupported,
                          "the INSERTs place more than " + std::to_string(kMaxPlacedEntities) +
                              " entities (this one of block '" + in.name + "' " + fmt_count(*c) +
                              "); expected fewer copies",
                          file_, in.line);
      }
    }
    return {};
  }

  Status expand(const Container& c, const Affine& xf, const std::string& block, int depth,
                std::uint32_t insert_line) {
    for (const auto& [is_insert, idx] : c.order) {
      if (is_insert) {
        if (Status s = expand_insert(c.inserts[idx], xf, depth); !s) return s;
      } else {
        if (Status s = place(c.entities[idx], xf, block, insert_line); !s) return s;
      }
    }
    return {};
  }

 private:
  static std::string fmt_count(double n) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", n);
    return b;
  }

  // The entities one INSERT places (all its copies, their INSERTs expanded),
  // its block counted once. `inside`: the block holding this INSERT ("" at
  // the top).
  Result<double> count(const RawInsert& in, int depth, const std::string& inside) {
    Result<const Container*> blk = block_of(in);
    if (!blk) return blk.error();
    if (depth > kMaxBlockDepth) return too_deep(in);
    double one = 0.0;  // one copy of the block
    if (const auto done = counted_.find(in.name); done != counted_.end()) {
      one = done->second;
    } else {
      if (!visiting_.insert(in.name).second) {
        return make_error(ErrorCode::DxfUnsupported,
                          "INSERT of block '" + in.name + "' inside block '" + inside +
                              "' closes a loop; expected no block to insert itself, directly "
                              "or through others",
                          file_, in.line);
      }
      one = static_cast<double>((*blk)->entities.size());
      for (const RawInsert& inner : (*blk)->inserts) {
        Result<double> c = count(inner, depth + 1, in.name);
        if (!c) return c.error();
        one += *c;
      }
      visiting_.erase(in.name);
      counted_[in.name] = one;
    }
    return one * in.cols * in.rows;
  }

  Diagnostic too_deep(const RawInsert& in) const {
    return make_error(ErrorCode::DxfUnsupported,
                      "INSERT of block '" + in.name + "' nests " + std::to_string(kMaxBlockDepth) +
                          " blocks deep; expected fewer",
                      file_, in.line);
  }

  // The block an INSERT names.
  Result<const Container*> block_of(const RawInsert& in) const {
    const auto it = blocks_.find(in.name);
    if (it == blocks_.end()) {
      return make_error(
          ErrorCode::DxfSyntax,
          "INSERT of block '" + in.name + "', which is not defined; expected a BLOCK of that name", file_,
          in.line);
    }
    return &it->second;
  }

  Status expand_insert(const RawInsert& in, const Affine& outer, int depth) {
    Result<const Container*> found = block_of(in);  // check() refused these first
    if (!found) return found.error();
    if (depth >= kMaxBlockDepth) return too_deep(in);
    const Container& blk = **found;
    const double ang = in.angle_deg * kPi / 180.0;
    const Eigen::Matrix2d rot = Eigen::Rotation2Dd(ang).toRotationMatrix();
    for (int r = 0; r < in.rows; ++r) {
      for (int col = 0; col < in.cols; ++col) {
        // p ↦ ocs(ip + R·(S·(p − base) + (col·col_sp, r·row_sp)))
        Affine local;
        local.m = rot * Eigen::Vector2d(in.sx, in.sy).asDiagonal();
        local.t = in.ip + rot * (Vec2(col * in.col_sp, r * in.row_sp) -
                                 Vec2(in.sx * blk.base.x(), in.sy * blk.base.y()));
        const Affine xf = local.then(in.ocs).then(outer);
        if (Status s = expand(blk, xf, in.name, depth + 1, in.line); !s) return s;
      }
    }
    return {};
  }

  Status place(const RawEntity& e, const Affine& xf, const std::string& block, std::uint32_t insert_line) {
    Entity out;
    out.kind = e.kind;
    out.line = e.line;
    out.layer = e.layer;
    out.block = block;
    out.closed = e.closed;
    const double det = xf.m.determinant();
    if (e.spline) {
      SplineData s = *e.spline;
      for (Vec2& p : s.control) p = xf(p);
      for (Vec2& p : s.fit) p = xf(p);
      for (std::optional<Vec2>* t : {&s.start_tangent, &s.end_tangent}) {
        if (*t) **t = xf.m * **t;  // a direction: the linear part only
      }
      std::string why;
      std::shared_ptr<const SplineCurve> curve =
          SplineCurve::make(s, &why, std::min(kSplineMaxNodes, spline_nodes_left_));
      if (!curve) {
        if (spline_nodes_left_ < kSplineMaxNodes)
          why += " — the drawing's splines take at most " + std::to_string(kMaxDrawingSplineNodes) +
                 " pieces in all, " + std::to_string(spline_nodes_left_) + " were left";
        return make_error(ErrorCode::DxfUnsupported, "SPLINE: " + why, file_, e.line);
      }
      spline_nodes_left_ -= curve->nodes();
      out.edges.push_back(make_spline(curve));
      // A closed spline whose ends do not meet: the closing line is drawn.
      if (e.closed && (curve->end() - curve->start()).norm() > kMinEdgeMm) {
        out.edges.push_back(make_line(curve->end(), curve->start()));
      }
    } else {
      for (const Edge& ed : e.edges) {
        if (ed.kind == EdgeKind::Line) {
          out.edges.push_back(make_line(xf(ed.a), xf(ed.b)));
        } else {
          // An arc stays an arc under a similarity only: M^T M = s² I.
          const double s2 = std::abs(det);
          const Eigen::Matrix2d mtm = xf.m.transpose() * xf.m;
          if ((mtm - s2 * Eigen::Matrix2d::Identity()).norm() > kSimilarityRel * s2) {
            return make_error(ErrorCode::DxfUnsupported,
                              std::string(entity_name(e.kind)) +
                                  " inserted with unequal X/Y "
                                  "scales (INSERT at line " +
                                  std::to_string(insert_line) +
                                  ") would be an ellipse; expected equal scales",
                              file_, e.line);
          }
          const double s = std::sqrt(s2);
          const Vec2 dir = xf.m * Vec2(std::cos(ed.start_rad), std::sin(ed.start_rad));
          Edge a = make_arc(xf(ed.center), ed.radius * s, std::atan2(dir.y(), dir.x()),
                            det < 0.0 ? -ed.sweep_rad : ed.sweep_rad);
          a.a = xf(ed.a);
          a.b = xf(ed.b);
          out.edges.push_back(a);
        }
      }
    }
    for (Edge& ed : out.edges) {
      ed.source = e.kind;
      ed.line = e.line;
    }
    if (!out.edges.empty()) out_.entities.push_back(std::move(out));
    return {};
  }

  const std::map<std::string, Container>& blocks_;
  const std::string& file_;
  Drawing& out_;
  std::map<std::string, double> counted_;  // check(): entities of one copy of each block
  std::set<std::string> visiting_;         // check(): the blocks being counted, outermost first
  std::size_t spline_nodes_left_ = kMaxDrawingSplineNodes;
};

}  // namespace

double insunits_mm(int code, std::string* name) {
  struct Unit {
    int code;
    const char* name;
    double mm;
  };
  static constexpr Unit kUnits[] = {
      {1, "inch", 25.4},
      {2, "foot", 304.8},
      {3, "mile", 1609344.0},
      {4, "mm", 1.0},
      {5, "cm", 10.0},
      {6, "m", 1000.0},
      {7, "km", 1e6},
      {8, "microinch", 25.4e-6},
      {9, "mil", 0.0254},
      {10, "yard", 914.4},
      {11, "angstrom", 1e-7},
      {12, "nanometre", 1e-6},
      {13, "micron", 1e-3},
      {14, "decimetre", 100.0},
      {15, "decametre", 1e4},
      {16, "hectometre", 1e5},
      {17, "gigametre", 1e12},
      {18, "astronomical unit", 1.495978707e14},
      {19, "light year", 9.4607304725808e18},
      {20, "parsec", 3.0856775814913673e19},
  };
  for (const Unit& u : kUnits) {
    if (u.code == code) {
      if (name) *name = u.name;
      return u.mm;
    }
  }
  return 0.0;
}

Result<ReadResult> read_dxf_text(std::string_view text, const std::string& file, const ReadOptions& opt) {
  Result<ScanResult> scan = scan_dxf(text, file);
  if (!scan) return scan.error();

  ReadResult out;
  out.drawing.file = file;
  for (const std::string& s : scan->ignored) out.notes.push_back("ignored: " + s);

  // Units: the option, else $INSUNITS, else mm.
  double unit_mm = opt.unit_mm;
  if (unit_mm > 0.0) {
    out.drawing.units = "set by the caller";
  } else if (scan->insunits <= 0) {
    unit_mm = 1.0;
    out.drawing.units_known = false;
    out.drawing.units =
        scan->insunits == 0 ? "unitless ($INSUNITS 0), read as mm" : "not set ($INSUNITS absent), read as mm";
  } else {
    std::string name;
    unit_mm = insunits_mm(scan->insunits, &name);
    if (unit_mm <= 0.0) {
      return make_error(ErrorCode::DxfUnsupported,
                        "$INSUNITS " + std::to_string(scan->insunits) +
                            " is not a length unit; expected 0–20 (4 = mm, 1 = inch)",
                        file, 0);
    }
    out.drawing.units = name;
  }
  out.drawing.unit_mm = unit_mm;
  out.notes.push_back("units: " + out.drawing.units +
                      (unit_mm != 1.0 ? " (" + std::to_string(unit_mm) + " mm per unit)" : ""));

  Collector col(*scan, file);
  DL_Dxf dxf;
  std::istringstream in(scan->filtered);
  dxf.in(in, &col);
  col.finish();
  if (col.error) return *col.error;
  if (!col.degenerate.empty()) {
    std::string list;
    for (std::size_t i = 0; i < col.degenerate.size() && i < 5; ++i)
      list += (i ? ", " : "") + col.degenerate[i];
    if (col.degenerate.size() > 5) list += ", …";
    out.notes.push_back("warning: " + std::to_string(col.degenerate.size()) + " entit" +
                        (col.degenerate.size() == 1 ? "y" : "ies") + " of zero length, not cut: " + list);
  }

  Affine units;
  units.m *= unit_mm;
  Expander ex(col.blocks, file, out.drawing);
  if (Status s = ex.check(col.top); !s) return s.error();
  if (Status s = ex.expand(col.top, units, {}, 0, 0); !s) return s.error();
  return out;
}

// Reads the file in chunks, bounded: a regular file larger than
// kMaxDxfFileBytes is refused before reading; any other file (a pipe, a
// device such as /dev/zero) is read only until it passes that size or a line
// passes kMaxDxfLine, so nothing is read or held without end.
Result<ReadResult> read_dxf_file(const std::string& path, const ReadOptions& opt) {
  struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
  };
  const std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) {
    return make_error(
        ErrorCode::FileNotFound,
        "cannot open '" + path + "': " + std::strerror(errno) + "; expected a readable DXF file", path);
  }
  const std::string bound =
      std::to_string(kMaxDxfFileBytes) + " bytes (" + std::to_string(kMaxDxfFileBytes >> 20) + " MiB)";
  std::string text;
  struct stat st {};
  if (::fstat(::fileno(f.get()), &st) == 0 && S_ISREG(st.st_mode)) {
    if (static_cast<std::uint64_t>(st.st_size) > kMaxDxfFileBytes) {
      return make_error(
          ErrorCode::DxfUnsupported,
          "a file of " + std::to_string(st.st_size) + " bytes; expected a DXF file of at most " + bound,
          path);
    }
    text.reserve(static_cast<std::size_t>(st.st_size));
  }
  constexpr std::size_t kChunk = 1u << 16;
  std::unique_ptr<char[]> chunk(new char[kChunk]);
  std::size_t line_bytes = 0;  // of the line being read, '\r' included
  std::uint32_t line = 1;
  for (;;) {
    const std::size_t got = std::fread(chunk.get(), 1, kChunk, f.get());
    if (got == 0) break;
    for (const char* p = chunk.get(); p < chunk.get() + got;) {
      const char* end = chunk.get() + got;
      const auto* nl = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
      line_bytes += static_cast<std::size_t>((nl != nullptr ? nl : end) - p);
      if (line_bytes > kMaxDxfLine + 1) {
        return make_error(ErrorCode::DxfSyntax,
                          "a line of more than " + std::to_string(kMaxDxfLine) +
                              " characters (no line end within them); expected at most " +
                              std::to_string(kMaxDxfLine) + " (a group code or value)",
                          path, line);
      }
      if (nl == nullptr) break;
      line_bytes = 0;
      ++line;
      p = nl + 1;
    }
    if (text.size() + got > kMaxDxfFileBytes) {
      return make_error(ErrorCode::DxfUnsupported,
                        "more than " + bound +
                            " read and no end of file; expected a DXF "
                            "file of at most " +
                            bound,
                        path);
    }
    text.append(chunk.get(), got);
  }
  if (std::ferror(f.get()) != 0) {
    return make_error(
        ErrorCode::FileNotFound,
        "reading '" + path + "' stopped: " + std::strerror(errno) + "; expected to read the whole DXF file",
        path);
  }
  return read_dxf_text(text, path, opt);
}

}  // namespace lcnc::dxf
