#include "cut/cut_program.h"

#include <gtest/gtest.h>

#include "core/dxf/dxf_test_util.h"
#include "cut/contour_polygon.h"

namespace lcnc::cut {
namespace {

using test::dxf_circle;
using test::dxf_doc;
using test::dxf_lwpoly;

// A 40 × 30 plate with a round and a square hole.
dxf::Drawing plate(bool with_units = true) {
  std::string text = dxf_doc(dxf_lwpoly({{0, 0}, {40, 0}, {40, 30}, {0, 30}}) + dxf_circle(10, 15, 4) +
                             dxf_lwpoly({{25, 10}, {33, 10}, {33, 20}, {25, 20}}));
  if (!with_units) text.replace(text.find("9\n$INSUNITS\n70\n4\n"), 17, "");
  Result<dxf::ReadResult> r = dxf::read_dxf_text(text, "plate.dxf");
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  return r.ok() ? r->drawing : dxf::Drawing{};
}

TEST(CutProgram, HolesBeforeTheOutlineInTheGivenDirections) {
  for (Direction dir : {Direction::Cw, Direction::Ccw}) {
    CutOptions opt;
    opt.outer = dir;
    Result<CutPlan> plan = plan_cut(plate(), opt);
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    ASSERT_EQ(plan->contours.size(), 3u);
    EXPECT_EQ(plan->holes, 2u);
    EXPECT_EQ(plan->parts, 1u);
    EXPECT_TRUE(plan->contours[0].hole);
    EXPECT_TRUE(plan->contours[1].hole);
    EXPECT_FALSE(plan->contours[2].hole);
    for (const CutContour& c : plan->contours) {
      const bool cw = (dir == Direction::Cw) != c.hole;
      EXPECT_EQ(signed_area(c.entry.path) < 0.0, cw) << c.name;
    }
  }
}

TEST(CutProgram, PathsAreHalfTheLayerKerfFromTheDrawing) {
  CutOptions opt;
  opt.process.defaults.kerf_mm = 0.3;
  Result<CutPlan> plan = plan_cut(plate(), opt);
  ASSERT_TRUE(plan.ok()) << plan.error().to_string();
  for (const CutContour& c : plan->contours) {
    for (const Vec2& p : c.entry.path) {
      EXPECT_NEAR(distance_to(p, c.drawing), 0.15, kChordToleranceMm + kKerfArcToleranceMm);
      EXPECT_EQ(inside(p, c.drawing), c.hole) << c.name;  // on the scrap side
    }
    EXPECT_EQ(inside(c.entry.pierce, c.drawing), c.hole) << c.name;
  }
}

TEST(CutProgram, AHoleTheKerfFillsIsAnErrorNamingIt) {
  CutOptions opt;
  opt.process.defaults.kerf_mm = 9.0;  // the 8 mm round hole vanishes
  Result<CutPlan> plan = plan_cut(plate(), opt);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().code, ErrorCode::CutKerf);
  EXPECT_MENTIONS(plan.error(), "CIRCLE");
  EXPECT_MENTIONS(plan.error(), "8.000 x 8.000 mm");
  EXPECT_GT(plan.error().line, 0u);
}

TEST(CutProgram, UnitsMissingOrImplausibleAskForUnits) {
  const dxf::Drawing no_units = plate(false);
  EXPECT_FALSE(no_units.units_known);
  Status s = check_units(no_units, false);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::CutUnits);
  EXPECT_MENTIONS(s.error(), "--units");
  EXPECT_TRUE(check_units(no_units, true).ok());
  EXPECT_TRUE(check_units(plate(), false).ok());
  dxf::Drawing tiny = plate();
  for (dxf::Entity& e : tiny.entities) {
    for (dxf::Edge& ed : e.edges) {
      ed.a *= 0.01;
      ed.b *= 0.01;
      ed.center *= 0.01;
      ed.radius *= 0.01;
    }
  }
  s = check_units(tiny, false);
  ASSERT_FALSE(s.ok());
  EXPECT_MENTIONS(s.error(), "0.4 x 0.3 mm");
}

TEST(CutProgram, GcodeHasPiercesLeadInsAndTheProcessOfTheLayer) {
  CutOptions opt;
  opt.process.defaults = Process{2400, 65, 0.3, 0.2};
  opt.origin = Vec2(100, 50);
  Result<CutPlan> plan = plan_cut(plate(), opt);
  ASSERT_TRUE(plan.ok());
  const std::string g = cut_gcode(*plan, opt, "plate.dxf");
  EXPECT_NE(g.find("G21 G90 G17 G94 G64 P0.01"), std::string::npos);
  EXPECT_NE(g.find("M3 S65\nG4 P0.3\n"), std::string::npos);
  EXPECT_NE(g.find("F2400 (lead-in 2.000 mm)"), std::string::npos);
  EXPECT_NE(g.find("(cut 3 of 3: outline contour 1"), std::string::npos) << g.substr(0, 2000);
  // shifted by the origin: the first pierce of a hole is inside (100..140, 50..80)
  const std::size_t at = g.find("G0 X");
  ASSERT_NE(at, std::string::npos);
  const double x = std::stod(g.substr(at + 4)), y = std::stod(g.substr(g.find('Y', at) + 1));
  EXPECT_GT(x, 100);
  EXPECT_LT(x, 140);
  EXPECT_GT(y, 50);
  EXPECT_LT(y, 80);
  EXPECT_NE(g.find("M5\n\nM9"), std::string::npos);
}

}  // namespace
}  // namespace lcnc::cut
