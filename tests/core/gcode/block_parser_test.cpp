// The block parser alone: words, codes by group, spans, numbers.
#include "gcode/block_parser.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

#include "support/test_scale.h"

namespace lcnc::gcode {
namespace {

constexpr std::uint8_t kAllAxes = 0x3F;

TEST(GcodeBlockParser, SortsCodesIntoGroupsAndKeepsWordSpans) {
  BlockParser p(kAllAxes);
  Block b;
  ASSERT_TRUE(p.parse("n5 g90 g1 x 1 0 y-2.5 f600 m3 s50 m8 (c) ; rest", b)) << p.fault().message;
  EXPECT_FALSE(b.empty);
  EXPECT_EQ(b.code(GGroup::Distance), 900);
  EXPECT_EQ(b.code(GGroup::Motion), 10);
  EXPECT_EQ(b.code(GGroup::Plane), -1);
  EXPECT_EQ(b.m_laser, 3);
  EXPECT_TRUE(b.m8);
  EXPECT_FALSE(b.m7);
  EXPECT_TRUE(b.has('X'));
  EXPECT_TRUE(b.has('F'));
  EXPECT_FALSE(b.has('Z'));
  EXPECT_DOUBLE_EQ(b['X'], 10.0);
  EXPECT_DOUBLE_EQ(b['Y'], -2.5);
  EXPECT_EQ(b.axis_mask, 0x03);
  EXPECT_EQ(p.text().text(b.span('X')), "X10");
  EXPECT_EQ(p.text().byte_pos(b.span('X')), 10u);  // the 'x' as written
  EXPECT_EQ(p.text().text(b.first_axis_word), "X10");
}

TEST(GcodeBlockParser, DecimalGCodesAreTenths) {
  BlockParser p(kAllAxes);
  Block b;
  ASSERT_TRUE(p.parse("G61.1 G90.1 G59", b));
  EXPECT_EQ(b.code(GGroup::PathControl), 611);
  EXPECT_EQ(b.code(GGroup::ArcDistance), 901);
  EXPECT_EQ(b.code(GGroup::CoordSystem), 590);
  EXPECT_EQ(g_code_name(611), "G61.1");
  EXPECT_EQ(g_code_name(10), "G1");
}

TEST(GcodeBlockParser, BlankCommentPercentAndDeleteLines) {
  BlockParser p(kAllAxes);
  Block b;
  ASSERT_TRUE(p.parse("   \t ", b));
  EXPECT_TRUE(b.empty);
  ASSERT_TRUE(p.parse("(only a comment) ; and more", b));
  EXPECT_TRUE(b.empty);
  ASSERT_TRUE(p.parse(" % ", b));
  EXPECT_TRUE(b.percent);
  ASSERT_TRUE(p.parse("/ G0 X1", b));
  EXPECT_TRUE(b.block_delete);
  EXPECT_FALSE(b.empty);
}

TEST(GcodeBlockParser, ReusedBlockForgetsThePreviousLine) {
  BlockParser p(kAllAxes);
  Block b;
  ASSERT_TRUE(p.parse("G2 X1 Y1 I1 M3 M7", b));
  ASSERT_TRUE(p.parse("G0 Z1", b));
  EXPECT_FALSE(b.has('X'));
  EXPECT_FALSE(b.has('I'));
  EXPECT_EQ(b.m_laser, -1);
  EXPECT_FALSE(b.m7);
  EXPECT_EQ(b.axis_mask, 0x04);
}

TEST(GcodeBlockParser, AbsentAxisIsRejectedWithItsColumn) {
  BlockParser p(0x2F);  // no B
  Block b;
  EXPECT_FALSE(p.parse("G0  B1", b));
  EXPECT_EQ(p.fault().code, ErrorCode::GcodeNoSuchAxis);
  EXPECT_EQ(p.fault().byte_pos, 4u);
}

// Fixed-seed property test: every number form reads as strtod reads it.
// LCNC_TEST_SCALE multiplies the case count for long runs.
TEST(GcodeBlockParser, NumbersReadExactlyAsStrtod) {
  const int cases = testing::scaled(20000);
  std::mt19937_64 rng(20240611);
  std::uniform_int_distribution<int> digit(0, 9);
  std::uniform_int_distribution<int> count(0, 20);
  std::uniform_int_distribution<int> form(0, 5);
  BlockParser p(kAllAxes);
  Block b;
  for (int i = 0; i < cases; ++i) {
    std::string num;
    const int f = form(rng);
    if (f == 1) num += '-';
    if (f == 2) num += '+';
    const int int_digits = count(rng);
    const int frac_digits = (f == 3) ? 0 : count(rng);
    for (int d = 0; d < int_digits; ++d) num += static_cast<char>('0' + digit(rng));
    if (f != 3 || int_digits == 0) num += '.';
    for (int d = 0; d < frac_digits; ++d) num += static_cast<char>('0' + digit(rng));
    if (int_digits == 0 && frac_digits == 0) num += '5';
    ASSERT_TRUE(p.parse("X" + num, b)) << num << ": " << p.fault().message;
    const double expected = std::strtod(num.c_str(), nullptr);
    ASSERT_EQ(b['X'], expected) << num;
  }
}

}  // namespace
}  // namespace lcnc::gcode
