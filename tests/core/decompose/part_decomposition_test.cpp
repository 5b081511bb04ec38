// A whole part's work bounds: what would take gigabytes (a drawing read in
// the wrong units, a contour speed no pair of axis groups reaches) is
// refused before anything is allocated, with what is wrong and what is
// allowed.
#include "decompose/part_decomposition.h"

#include <gtest/gtest.h>

#include "core/dxf/dxf_test_util.h"
#include "dxf/contour_chain.h"
#include "dxf/dxf_reader.h"

namespace lcnc::decompose {
namespace {

const std::string kMetres = std::string(LCNC_SOURCE_DIR) + "/tests/data/dxf/plate_in_metres.dxf";

TEST(PartDecomposition, APartReadInMetresIsRefusedByItsEstimatedPoints) {
  const dxf::Drawing d = test::read_ok(kMetres);
  ASSERT_DOUBLE_EQ(d.unit_mm, 1000.0);
  Result<std::vector<dxf::Contour>> cs = dxf::chain_contours(d);
  ASSERT_TRUE(cs.ok()) << cs.error().to_string();
  const Status s = check_part_size(d, *cs, 0.01);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::DecomposeTooLarge);
  const std::string& m = s.error().message;
  EXPECT_NE(m.find("71.3 M points"), std::string::npos) << m;
  EXPECT_NE(m.find("more than the 2.0 M allowed"), std::string::npos) << m;
  EXPECT_NE(m.find("$INSUNITS"), std::string::npos) << m;
  EXPECT_NE(m.find("(1000 mm per unit)"), std::string::npos) << m;
  EXPECT_EQ(s.error().file, kMetres);
  // prepare_part stops there, before discretizing
  Result<PreparedPart> p = prepare_part(d, 0.01);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::DecomposeTooLarge);
}

TEST(PartDecomposition, TheSamePartInMillimetresIsWithinTheBound) {
  dxf::ReadOptions mm;
  mm.unit_mm = 1.0;
  Result<dxf::ReadResult> r = dxf::read_dxf_file(kMetres, mm);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  Result<std::vector<dxf::Contour>> cs = dxf::chain_contours(r->drawing);
  ASSERT_TRUE(cs.ok());
  EXPECT_TRUE(check_part_size(r->drawing, *cs, 0.01).ok());
  // the bound is on points: a step 50 times finer passes it
  const Status fine = check_part_size(r->drawing, *cs, 0.0002);
  EXPECT_FALSE(fine.ok());
}

TEST(PartDecomposition, ASyncSpeedBeyondBothGroupsTogetherIsRefusedBeforeAnyWork) {
  Options o;
  o.speed_mm_s = o.main_speed_mm_s + o.aux_speed_mm_s;
  EXPECT_TRUE(check_options(o).ok());
  o.speed_mm_s *= 1.001;
  const Status s = check_options(o);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::DecomposeInfeasible);
  EXPECT_NE(s.error().message.find("reach together"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("340.00 m/min"), std::string::npos) << s.error().message;
  // the paper's mode keeps no limit (it reports them): any positive speed
  o.mode = Mode::Seed;
  EXPECT_TRUE(check_options(o).ok());
}

}  // namespace
}  // namespace lcnc::decompose
