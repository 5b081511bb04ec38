// The hole record's field table: one well-formed entry per field, and every
// reader of it (validate(), the CSV) uses its names and ranges — the beam
// offset included, whose range once differed from place to place.
#include "holes/hole_fields.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "holes/hole_table.h"

namespace lcnc {
namespace {

// The record's defaults are a valid helix.
HoleProcessParams good() {
  HoleProcessParams p;
  p.hole_number = 4;
  return p;
}

TEST(HoleFields, OneEntryPerFieldInOrderWithDistinctNames) {
  std::set<std::string_view> columns, registers;
  for (std::size_t i = 0; i < kHoleFields.size(); ++i) {
    const HoleField& f = kHoleFields[i];
    EXPECT_EQ(f.number, static_cast<int>(i) + 1);
    EXPECT_TRUE(columns.insert(f.column).second) << f.column;
    EXPECT_TRUE(registers.insert(f.register_name).second) << f.register_name;
    EXPECT_LT(f.lo, f.hi) << f.column;
    EXPECT_FALSE(f.label.empty());
    EXPECT_EQ(hole_field_by_column(f.column), i);
    EXPECT_EQ(hole_field_by_register(f.register_name), i);
  }
  EXPECT_FALSE(hole_field_by_column("shape").has_value());
}

TEST(HoleFields, GetAndSetReachTheirMember) {
  HoleProcessParams p = good();
  for (const HoleField& f : kHoleFields) {
    const double v = f.type == HoleFieldType::Real ? f.hi / 2 + 0.25 : f.hi;
    f.set(p, v);
    EXPECT_EQ(f.get(p), v) << f.column;
  }
  EXPECT_EQ(p.position[4], 0.0);  // B is not a field
  EXPECT_EQ(p.head.beam_offset_mm, 1.25);
  EXPECT_EQ(p.process, HoleProcessId::FreeShape);
}

// validate() refuses just outside each end of every field's range, naming
// the field, and takes both ends themselves (the open ones excepted).
TEST(HoleFields, ValidateChecksEveryFieldAgainstTheTable) {
  for (const HoleField& f : kHoleFields) {
    for (const double v : {f.lo - 1, f.hi + 1}) {
      HoleProcessParams p = good();
      f.set(p, v);
      if (f.type != HoleFieldType::Real && v < 0) continue;  // counts cannot hold it
      const Status s = validate(p);
      ASSERT_FALSE(s.ok()) << f.column << " = " << v;
      const std::string want = "field " + std::to_string(f.number) + " " + std::string(f.label) + " = ";
      EXPECT_NE(s.error().message.find(want), std::string::npos) << s.error().message;
    }
  }
  HoleProcessParams p = good();
  p.head.beam_offset_mm = kMaxBeamOffsetMm;
  EXPECT_TRUE(validate(p).ok());
  p.head.beam_offset_mm = -kMaxBeamOffsetMm;
  EXPECT_TRUE(validate(p).ok());
  p.head.beam_offset_mm = 2.5;
  const Status s = validate(p);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("hole 4: field 17 beam offset = 2.5 mm; allowed -2 … 2 mm"),
            std::string::npos)
      << s.error().message;
}

TEST(HoleFields, TheCsvHeaderIsTheTableThenTheShape) {
  const std::string csv = write_hole_table({good()});
  std::string header;
  for (const HoleField& f : kHoleFields) header += std::string(f.column) + ",";
  EXPECT_EQ(csv.substr(0, csv.find('\n')), header + "shape");
  HoleProcessParams p = good();
  p.head.beam_offset_mm = 5.0;  // beyond the head's reach
  const auto t = parse_hole_table(write_hole_table({p}), "h.csv");
  ASSERT_FALSE(static_cast<bool>(t));
  EXPECT_NE(t.error().message.find("field 17 beam offset = 5 mm"), std::string::npos) << t.error().message;
}

}  // namespace
}  // namespace lcnc

namespace lcnc {
namespace {

// What `lasercnc drill` and the HMI's adjust screen write to the head: the
// six registers of fields 12–17, named as the table's columns, in order.
TEST(HoleFields, TheScanHeadBlockIsFields12To17InOrder) {
  ScanHeadParams h;
  h.start_radius_mm = 1.25;
  h.end_radius_mm = 0.75;
  h.radius_turns = 4;
  h.scan_speed_mm_s = 120.0;
  h.wedge_speed_rpm = 6000.0;
  h.beam_offset_mm = -0.5;
  const std::vector<std::pair<std::string, double>> block = scan_head_block(h);
  const std::vector<std::pair<std::string, double>> expected{
      {"start_radius_mm", 1.25},  {"end_radius_mm", 0.75},     {"radius_turns", 4.0},
      {"scan_speed_mm_s", 120.0}, {"wedge_speed_rpm", 6000.0}, {"beam_offset_mm", -0.5}};
  EXPECT_EQ(block, expected);
}

}  // namespace
}  // namespace lcnc
