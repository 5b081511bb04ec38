// End-to-end: `lasercnc cut` on the shipped sample plate — the G-code it
// writes is parsed back and measured against the drawing (holes first,
// every cut point kerf/2 from the drawing, pierces on the scrap side with
// lead-ins), then run by `lasercnc run`; units, bad input and the help.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cut/contour_polygon.h"
#include "cut/cut_tolerances.h"
#include "dxf/contour_chain.h"
#include "dxf/dxf_reader.h"
#include "tests/e2e/e2e_support.h"

namespace {

using e2e::kSample;
using e2e::lasercnc;
namespace fs = std::filesystem;
using Vec2 = Eigen::Vector2d;

// One contour of the program: its comment, pierce point, lead-in end and
// the points cut after it (contour, closing move and lead-out).
struct Section {
  bool hole = false;
  unsigned contour = 0;  // the drawing's contour number
  Vec2 pierce = Vec2::Zero();
  bool has_lead_in = false;
  std::vector<Vec2> cut;  // from the lead-in's end on
};

std::vector<Section> parse(const std::string& gcode, const Vec2& origin) {
  std::vector<Section> out;
  const std::regex head(R"(\(cut \d+ of \d+: (hole|outline) contour (\d+))");
  const std::regex xy(R"(X(-?[0-9.]+) Y(-?[0-9.]+))");
  std::istringstream in(gcode);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_search(l, m, head)) {
      out.emplace_back();
      out.back().hole = m[1] == "hole";
      out.back().contour = static_cast<unsigned>(std::stoul(m[2]));
      continue;
    }
    if (out.empty() || !std::regex_search(l, m, xy)) continue;
    const Vec2 p = Vec2(std::stod(m[1]), std::stod(m[2])) - origin;
    if (l.rfind("G0 ", 0) == 0) {
      out.back().pierce = p;
    } else if (l.rfind("G1 ", 0) == 0) {
      out.back().has_lead_in |= l.find("(lead-in") != std::string::npos;
      out.back().cut.push_back(p);
    }
  }
  return out;
}

// Distance from p to the nearest edge of the drawing: lines and arcs exact,
// splines through points every micrometre.
struct DrawingDistance {
  std::vector<lcnc::dxf::Edge> edges;
  std::vector<std::vector<Vec2>> spline_pts;

  explicit DrawingDistance(const std::vector<lcnc::dxf::Contour>& cs) {
    for (const auto& c : cs) {
      for (const auto& e : c.edges) {
        if (e.kind == lcnc::dxf::EdgeKind::Spline) {
          std::vector<Vec2> pts;
          const double len = lcnc::dxf::edge_length(e);
          for (double s = 0; s < len; s += 1e-3) pts.push_back(lcnc::dxf::edge_point(e, s));
          pts.push_back(e.b);
          spline_pts.push_back(std::move(pts));
        } else {
          edges.push_back(e);
        }
      }
    }
  }
  static double segment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + t * ab - p).norm();
  }
  double operator()(const Vec2& p) const {
    double d = 1e300;
    for (const auto& e : edges) {
      if (e.kind == lcnc::dxf::EdgeKind::Line) {
        d = std::min(d, segment(p, e.a, e.b));
        continue;
      }
      // arc: the circle where p's angle is within the sweep, else an end
      const double a = std::atan2(p.y() - e.center.y(), p.x() - e.center.x());
      double rel = (a - e.start_rad) * (e.sweep_rad > 0 ? 1 : -1);
      rel = std::fmod(std::fmod(rel, 2 * M_PI) + 2 * M_PI, 2 * M_PI);
      if (rel <= std::abs(e.sweep_rad)) d = std::min(d, std::abs((p - e.center).norm() - e.radius));
      d = std::min({d, (p - e.a).norm(), (p - e.b).norm()});
    }
    for (const auto& pts : spline_pts) {
      for (std::size_t i = 1; i < pts.size(); ++i) d = std::min(d, segment(p, pts[i - 1], pts[i]));
    }
    return d;
  }
};

TEST(LasercncCut, SamplePlateHolesFirstKerfOffsetLeadInsAndItRuns) {
  const fs::path dir = e2e::temp_dir();
  const fs::path ngc = dir / "plate.ngc", svg = dir / "plate.svg";
  const double kerf = 0.2;
  const Vec2 origin(10, 10);
  const e2e::CmdResult r = lasercnc("cut " + kSample + " -o " + ngc.string() + " --svg " + svg.string() +
                                    " --kerf 0.2 --feed 24000 --pierce 0.05 --power 70 --origin 10,10");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("7 contours: 1 outlines, 6 holes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("estimated time"), std::string::npos) << r.out;
  EXPECT_NE(e2e::slurp(svg).find("<svg"), std::string::npos);

  const std::vector<Section> sec = parse(e2e::slurp(ngc), origin);
  ASSERT_EQ(sec.size(), 7u);
  // holes before the outline
  for (std::size_t i = 0; i + 1 < sec.size(); ++i) EXPECT_TRUE(sec[i].hole) << i;
  EXPECT_FALSE(sec.back().hole);

  // the drawing, read back independently
  auto read = lcnc::dxf::read_dxf_file(kSample);
  ASSERT_TRUE(read.ok());
  auto contours = lcnc::dxf::chain_contours(read->drawing);
  ASSERT_TRUE(contours.ok());
  const DrawingDistance dist(*contours);

  // every cut point, and every chord's midpoint, kerf/2 from the drawing
  const double tol = lcnc::cut::kChordToleranceMm + lcnc::cut::kKerfArcToleranceMm + 1e-4;
  double worst = 0, points = 0;
  for (const Section& s : sec) {
    ASSERT_GT(s.cut.size(), 3u);
    for (std::size_t i = 0; i < s.cut.size(); ++i) {
      const double d = dist(s.cut[i]);
      EXPECT_NEAR(d, kerf / 2, tol) << "contour " << s.contour << " point " << i;
      worst = std::max(worst, std::abs(d - kerf / 2));
      ++points;
      if (i > 0) {
        const double dm = dist(0.5 * (s.cut[i] + s.cut[i - 1]));
        EXPECT_NEAR(dm, kerf / 2, tol) << "contour " << s.contour << " chord " << i;
        worst = std::max(worst, std::abs(dm - kerf / 2));
      }
    }
    // the pierce off the part on the scrap side, at the start of a lead-in
    EXPECT_TRUE(s.has_lead_in) << s.contour;
    const auto poly = lcnc::cut::contour_polygon((*contours)[s.contour - 1], 1e-3).pts;
    EXPECT_EQ(lcnc::cut::inside(s.pierce, poly), s.hole) << "contour " << s.contour;
    EXPECT_GT(dist(s.pierce), kerf / 2 + 0.5) << "contour " << s.contour;
  }
  std::printf(
      "[ measured ] %.0f cut points and chord midpoints: max |distance - kerf/2| = %.6f mm "
      "(tolerance %.4f)\n",
      points, worst, tol);

  // the machine runs it
  const e2e::CmdResult run = lasercnc("run " + ngc.string() + " --no-progress --fast");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
}

void write_file_lasercnc_cut(const fs::path& p, const char* text) {
  std::FILE* f = std::fopen(p.c_str(), "w");
  ASSERT_NE(f, nullptr) << p;
  std::fputs(text, f);
  std::fclose(f);
}

fs::path tiny_square_without_units(const fs::path& dir) {
  // 0.5 × 0.5 drawing units, no $INSUNITS: half an inch is a plausible part
  const fs::path p = dir / "tiny.dxf";
  write_file_lasercnc_cut(
      p,
      "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\nCUT\n90\n4\n70\n1\n"
      "10\n0\n20\n0\n10\n0.5\n20\n0\n10\n0.5\n20\n0.5\n10\n0\n20\n0.5\n0\nENDSEC\n0\nEOF\n");
  return p;
}

TEST(LasercncCut, MissingUnitsOnATinyPartAskForUnitsAndInchWorks) {
  const fs::path dir = e2e::temp_dir();
  const fs::path dxf = tiny_square_without_units(dir), ngc = dir / "tiny.ngc";
  e2e::CmdResult r = lasercnc("cut " + dxf.string() + " -o " + ngc.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E620"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--units"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0.5 x 0.5 mm"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ngc));
  r = lasercnc("cut " + dxf.string() + " -o " + ngc.string() + " --units inch --lead-in 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // 12.7 mm square, kerf 0.2: the path's corner sits 0.1 mm beyond x 12.7
  const std::string g = e2e::slurp(ngc);
  EXPECT_NE(g.find("X12.8000"), std::string::npos) << g;
}

TEST(LasercncCut, ProcessTableSetsTheLayersFeedPowerAndKerf) {
  const fs::path dir = e2e::temp_dir();
  const fs::path csv = dir / "steel.csv", ngc = dir / "p.ngc";
  write_file_lasercnc_cut(csv, "layer,feed_mm_min,power_pct,pierce_s,kerf_mm\nCUT,1800,95,1.2,0.3\n");
  const e2e::CmdResult r = lasercnc("cut " + kSample + " -o " + ngc.string() + " --process " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string g = e2e::slurp(ngc);
  EXPECT_NE(g.find("M3 S95\nG4 P1.2\n"), std::string::npos);
  EXPECT_NE(g.find(" F1800 (lead-in"), std::string::npos);
  EXPECT_NE(g.find("kerf 0.300 mm"), std::string::npos);
}

// A drawing in mm with the given entities.
std::string dxf_mm(const std::string& entities) {
  return "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n" + entities +
         "0\nENDSEC\n0\nEOF\n";
}

// A closed LWPOLYLINE; `bulges` (if given) per vertex.
std::string lwpoly(const std::vector<Vec2>& pts, const std::vector<std::string>& bulges = {}) {
  std::string s = "0\nLWPOLYLINE\n8\nCUT\n90\n" + std::to_string(pts.size()) + "\n70\n1\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    s += "10\n" + std::to_string(pts[i].x()) + "\n20\n" + std::to_string(pts[i].y()) + "\n";
    if (i < bulges.size()) s += "42\n" + bulges[i] + "\n";
  }
  return s;
}

// Drawings the machine cannot cut as drawn are refused before anything is
// written, saying where; entities of zero size are named, never dropped
// unsaid.
TEST(LasercncCut, CrossingTouchingAndAbsurdDrawingsAreRefusedZeroSizeOnesNamed) {
  const fs::path dir = e2e::temp_dir();
  const fs::path ngc = dir / "out.ngc";
  auto cut = [&](const std::string& name, const std::string& text) {
    write_file_lasercnc_cut(dir / name, text.c_str());
    return lasercnc("cut " + (dir / name).string() + " -o " + ngc.string());
  };
  // the bow tie: one lobe only was cut before
  e2e::CmdResult r = lasercnc("cut " + std::string(LCNC_SOURCE_DIR) +
                              "/tests/data/dxf/crossing_self.dxf -o " + ngc.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E604"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("crosses itself at (5.000, 5.000)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ngc));
  // a figure 8 pinched at one vertex: touches, does not cross
  r = cut("eight.dxf", dxf_mm(lwpoly({{0, 0}, {10, 5}, {20, 0}, {20, 10}, {10, 5}, {0, 10}})));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("eight.dxf:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("touches itself at (10.000, 5.000)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ngc));
  // a notch whose two sides touch along a stretch (collinear overlap)
  r = cut("notch.dxf", dxf_mm(lwpoly({{0, 0}, {30, 0}, {30, 20}, {20, 20}, {20, 5}, {20, 12}, {0, 12}})));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E604"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ngc));
  // a bulge of 1e300 is no arc: it was cut as a straight edge
  r = cut("bulge.dxf", dxf_mm(lwpoly({{0, 0}, {20, 0}, {20, 20}, {0, 20}}, {"0", "1e300"})));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bulge.dxf:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("vertex 2 has bulge 1e+300"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(ngc));
  // a line of zero length and a polyline folded onto one point: said, then
  // the square is cut
  r = cut("dots.dxf",
          dxf_mm(lwpoly({{0, 0}, {20, 0}, {20, 20}, {0, 20}}) +
                 "0\nLINE\n8\nCUT\n10\n40\n20\n5\n11\n40\n21\n5\n" + lwpoly({{50, 5}, {50, 5}, {50, 5}})));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("warning: 2 entities of zero length, not cut: LINE at DXF line"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("LWPOLYLINE at DXF line"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(ngc));
}

TEST(LasercncCut, BadInputNamesWhereAndBadCommandLinesExit2) {
  const fs::path dir = e2e::temp_dir();
  const fs::path csv = dir / "bad.csv", ngc = dir / "x.ngc";
  write_file_lasercnc_cut(csv, "# table\nCUT,1800,150,1.2,0.3\n");
  e2e::CmdResult r = lasercnc("cut " + kSample + " -o " + ngc.string() + " --process " + csv.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(csv.string() + ":2: error E622"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("power 150"), std::string::npos) << r.err;
  r = lasercnc("cut " + kSample + " -o " + ngc.string() + " --kerf 30");
  EXPECT_EQ(r.exit_code, 2);
  r = lasercnc("cut " + kSample + " -o " + ngc.string() + " --kerf 6");  // the 5 mm holes vanish
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E621"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("vanishes"), std::string::npos) << r.err;
  r = lasercnc("cut " + kSample);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing -o"), std::string::npos) << r.err;
  r = lasercnc("cut " + kSample + " -o " + kSample);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(ngc));
  r = lasercnc("cut --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"-o ", "--svg", "--process", "--feed", "--power", "--pierce", "--kerf", "--lead-in",
                          "--lead-out", "--direction", "--units", "--origin"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
  EXPECT_NE(lasercnc("--help").out.find("lasercnc cut PART.dxf"), std::string::npos);
}

}  // namespace
