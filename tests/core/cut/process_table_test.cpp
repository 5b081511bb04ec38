#include "cut/process_table.h"

#include <gtest/gtest.h>

namespace lcnc::cut {
namespace {

TEST(ProcessTable, RowsOverrideTheDefaultsPerLayerAndEmptyFieldsKeepThem) {
  const Process d{3000, 80, 0.5, 0.2};
  Result<ProcessTable> t = parse_process_table(
      "# steel 2 mm\nlayer,feed_mm_min,power_pct,pierce_s,kerf_mm\n\nCUT, 2400, 90, 0.8, 0.25\n"
      "ENGRAVE,6000,20,,\n",
      "p.csv", d);
  ASSERT_TRUE(t.ok()) << t.error().to_string();
  EXPECT_EQ(t->for_layer("CUT").feed_mm_min, 2400);
  EXPECT_EQ(t->for_layer("CUT").kerf_mm, 0.25);
  EXPECT_EQ(t->for_layer("ENGRAVE").power_pct, 20);
  EXPECT_EQ(t->for_layer("ENGRAVE").pierce_s, 0.5);
  EXPECT_EQ(t->for_layer("OTHER").feed_mm_min, 3000);
  EXPECT_EQ(t->for_layer("cut").feed_mm_min, 3000);  // names are case-sensitive
}

TEST(ProcessTable, ErrorsNameTheLineAndTheField) {
  const Process d;
  auto err = [&](const char* text) { return parse_process_table(text, "p.csv", d).error(); };
  Diagnostic e = err("CUT,2400,90,0.8,0.25\nCUT,1,1,1,1\n");
  EXPECT_EQ(e.line, 2u);
  EXPECT_NE(e.message.find("twice"), std::string::npos);
  e = err("# c\nCUT,fast,90,0.8,0.25\n");
  EXPECT_EQ(e.code, ErrorCode::ProcessTableSyntax);
  EXPECT_EQ(e.line, 2u);
  EXPECT_NE(e.message.find("feed_mm_min 'fast'"), std::string::npos) << e.message;
  e = err("CUT,2400,120,0.8,0.25\n");
  EXPECT_NE(e.message.find("power 120"), std::string::npos) << e.message;
  e = err("CUT,2400,90\n");
  EXPECT_NE(e.message.find("3 fields; expected 5"), std::string::npos) << e.message;
  EXPECT_EQ(e.to_string().rfind("p.csv:1: error E622", 0), 0u) << e.to_string();
}

}  // namespace
}  // namespace lcnc::cut
