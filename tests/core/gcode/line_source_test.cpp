// Line splitting from memory and from files larger than one read chunk.
#include "gcode/line_source.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace lcnc::gcode {
namespace {

std::vector<std::string> all_lines(LineSource& src) {
  std::vector<std::string> out;
  std::string_view l;
  while (src.next(l)) out.emplace_back(l);
  return out;
}

TEST(GcodeLineSource, SplitsOnNewlineAndDropsCarriageReturn) {
  LineSource src("a\r\nb\n\nc");
  EXPECT_EQ(all_lines(src), (std::vector<std::string>{"a", "b", "", "c"}));
}

TEST(GcodeLineSource, EmptyTextHasNoLines) {
  LineSource src("");
  EXPECT_TRUE(all_lines(src).empty());
}

TEST(GcodeLineSource, SkipsAByteOrderMarkOnlyAtTheStart) {
  LineSource src("\xEF\xBB\xBFG0\n\xEF\xBB\xBFG1\n");
  const auto lines = all_lines(src);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "G0");
  EXPECT_EQ(lines[1], "\xEF\xBB\xBFG1");
}

TEST(GcodeLineSource, FileLinesMatchMemoryLinesAcrossChunks) {
  std::string text;
  for (int i = 0; i < 200000; ++i) text += "G1 X" + std::to_string(i) + " Y1.5\n";
  text += std::string(3 << 20, 'z');  // a last line longer than a chunk, no '\n'
  const std::string path = ::testing::TempDir() + "line_source_chunks.ngc";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);

  std::string why;
  auto file = LineSource::open_file(path, why);
  ASSERT_NE(file, nullptr) << why;
  LineSource mem(text);
  EXPECT_EQ(all_lines(*file), all_lines(mem));
  std::remove(path.c_str());
}

TEST(GcodeLineSource, MissingFileSaysWhy) {
  std::string why;
  EXPECT_EQ(LineSource::open_file("/nonexistent/x.ngc", why), nullptr);
  EXPECT_FALSE(why.empty());
}

}  // namespace
}  // namespace lcnc::gcode
