// Crossing checks on the discretized contours: self-crossing, crossing and
// touching of two contours are errors naming both and the point; nested and
// separate contours pass.
#include "dxf/contour_check.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "core/dxf/dxf_test_util.h"
#include "dxf/contour_chain.h"

namespace lcnc::dxf {
namespace {

Status check_drawing(const Drawing& d, double step = 0.01) {
  Result<std::vector<Contour>> cs = chain_contours(d);
  EXPECT_TRUE(cs.ok());
  if (!cs.ok()) return cs.error();
  Result<std::vector<Polyline>> pl = discretize_all(*cs, step, d.file);
  EXPECT_TRUE(pl.ok());
  if (!pl.ok()) return pl.error();
  return check_crossings(*cs, *pl, d.file);
}

Status check_text(const std::string& entities) {
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(entities), "x.dxf");
  EXPECT_TRUE(r.ok());
  return r.ok() ? check_drawing(r->drawing) : Status(r.error());
}

TEST(ContourCheck, BowTieCrossesItself) {
  const Status s = check_drawing(test::read_ok(test::dxf_data("crossing_self.dxf")));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::DxfCrossing);
  EXPECT_MENTIONS(s.error(),
                  "contour 1 (LWPOLYLINE at DXF line 19, layer CUT) crosses itself at (5.000, 5.000)");
}

TEST(ContourCheck, OverlappingCirclesCrossEachOther) {
  const Status s = check_drawing(test::read_ok(test::dxf_data("crossing_mutual.dxf")));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::DxfCrossing);
  EXPECT_MENTIONS(s.error(), "contour 1 (CIRCLE at DXF line 19, layer CUT) crosses contour 2");
  // Circles r 5 about (0,0) and (8,0) meet at (4, ±3).
  EXPECT_TRUE(s.error().message.find("(4.000, 3.000)") != std::string::npos ||
              s.error().message.find("(4.000, -3.000)") != std::string::npos)
      << s.error().message;
}

TEST(ContourCheck, SquaresSharingAnEdgeTouch) {
  const Status s = check_drawing(test::read_ok(test::dxf_data("touching_squares.dxf")));
  ASSERT_FALSE(s.ok());
  EXPECT_MENTIONS(s.error(), "touches contour 1");
}

TEST(ContourCheck, NestedAndSeparateContoursPass) {
  EXPECT_TRUE(check_text(test::dxf_lwpoly({{0, 0}, {100, 0}, {100, 50}, {0, 50}}) +
                         test::dxf_circle(20, 25, 10) + test::dxf_circle(45, 25, 10) +
                         test::dxf_circle(80, 25, 0.5))
                  .ok());
  EXPECT_TRUE(check_drawing(test::read_ok(test::sample_part())).ok());
}

TEST(ContourCheck, ContoursAFewMicronsApartPass) {
  // 5 µm apart at step 1 µm.
  EXPECT_TRUE(check_drawing(test::read_ok(test::dxf_data("line_square.dxf")), 0.001).ok());
  Result<ReadResult> r =
      read_dxf_text(test::dxf_doc(test::dxf_lwpoly({{0, 0}, {10, 0}, {10, 10}, {0, 10}}) +
                                  test::dxf_lwpoly({{10.005, 0}, {20, 0}, {20, 10}, {10.005, 10}})),
                    "gap.dxf");
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(check_drawing(r->drawing, 0.001).ok());
}

TEST(ContourCheck, ContourThatTurnsBackOnItselfIsRejected) {
  // A "contour" out and back along one line: closed, but no area.
  const Status s = check_text(test::dxf_line(0, 0, 10, 0) + test::dxf_line(10, 0, 0, 0));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::DxfCrossing);
}

}  // namespace
}  // namespace lcnc::dxf
