// Chaining entities into closed contours; open and branching chains are
// errors naming the contour, the entity and the point.
#include "dxf/contour_chain.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "core/dxf/dxf_test_util.h"

namespace lcnc::dxf {
namespace {

using test::dxf_doc;
using test::dxf_line;

Result<std::vector<Contour>> chain_text(const std::string& entities) {
  Result<ReadResult> r = read_dxf_text(dxf_doc(entities), "c.dxf");
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  if (!r.ok()) return r.error();
  return chain_contours(r->drawing);
}

TEST(ContourChain, ReversedEntitiesAreTurnedAround) {
  // A triangle drawn as three lines in mixed directions.
  Result<std::vector<Contour>> cs =
      chain_text(dxf_line(0, 0, 10, 0) + dxf_line(5, 8, 10, 0) + dxf_line(5, 8, 0, 0));
  ASSERT_TRUE(cs.ok());
  ASSERT_EQ(cs->size(), 1u);
  const Contour& c = (*cs)[0];
  ASSERT_EQ(c.edges.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(c.edges[i].b, c.edges[(i + 1) % 3].a) << "edge " << i;
  }
  EXPECT_EQ(c.index, 1u);
  EXPECT_EQ(c.first_kind, EntityKind::Line);
}

TEST(ContourChain, GapsBelowTheJoinToleranceClose) {
  Result<std::vector<Contour>> cs =
      chain_text(dxf_line(0, 0, 10, 0) + dxf_line(10.0004, 0, 10, 10) + dxf_line(10, 10, 0, 0.0003));
  ASSERT_TRUE(cs.ok()) << cs.error().to_string();
  EXPECT_EQ(cs->size(), 1u);
}

TEST(ContourChain, OpenContourNamesTheContourAndThePoint) {
  Result<ReadResult> r = read_dxf_file(test::dxf_data("open_contour.dxf"));
  ASSERT_TRUE(r.ok());
  Result<std::vector<Contour>> cs = chain_contours(r->drawing);
  ASSERT_FALSE(cs.ok());
  const Diagnostic& e = cs.error();
  EXPECT_EQ(e.code, ErrorCode::DxfOpenContour);
  EXPECT_EQ(e.line, 51u);  // the last LINE, whose end is free
  EXPECT_MENTIONS(e, "contour 1 (LINE at DXF line 19, layer CUT) is open");
  EXPECT_MENTIONS(e, "ends at (0.000, 10.000)");
  EXPECT_MENTIONS(e, "starts at (0.000, 0.000)");
}

TEST(ContourChain, GapAboveTheJoinToleranceIsOpen) {
  Result<std::vector<Contour>> cs =
      chain_text(dxf_line(0, 0, 10, 0) + dxf_line(10.002, 0, 10, 10) + dxf_line(10, 10, 0, 0));
  ASSERT_FALSE(cs.ok());
  EXPECT_MENTIONS(cs.error(), "is open");
}

TEST(ContourChain, ThreeEndsAtOnePointBranch) {
  Result<ReadResult> r = read_dxf_file(test::dxf_data("branch.dxf"));
  ASSERT_TRUE(r.ok());
  Result<std::vector<Contour>> cs = chain_contours(r->drawing);
  ASSERT_FALSE(cs.ok());
  EXPECT_EQ(cs.error().code, ErrorCode::DxfOpenContour);
  EXPECT_MENTIONS(cs.error(), "branches at (10.000, 0.000)");
}

TEST(ContourChain, ContoursAreNumberedInDrawingOrder) {
  Result<std::vector<Contour>> cs = chain_text(test::dxf_circle(50, 50, 5) + dxf_line(0, 0, 10, 0) +
                                               dxf_line(10, 0, 0, 10) + dxf_line(0, 10, 0, 0));
  ASSERT_TRUE(cs.ok());
  ASSERT_EQ(cs->size(), 2u);
  EXPECT_EQ((*cs)[0].first_kind, EntityKind::Circle);
  EXPECT_EQ((*cs)[1].index, 2u);
  EXPECT_EQ((*cs)[1].name().rfind("contour 2 (LINE at DXF line", 0), 0u) << (*cs)[1].name();
}

}  // namespace
}  // namespace lcnc::dxf
