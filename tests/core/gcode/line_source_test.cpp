// Line splitting from memory and from files larger than one read chunk.
#include "gcode/line_source.h"

#include "gcode/gcode_tolerances.h"

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

TEST(GcodeLineSource, LoneCarriageReturnEndsALine) {
  LineSource mac("G1 X1\rG1 X2\r");
  EXPECT_EQ(all_lines(mac), (std::vector<std::string>{"G1 X1", "G1 X2"}));
  // CRLF is one line end; a CR before it, or alone, one more
  LineSource mixed("a\rb\r\nc\n\r\r\nd\r");
  EXPECT_EQ(all_lines(mixed), (std::vector<std::string>{"a", "b", "c", "", "", "d"}));
}

std::vector<std::string> file_lines(const std::string& text, const std::string& name) {
  const std::string path = ::testing::TempDir() + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  EXPECT_NE(f, nullptr);
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  std::string why;
  auto src = LineSource::open_file(path, why);
  EXPECT_NE(src, nullptr) << why;
  std::vector<std::string> lines = src ? all_lines(*src) : std::vector<std::string>{};
  std::remove(path.c_str());
  return lines;
}

TEST(GcodeLineSource, LineEndSplitBetweenReadChunksIsOneLineEnd) {
  // CR as the last byte of the first read chunk; LF (or not) the first of the next
  std::string text;
  while (text.size() < LineSource::kChunkBytes - 10) text += "G1 X1\n";
  text.resize(LineSource::kChunkBytes - 1, 'x');
  std::string lone = text + "\rb\r";
  std::string pair = text + "\r\nb\r";
  const auto lone_lines = file_lines(lone, "split_lone_cr.ngc");
  const auto pair_lines = file_lines(pair, "split_cr_lf.ngc");
  LineSource lone_mem(lone);
  LineSource pair_mem(pair);
  EXPECT_EQ(lone_lines, all_lines(lone_mem));
  EXPECT_EQ(pair_lines, all_lines(pair_mem));
  EXPECT_EQ(lone_lines, pair_lines);
  ASSERT_FALSE(lone_lines.empty());
  EXPECT_EQ(lone_lines.back(), "b");
}

TEST(GcodeLineSource, LineLongerThanTheBoundStopsReading) {
  LineSource src("G0\n" + std::string(kMaxLineBytes + 1, 'x') + "\nG1\n");
  std::string_view l;
  ASSERT_TRUE(src.next(l));
  EXPECT_EQ(l, "G0");
  EXPECT_FALSE(src.next(l));
  EXPECT_TRUE(src.too_long());
  EXPECT_FALSE(src.next(l));  // and stays stopped
  LineSource at_bound(std::string(kMaxLineBytes, 'x') + "\r\n");
  ASSERT_TRUE(at_bound.next(l));
  EXPECT_EQ(l.size(), kMaxLineBytes);
  EXPECT_FALSE(at_bound.too_long());
}

TEST(GcodeLineSource, FileWithoutLineEndsFailsWithinItsReadBuffer) {
  // 10 MB and no '\n': the source gives up after the bound and never grows
  // its buffer past one chunk.
  const std::string path = ::testing::TempDir() + "line_source_no_line_end.ngc";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  const std::string block(1u << 20, 'x');
  for (int i = 0; i < 10; ++i) std::fwrite(block.data(), 1, block.size(), f);
  std::fclose(f);
  std::string why;
  auto src = LineSource::open_file(path, why);
  ASSERT_NE(src, nullptr) << why;
  std::string_view l;
  EXPECT_FALSE(src->next(l));
  EXPECT_TRUE(src->too_long());
  EXPECT_TRUE(src->read_error().empty());
  EXPECT_LE(src->buffer_bytes(), LineSource::kChunkBytes);
  std::remove(path.c_str());
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
  for (int i = 0; i < 50000; ++i) text += "G1 X" + std::to_string(i) + (i % 2 ? "\r" : "\r\n");
  text += std::string(kMaxLineBytes, 'z');  // a last line as long as allowed, no line end
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
