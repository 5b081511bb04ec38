// check_program: the whole-program pass before motion starts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::pose;
using test::start_at;

class GcodeCheckProgram : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    path_ = ::testing::TempDir() + "check_program_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".ngc";
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    EXPECT_NE(f, nullptr);
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
    return path_;
  }
  void TearDown() override {
    if (!path_.empty()) std::remove(path_.c_str());
  }
  std::string path_;
};

TEST_F(GcodeCheckProgram, SumsLengthsAndBoundsIncludingArcs) {
  const std::string path = write(
      "G0 X100 Y100\n"          // rapid: 90·√2
      "G1 X110 F600\n"          // 10
      "G2 X110 Y100 I-10 J0\n"  // full circle about (100, 100), r 10: 20π
      "G4 P1\n"                 // dwell: no length
      "M2\n");
  auto sum = check_program(path, test::test_machine(), start_at());
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_EQ(sum->segments, 4u);
  EXPECT_EQ(sum->lines, 5u);
  const double rapid = 90.0 * std::sqrt(2.0);
  const double circle = 20.0 * std::numbers::pi;
  EXPECT_NEAR(sum->path_length_mm, rapid + 10.0 + circle, 1e-9);
  EXPECT_NEAR(sum->feed_length_mm, 10.0 + circle, 1e-9);
  // The box includes the start and the circle's extremes (90..110 in X and Y).
  EXPECT_POSE_NEAR(sum->min, pose(10, 10, 10), 1e-9);
  EXPECT_POSE_NEAR(sum->max, pose(110, 110, 10), 1e-9);
  EXPECT_TRUE(sum->warnings.empty());
}

TEST_F(GcodeCheckProgram, HelixLengthIncludesTheNormalTravel) {
  const std::string path = write("G3 X100 Y100 Z30 I10 P2 F600\n");
  auto sum = check_program(path, test::test_machine(), start_at(100, 100, 10));
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_NEAR(sum->path_length_mm, std::hypot(10 * 4 * std::numbers::pi, 20.0), 1e-9);
  EXPECT_NEAR(sum->min[0], 100, 1e-9);
  EXPECT_NEAR(sum->max[0], 120, 1e-9);
  EXPECT_NEAR(sum->min[1], 90, 1e-9);
  EXPECT_NEAR(sum->max[1], 110, 1e-9);
  EXPECT_NEAR(sum->max[2], 30, 1e-9);
}

TEST_F(GcodeCheckProgram, ReturnsTheFirstErrorWithFileLineAndColumn) {
  const std::string path = write("G0 X20\nG1 X30\nT1\n");
  auto sum = check_program(path, test::test_machine(), start_at());
  ASSERT_FALSE(sum.ok());
  EXPECT_EQ(sum.error().code, ErrorCode::GcodeNoFeed);
  EXPECT_EQ(sum.error().file, path);
  EXPECT_EQ(sum.error().line, 2u);
  EXPECT_EQ(sum.error().col, 1u);
}

TEST_F(GcodeCheckProgram, PassesWarningsOn) {
  const std::string path = write("G0 X20\nM30\nG0 X30\n");
  auto sum = check_program(path, test::test_machine(), start_at());
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_EQ(sum->segments, 1u);
  EXPECT_EQ(sum->lines, 3u);
  ASSERT_EQ(sum->warnings.size(), 1u);
  EXPECT_EQ(sum->warnings[0].code, ErrorCode::GcodeLinesAfterEnd);
  EXPECT_EQ(sum->warnings[0].file, path);
}

TEST_F(GcodeCheckProgram, ReadsLargeProgramsAcrossBufferBoundaries) {
  // More than one 1 MiB chunk of short lines: every line counted, none split.
  std::string text = "G1 F6000\n";
  const int n = 120000;
  for (int i = 0; i < n; ++i) {
    text += (i % 2 == 0) ? "X20.125 Y30.5\n" : "X10.125 Y10.5\n";
  }
  const std::string path = write(text);
  auto sum = check_program(path, test::test_machine(), start_at());
  ASSERT_TRUE(sum.ok()) << sum.error().to_string();
  EXPECT_EQ(sum->lines, static_cast<std::uint32_t>(n + 1));
  EXPECT_EQ(sum->segments, static_cast<std::uint64_t>(n));
  EXPECT_POSE_NEAR(sum->max, pose(20.125, 30.5, 10), 1e-12);
}

TEST_F(GcodeCheckProgram, MissingFileIsFileNotFound) {
  auto sum = check_program("/nonexistent/part.ngc", test::test_machine());
  ASSERT_FALSE(sum.ok());
  EXPECT_EQ(sum.error().code, ErrorCode::FileNotFound);
}

// A file with no line ends (/dev/zero, a binary dropped in by mistake) is an
// error on its first line naming the limit, read no further than the bound.
TEST_F(GcodeCheckProgram, FileWithoutLineEndsIsAnErrorNotAnEndlessRead) {
  const std::string path = write(std::string(10u << 20, '\0'));
  auto sum = check_program(path, test::test_machine(), start_at());
  ASSERT_FALSE(sum.ok());
  EXPECT_EQ(sum.error().code, ErrorCode::GcodeSyntax);
  EXPECT_EQ(sum.error().line, 1u);
  EXPECT_NE(sum.error().message.find("longer than 65536 bytes"), std::string::npos) << sum.error().message;
}

TEST(GcodeCheckProgramDevice, DevZeroIsAnErrorOnLineOne) {
  auto sum = check_program("/dev/zero", test::test_machine(), start_at());
  ASSERT_FALSE(sum.ok());
  EXPECT_EQ(sum.error().to_string().rfind("/dev/zero:1: error E201 (GcodeSyntax): found a line "
                                          "longer than 65536 bytes",
                                          0),
            0u)
      << sum.error().to_string();
}

}  // namespace
}  // namespace lcnc
