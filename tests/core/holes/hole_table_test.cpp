// The process database's CSV: every field read in its unit, round trips,
// and every mistake named by file:line:col with what was expected.
#include "holes/hole_table.h"

#include <gtest/gtest.h>

#include <string>

namespace lcnc {
namespace {

const std::string kHeader =
    "hole,x_mm,y_mm,z_mm,a_deg,c_deg,feed_mm_min,layer_feed_mm,layer_count,total_depth_mm,"
    "power_pct,start_radius_mm,end_radius_mm,radius_turns,scan_speed_mm_s,wedge_speed_rpm,"
    "beam_offset_mm,process,shape\n";
const std::string kHelix = "7,100,50.5,20,-20,90,600,0.1,10,1,80,0.5,0.3,1,200,3000,0.1,helix,\n";
const std::string kShape = "8,120,50,20,0,0,300,0.1,5,0.5,90,0.5,0.5,1,100,3000,0,2,0.8@0;0.5@120;0.8@240\n";

TEST(HoleTable, ReadsEveryFieldInItsUnit) {
  std::vector<std::uint32_t> lines;
  Result<std::vector<HoleProcessParams>> t =
      parse_hole_table("# comment\n\n" + kHeader + kHelix + kShape, "holes.csv", &lines);
  ASSERT_TRUE(static_cast<bool>(t)) << t.error().to_string();
  ASSERT_EQ(t->size(), 2u);
  EXPECT_EQ(lines, (std::vector<std::uint32_t>{4, 5}));
  const HoleProcessParams& h = (*t)[0];
  EXPECT_EQ(h.hole_number, 7u);
  EXPECT_EQ(h.position[0], 100.0);
  EXPECT_EQ(h.position[1], 50.5);
  EXPECT_EQ(h.position[3], -20.0);  // A
  EXPECT_EQ(h.position[4], 0.0);    // B: not a field
  EXPECT_EQ(h.position[5], 90.0);   // C
  EXPECT_EQ(h.feed_mm_min, 600.0);
  EXPECT_EQ(h.layer_count, 10u);
  EXPECT_EQ(h.total_depth_mm, 1.0);
  EXPECT_EQ(h.power_pct, 80.0);
  EXPECT_EQ(h.head.start_radius_mm, 0.5);
  EXPECT_EQ(h.head.end_radius_mm, 0.3);
  EXPECT_EQ(h.head.beam_offset_mm, 0.1);
  EXPECT_EQ(h.process, HoleProcessId::Helix);
  const HoleProcessParams& s = (*t)[1];
  EXPECT_EQ(s.process, HoleProcessId::FreeShape);
  ASSERT_EQ(s.shape.size(), 3u);
  EXPECT_EQ(s.shape[1].radius_mm, 0.5);
  EXPECT_EQ(s.shape[1].angle_deg, 120.0);
}

TEST(HoleTable, ColumnsInAnyOrderAndShapeOptional) {
  const std::string text =
      "process,hole,x_mm,y_mm,z_mm,a_deg,c_deg,feed_mm_min,layer_feed_mm,layer_count,total_depth_mm,"
      "power_pct,start_radius_mm,end_radius_mm,radius_turns,scan_speed_mm_s,wedge_speed_rpm,beam_offset_mm\n"
      "circle,3,10,10,5,0,0,400,0.05,8,0.4,70,0.2,0.8,4,150,6000,0\n";
  Result<std::vector<HoleProcessParams>> t = parse_hole_table(text, "t.csv");
  ASSERT_TRUE(static_cast<bool>(t)) << t.error().to_string();
  EXPECT_EQ((*t)[0].hole_number, 3u);
  EXPECT_EQ((*t)[0].process, HoleProcessId::Circle);
  EXPECT_EQ((*t)[0].head.radius_turns, 4u);
}

TEST(HoleTable, WriteThenReadGivesTheSameRows) {
  Result<std::vector<HoleProcessParams>> t = parse_hole_table(kHeader + kHelix + kShape, "a.csv");
  ASSERT_TRUE(static_cast<bool>(t));
  (*t)[0].position[0] = 123.456789012345;  // needs 15 digits
  const std::string out = write_hole_table(*t);
  Result<std::vector<HoleProcessParams>> back = parse_hole_table(out, "b.csv");
  ASSERT_TRUE(static_cast<bool>(back)) << back.error().to_string() << "\n" << out;
  ASSERT_EQ(back->size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ((*back)[i].hole_number, (*t)[i].hole_number);
    EXPECT_EQ((*back)[i].position, (*t)[i].position);
    EXPECT_EQ((*back)[i].total_depth_mm, (*t)[i].total_depth_mm);
    EXPECT_EQ((*back)[i].head.end_radius_mm, (*t)[i].head.end_radius_mm);
    EXPECT_EQ((*back)[i].process, (*t)[i].process);
    EXPECT_EQ((*back)[i].shape.size(), (*t)[i].shape.size());
  }
  EXPECT_EQ(write_hole_table(*back), out);
}

struct Bad {
  const char* what;
  std::string text;
  ErrorCode code;
  const char* where;  // "file:line:col"
  const char* says;
};

class HoleTableErrors : public ::testing::TestWithParam<Bad> {};

TEST_P(HoleTableErrors, NameFileLineColumnAndWhatWasExpected) {
  const Bad& b = GetParam();
  Result<std::vector<HoleProcessParams>> t = parse_hole_table(b.text, "holes.csv");
  ASSERT_FALSE(static_cast<bool>(t)) << b.what;
  EXPECT_EQ(t.error().code, b.code) << b.what;
  const std::string s = t.error().to_string();
  EXPECT_NE(s.find(b.where), std::string::npos) << b.what << ": " << s;
  EXPECT_NE(s.find(b.says), std::string::npos) << b.what << ": " << s;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, HoleTableErrors,
    ::testing::Values(
        Bad{"bad number", kHeader + "7,1O0,50,20,0,0,600,0.1,10,1,80,0.5,0.5,1,200,3000,0,helix,\n",
            ErrorCode::HoleTableSyntax, "holes.csv:2:3", "x_mm: found '1O0'; expected a number"},
        Bad{"unknown column", "hole,x,y\n", ErrorCode::HoleTableSyntax, "holes.csv:1:6",
            "unknown column 'x'"},
        Bad{"missing column", "hole,x_mm\n", ErrorCode::HoleTableSyntax, "holes.csv:1:1",
            "lacks column 'y_mm'"},
        Bad{"short row", kHeader + "7,100,50\n", ErrorCode::HoleTableSyntax,
            "holes.csv:2:", "3 fields; expected 19"},
        Bad{"depth mismatch", kHeader + "7,100,50,20,0,0,600,0.1,10,1.2,80,0.5,0.5,1,200,3000,0,helix,\n",
            ErrorCode::HoleTableBadValue, "holes.csv:2:1", "field 10 total depth"},
        Bad{"A out of range", kHeader + "7,100,50,20,120,0,600,0.1,10,1,80,0.5,0.5,1,200,3000,0,helix,\n",
            ErrorCode::HoleTableBadValue, "holes.csv:2:1", "field 5 A = 120"},
        Bad{"duplicate", kHeader + kHelix + kHelix, ErrorCode::HoleTableDuplicate, "holes.csv:3:1",
            "hole 7 is listed twice"},
        Bad{"bad process", kHeader + "7,100,50,20,0,0,600,0.1,10,1,80,0.5,0.5,1,200,3000,0,spiral,\n",
            ErrorCode::HoleTableSyntax, "holes.csv:2:", "expected 0/helix, 1/circle or 2/free_shape"},
        Bad{"bad vertex", kHeader + "8,120,50,20,0,0,300,0.1,5,0.5,90,0.5,0.5,1,100,3000,0,2,0.8@0;x\n",
            ErrorCode::HoleTableSyntax, "holes.csv:2:", "expected radius@angle"},
        Bad{"negative count", kHeader + "7,100,50,20,0,0,600,0.1,-10,1,80,0.5,0.5,1,200,3000,0,helix,\n",
            ErrorCode::HoleTableSyntax, "holes.csv:2:", "layer_count: found '-10'"},
        Bad{"no header", "", ErrorCode::HoleTableSyntax, "holes.csv:1:1", "no header line"}));

}  // namespace
}  // namespace lcnc
