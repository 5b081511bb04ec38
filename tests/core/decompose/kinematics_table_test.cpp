// The kinematics table: derived columns, CSV layout, pictures.
#include "decompose/kinematics_table.h"

#include <gtest/gtest.h>

#include <numbers>
#include <sstream>

#include "core/dxf/dxf_test_util.h"
#include "decompose/decompose_svg.h"
#include "decompose/part_decomposition.h"

namespace lcnc::decompose {
namespace {

TEST(KinematicsTable, DerivativesOfAUniformCircle) {
  // Beam on a circle of r 10 at 100 mm/s, main standing still at the centre.
  KinematicsTable t;
  const int n = 3600;
  const double r = 10, v = 100, dt = (2 * std::numbers::pi * r / n) / v;
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    t.beam.emplace_back(r * std::cos(a), r * std::sin(a));
    t.main.emplace_back(0, 0);
    t.t_s.push_back(i * dt);
  }
  fill_derivatives(t, 0.0, 0.0);
  EXPECT_NEAR(t.v_aux[100], v, 1e-3);
  EXPECT_NEAR(t.a_eff[100], v * v / r, 1.0);
  EXPECT_NEAR(t.a_aux[100], v * v / r, 1.0);
  EXPECT_EQ(t.a_main[100], 0.0);
  EXPECT_NEAR(loop_accel(t.beam, t.t_s, 0, n), v * v / r, 1.0);
}

TEST(KinematicsTable, CsvHasTheSeedColumnsAndOneRowPerPoint) {
  Result<PartResult> r = decompose_part(test::read_ok(test::dxf_data("circle.dxf")), 0.1, {});
  ASSERT_TRUE(r.ok());
  std::ostringstream out;
  write_csv(out, {&r->contours[0].table});
  std::istringstream in(out.str());
  std::string header, row;
  std::getline(in, header);
  EXPECT_EQ(header,
            "contour,i,x_mm,y_mm,p_mm,q_mm,t_s,v_main_mm_s,v_aux_mm_s,a_main_mm_s2,a_aux_mm_s2,"
            "at_main_mm_s2,at_aux_mm_s2,a_eff_mm_s2,sx_mm,sy_mm");
  std::size_t rows = 0;
  while (std::getline(in, row)) ++rows;
  EXPECT_EQ(rows, r->contours[0].table.size());
  // Row 0: main at the start point (9, 5), aux centred, time 0.
  std::istringstream first(out.str().substr(header.size() + 1));
  std::getline(first, row);
  EXPECT_EQ(row.rfind("1,0,9.000000,5.000000,0.000000,0.000000,0.000000000,", 0), 0u) << row;
}

TEST(DecomposeSvg, DrawsSGreenS1BlueS2Red) {
  Options o;
  Result<PartResult> r = decompose_part(test::read_ok(test::dxf_data("arc_slot.dxf")), 0.05, o);
  ASSERT_TRUE(r.ok());
  const std::string svg = paths_svg(*r, o, "slot <test>");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("stroke=\"green\""), std::string::npos);
  EXPECT_NE(svg.find("stroke=\"blue\""), std::string::npos);
  EXPECT_NE(svg.find("stroke=\"red\""), std::string::npos);
  EXPECT_NE(svg.find("slot &lt;test&gt;"), std::string::npos);
  const std::string acc = accel_svg(*r, o, "slot");
  EXPECT_NE(acc.find("effective (beam)"), std::string::npos);
  EXPECT_NE(acc.find("stroke-dasharray"), std::string::npos);  // the limit
}

}  // namespace
}  // namespace lcnc::decompose
