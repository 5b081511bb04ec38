#include "cut/cut_program.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <cstdio>

#include "cut/contour_nesting.h"
#include "cut/contour_polygon.h"
#include "cut/cut_order.h"
#include "cut/kerf_offset.h"
#include "dxf/contour_chain.h"
#include "dxf/contour_check.h"

namespace lcnc::cut {
namespace {

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

// Everything the drawing's entities cover: line ends, arcs as their circles.
Eigen::AlignedBox2d drawing_box(const dxf::Drawing& d) {
  Eigen::AlignedBox2d box;
  for (const dxf::Entity& e : d.entities) {
    for (const dxf::Edge& ed : e.edges) {
      box.extend(ed.a);
      box.extend(ed.b);
      if (ed.kind == dxf::EdgeKind::Arc) {
        box.extend(ed.center - Vec2::Constant(ed.radius));
        box.extend(ed.center + Vec2::Constant(ed.radius));
      }
    }
  }
  return box;
}

// The contour's exact extent: edge ends, and the points of its arcs at 0°,
// 90°, 180°, 270° that lie within their sweeps (splines by their ends and
// the polygon's vertices).
Eigen::AlignedBox2d contour_box(const dxf::Contour& c, const std::vector<Vec2>& poly) {
  Eigen::AlignedBox2d b;
  for (const Vec2& p : poly) b.extend(p);
  for (const dxf::Edge& e : c.edges) {
    if (e.kind != dxf::EdgeKind::Arc) continue;
    for (int q = 0; q < 4; ++q) {
      const double a = q * M_PI / 2;
      double rel = (a - e.start_rad) * (e.sweep_rad > 0 ? 1.0 : -1.0);
      rel = std::fmod(std::fmod(rel, 2 * M_PI) + 2 * M_PI, 2 * M_PI);
      if (rel <= std::abs(e.sweep_rad)) b.extend(e.center + e.radius * Vec2(std::cos(a), std::sin(a)));
    }
  }
  return b;
}

double path_length(const std::vector<Vec2>& p) {
  double l = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) l += (p[(i + 1) % p.size()] - p[i]).norm();
  return l;
}

double polyline_length(const Vec2& from, const std::vector<Vec2>& p) {
  double l = 0.0;
  Vec2 at = from;
  for (const Vec2& q : p) {
    l += (q - at).norm();
    at = q;
  }
  return l;
}

}  // namespace

Status check_units(const dxf::Drawing& d, bool units_given) {
  if (units_given) return {};
  const Eigen::AlignedBox2d box = drawing_box(d);
  const Vec2 size = box.isEmpty() ? Vec2::Zero() : Vec2(box.sizes());
  const std::string extent = fmt("%.4g x %.4g mm", size.x(), size.y());
  if (!d.units_known) {
    return make_error(ErrorCode::CutUnits,
                      "the drawing's units are not known (" + d.units + "; the part is " + extent +
                          " across if read as mm); expected --units mm|inch|cm|m",
                      d.file);
  }
  const double across = size.maxCoeff();
  if (across < kMinPartMm || across > kMaxPartMm) {
    return make_error(ErrorCode::CutUnits,
                      "the part is " + extent + " across in the drawing's units (" + d.units + "), " +
                          (across < kMinPartMm ? "smaller than " : "larger than ") +
                          fmt("%g mm", across < kMinPartMm ? kMinPartMm : kMaxPartMm) +
                          ": wrong units?; expected --units mm|inch|cm|m to say which",
                      d.file);
  }
  return {};
}

Result<CutPlan> plan_cut(const dxf::Drawing& d, const CutOptions& opt) {
  // 1. contours and their polygons, none crossing
  Result<std::vector<dxf::Contour>> chained = dxf::chain_contours(d);
  if (!chained) return chained.error();
  const std::vector<dxf::Contour>& contours = *chained;
  std::vector<dxf::Polyline> lines;
  std::vector<std::vector<Vec2>> polys;
  for (const dxf::Contour& c : contours) {
    lines.push_back(contour_polygon(c, kChordToleranceMm));
    polys.push_back(lines.back().pts);
  }
  if (Status s = dxf::check_crossings(contours, lines, d.file); !s) return s.error();

  // 2. parts and holes
  const Nesting nest = nest_contours(polys);

  // 3. kerf offset, oriented
  std::vector<std::vector<Vec2>> paths(contours.size());
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const bool hole = nest.is_hole(i);
    const double half = opt.process.for_layer(contours[i].layer).kerf_mm / 2.0;
    if (half > 0.0) {
      std::vector<std::vector<Vec2>> off = offset_polygon(polys[i], hole ? -half : half);
      const Eigen::AlignedBox2d box = contour_box(contours[i], polys[i]);
      const std::string size = fmt("%.3f x %.3f mm", box.sizes().x(), box.sizes().y());
      if (off.empty()) {
        return make_error(ErrorCode::CutKerf,
                          contours[i].name() + ", a hole " + size +
                              ", vanishes under the kerf "
                              "offset of " +
                              fmt("%.3f mm (kerf %.3f mm)", half, 2 * half) +
                              "; expected a hole wider than the kerf",
                          d.file, contours[i].first_line);
      }
      if (hole && off.size() > 1) {
        return make_error(ErrorCode::CutKerf,
                          contours[i].name() + ", a hole " + size + ", splits into " +
                              std::to_string(off.size()) + " pieces under the kerf offset of " +
                              fmt("%.3f mm", half) +
                              " (a waist narrower than the kerf); expected "
                              "every part of a hole wider than the kerf",
                          d.file, contours[i].first_line);
      }
      paths[i] = std::move(off.front());
    } else {
      paths[i] = polys[i];
      if (signed_area(paths[i]) < 0.0) std::reverse(paths[i].begin(), paths[i].end());
    }
    // counter-clockwise now; clockwise where asked
    const bool cw = (opt.outer == Direction::Cw) != hole;
    if (cw) std::reverse(paths[i].begin(), paths[i].end());
  }

  // 4. order, pierce points, lead-ins
  CutPlan plan;
  Vec2 at = Vec2::Zero() - opt.origin;  // the program starts at X0 Y0
  const std::vector<std::size_t> order = cut_order(nest, paths, at, [&](std::size_t i, const Vec2& from) {
    std::vector<const std::vector<Vec2>*> others;
    for (std::size_t j = 0; j < paths.size(); ++j) {
      if (j != i) others.push_back(&paths[j]);
    }
    CutContour c;
    c.index = contours[i].index;
    c.name = contours[i].name();
    c.layer = contours[i].layer;
    c.depth = nest.depth[i];
    c.hole = nest.is_hole(i);
    c.process = opt.process.for_layer(c.layer);
    c.drawing = polys[i];
    LeadInRequest req;
    req.hole = c.hole;
    req.lead_in_mm = opt.lead_in_mm;
    req.lead_out_mm = opt.lead_out_mm;
    req.offset_mm = c.process.kerf_mm / 2.0;
    c.entry = place_lead_in(paths[i], polys[i], from, req, others);
    if (c.entry.shortened) {
      plan.warnings.push_back(
          c.name + (c.hole ? ": the hole" : ": the outline") +
          fmt(" has no room for a %.3f mm lead-in; %.3f mm used", opt.lead_in_mm, c.entry.lead_in_mm));
    }
    c.path_mm = path_length(c.entry.path);
    plan.rapid_mm += (c.entry.pierce - from).norm();
    const double overcut = polyline_length(c.entry.path.front(), c.entry.overcut);
    plan.cut_mm += c.path_mm + overcut;
    plan.lead_mm += c.entry.lead_in_mm;
    plan.time_s += (c.path_mm + overcut + c.entry.lead_in_mm) / (c.process.feed_mm_min / 60.0) +
                   c.process.pierce_s + (c.entry.pierce - from).norm() / kEstimateRapidMmS;
    (c.hole ? plan.holes : plan.parts) += 1;
    Vec2 end = c.entry.overcut.empty() ? c.entry.path.front() : c.entry.overcut.back();
    plan.contours.push_back(std::move(c));
    return end;
  });
  (void)order;  // plan.contours is in the same order
  return plan;
}

std::string cut_gcode(const CutPlan& plan, const CutOptions& opt, const std::string& source) {
  std::string g;
  auto line = [&](const std::string& s) { g += s + "\n"; };
  auto xy = [&](const Vec2& p) {
    const Vec2 q = p + opt.origin;
    char buf[64];
    std::snprintf(buf, sizeof buf, "X%.4f Y%.4f", q.x(), q.y());
    return std::string(buf);
  };
  auto paren = [](std::string s) {  // a comment may not hold parentheses
    std::replace(s.begin(), s.end(), '(', '[');
    std::replace(s.begin(), s.end(), ')', ']');
    return s;
  };
  const char* outer = opt.outer == Direction::Cw ? "cw" : "ccw";
  const char* inner = opt.outer == Direction::Cw ? "ccw" : "cw";
  line("%");
  line("(" +
       paren("lasercnc cut: " + source + ", " + std::to_string(plan.contours.size()) + " contours: " +
             std::to_string(plan.parts) + " outlines, " + std::to_string(plan.holes) + " holes") +
       ")");
  line("(units mm; kerf compensated in the path: outlines offset outward, holes inward by kerf/2)");
  line(std::string("(outlines ") + outer + ", holes " + inner +
       fmt("; lead-in %.3f mm from the scrap side, lead-out overcut %.3f mm)", opt.lead_in_mm,
           opt.lead_out_mm));
  line(fmt("(drawing 0,0 at X%.4f Y%.4f; order: inner contours before the contour around them)",
           opt.origin.x(), opt.origin.y()));
  line(fmt("G21 G90 G17 G94 G64 P%.4g", kBlendToleranceMm));
  line("M8 (assist gas on)");
  std::size_t k = 0;
  for (const CutContour& c : plan.contours) {
    ++k;
    line("");
    line("(" +
         paren(fmt("cut %.0f of %.0f: ", static_cast<double>(k), static_cast<double>(plan.contours.size())) +
               (c.hole ? "hole" : "outline") + " " + c.name + ", layer " + c.layer +
               fmt(", depth %.0f, kerf %.3f mm", c.depth, c.process.kerf_mm)) +
         ")");
    line("G0 " + xy(c.entry.pierce) + " (pierce)");
    line(fmt("M3 S%.4g", c.process.power_pct));
    if (c.process.pierce_s > 0.0) line(fmt("G4 P%.4g", c.process.pierce_s));
    const std::string feed = fmt(" F%.6g", c.process.feed_mm_min);
    if (c.entry.lead_in_mm > 0.0) {
      line("G1 " + xy(c.entry.path.front()) + feed + fmt(" (lead-in %.3f mm)", c.entry.lead_in_mm));
      for (std::size_t i = 1; i < c.entry.path.size(); ++i) line("G1 " + xy(c.entry.path[i]));
    } else {
      for (std::size_t i = 1; i < c.entry.path.size(); ++i)
        line("G1 " + xy(c.entry.path[i]) + (i == 1 ? feed : std::string()));
    }
    line("G1 " + xy(c.entry.path.front()) + " (closed)");
    for (std::size_t i = 0; i < c.entry.overcut.size(); ++i)
      line("G1 " + xy(c.entry.overcut[i]) + (i == 0 ? " (lead-out)" : ""));
    line("M5");
  }
  line("");
  line("M9 (assist gas off)");
  line("M2");
  line("%");
  return g;
}

}  // namespace lcnc::cut
