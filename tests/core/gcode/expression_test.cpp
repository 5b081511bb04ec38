// The expression reader against LinuxCNC's rules: precedence, functions in
// degrees, parameters, and an error that points where the problem is.
#include "gcode/expression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "gcode/block_parser.h"

namespace lcnc::gcode {
namespace {

class Params : public ParameterReader {
 public:
  std::map<int, double> numbered_values;
  std::map<std::string, double, std::less<>> named_values;
  [[nodiscard]] double numbered(int index) const override {
    auto it = numbered_values.find(index);
    return it == numbered_values.end() ? 0.0 : it->second;
  }
  [[nodiscard]] bool named(std::string_view name, double& out) const override {
    auto it = named_values.find(name);
    if (it == named_values.end()) return false;
    out = it->second;
    return true;
  }
};

// The line as the block parser compacts it: upper-case, no blanks.
struct Compacted {
  std::string original;
  LineText text;
  explicit Compacted(std::string line) : original(std::move(line)) {
    text.original = original;
    for (std::uint32_t i = 0; i < original.size(); ++i) {
      const char ch = original[i];
      if (ch == ' ') continue;
      text.compact.push_back(ch >= 'a' && ch <= 'z' ? static_cast<char>(ch - 'a' + 'A') : ch);
      text.offset.push_back(i);
    }
    text.size = static_cast<std::uint32_t>(text.compact.size());
  }
};

struct Eval {
  bool ok = false;
  double value = 0.0;
  std::uint32_t end = 0;
  Fault fault;
};

Eval eval(const std::string& line, const Params& p = Params{}) {
  Compacted c(line);
  ExpressionReader r(c.text, p);
  Eval e;
  std::uint32_t i = 0;
  e.ok = r.real_value(i, e.value);
  e.end = i;
  e.fault = r.fault();
  return e;
}

double value_of(const std::string& line, const Params& p = Params{}) {
  const Eval e = eval(line, p);
  EXPECT_TRUE(e.ok) << line << ": " << e.fault.message;
  return e.value;
}

TEST(Expression, PrecedenceAndLeftToRight) {
  EXPECT_DOUBLE_EQ(value_of("[1 + 2 * 3]"), 7.0);
  EXPECT_DOUBLE_EQ(value_of("[[1 + 2] * 3]"), 9.0);
  EXPECT_DOUBLE_EQ(value_of("[8 - 3 - 2]"), 3.0);
  EXPECT_DOUBLE_EQ(value_of("[8 / 4 / 2]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("[2 ** 3 ** 2]"), 64.0);  // left to right, as LinuxCNC
  EXPECT_DOUBLE_EQ(value_of("[2 * 3 ** 2]"), 18.0);
  EXPECT_DOUBLE_EQ(value_of("[1 + 2 GT 2]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("[1 LT 2 AND 3 GT 4]"), 0.0);
  EXPECT_DOUBLE_EQ(value_of("[1 LT 2 OR 3 GT 4]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("[1 XOR 1]"), 0.0);
  EXPECT_DOUBLE_EQ(value_of("[-7 MOD 3]"), 2.0);  // never negative
  EXPECT_DOUBLE_EQ(value_of("[7 MOD 3]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("-[2 + 3]"), -5.0);
  EXPECT_DOUBLE_EQ(value_of("[-2.5]"), -2.5);
}

TEST(Expression, ComparisonsWithinAMillionth) {
  EXPECT_DOUBLE_EQ(value_of("[1 EQ 1.0000005]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("[1 EQ 1.00001]"), 0.0);
  EXPECT_DOUBLE_EQ(value_of("[1 NE 1.0000005]"), 0.0);
  EXPECT_DOUBLE_EQ(value_of("[1.0000005 LE 1]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("[1 GE 1.0000005]"), 1.0);
  EXPECT_DOUBLE_EQ(value_of("[1 GT 1]"), 0.0);
}

TEST(Expression, FunctionsInDegrees) {
  EXPECT_NEAR(value_of("SIN[30]"), 0.5, 1e-15);
  EXPECT_NEAR(value_of("[COS[60] * 2]"), 1.0, 1e-15);
  EXPECT_NEAR(value_of("TAN[45]"), 1.0, 1e-15);
  EXPECT_NEAR(value_of("ASIN[0.5]"), 30.0, 1e-12);
  EXPECT_NEAR(value_of("ACOS[0]"), 90.0, 1e-12);
  EXPECT_NEAR(value_of("ATAN[1]/[-1]"), 135.0, 1e-12);
  EXPECT_DOUBLE_EQ(value_of("SQRT[16]"), 4.0);
  EXPECT_DOUBLE_EQ(value_of("ABS[-3]"), 3.0);
  EXPECT_DOUBLE_EQ(value_of("FIX[-2.5]"), -3.0);
  EXPECT_DOUBLE_EQ(value_of("FUP[2.1]"), 3.0);
  EXPECT_DOUBLE_EQ(value_of("ROUND[2.5]"), 3.0);
  EXPECT_DOUBLE_EQ(value_of("ROUND[-2.5]"), -3.0);
  EXPECT_NEAR(value_of("LN[EXP[2]]"), 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(value_of("sin[0]"), 0.0);  // lower case, as written
}

TEST(Expression, ParametersNumberedIndirectAndNamed) {
  Params p;
  p.numbered_values[1] = 2.0;
  p.numbered_values[2] = 7.5;
  p.named_values["depth"] = -1.25;
  p.named_values["_global"] = 4.0;
  EXPECT_DOUBLE_EQ(value_of("#1", p), 2.0);
  EXPECT_DOUBLE_EQ(value_of("##1", p), 7.5);  // #[#1]
  EXPECT_DOUBLE_EQ(value_of("#[#1 - 1]", p), 2.0);
  EXPECT_DOUBLE_EQ(value_of("#33", p), 0.0);         // unset: 0
  EXPECT_DOUBLE_EQ(value_of("#<Depth>", p), -1.25);  // names ignore case
  EXPECT_DOUBLE_EQ(value_of("[#<_global> * #2]", p), 30.0);
  EXPECT_DOUBLE_EQ(value_of("EXISTS[#<depth>]", p), 1.0);
  EXPECT_DOUBLE_EQ(value_of("EXISTS[#<nothing>]", p), 0.0);
  EXPECT_DOUBLE_EQ(value_of("-#2", p), -7.5);
}

TEST(Expression, StopsRightAfterItsValue) {
  const Eval e = eval("[1+2]X5");
  ASSERT_TRUE(e.ok);
  EXPECT_EQ(e.end, 5u);
}

TEST(Expression, ErrorsSayWhatAndWhere) {
  Eval e = eval("[1 + 2");
  EXPECT_FALSE(e.ok);
  EXPECT_EQ(e.fault.byte_pos, 0u);
  EXPECT_NE(e.fault.message.find("not closed"), std::string::npos) << e.fault.message;

  e = eval("[4 / [2 - 2]]");
  EXPECT_FALSE(e.ok);
  EXPECT_EQ(e.fault.code, ErrorCode::GcodeBadValue);
  EXPECT_EQ(e.fault.byte_pos, 3u);  // the '/'
  EXPECT_NE(e.fault.message.find("division by zero"), std::string::npos);

  e = eval("SQRT[-1]");
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("SQRT of a value >= 0"), std::string::npos) << e.fault.message;

  e = eval("#<undefined>");
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("#<undefined>"), std::string::npos) << e.fault.message;

  e = eval("#0");
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("from 1 to 5602"), std::string::npos) << e.fault.message;

  e = eval("[1 $ 2]");
  EXPECT_FALSE(e.ok);
  EXPECT_EQ(e.fault.byte_pos, 3u);
  EXPECT_NE(e.fault.message.find("expected an operator"), std::string::npos);

  e = eval("SINE[30]");
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("not a function"), std::string::npos);

  e = eval("[[-1] ** 0.5]");
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("non-integer power"), std::string::npos);

  e = eval("[10 ** 400]");
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("infinity"), std::string::npos) << e.fault.message;
}

TEST(Expression, DeepNestingIsAnErrorNotACrash) {
  const std::string deep = std::string(200, '[') + "1" + std::string(200, ']');
  const Eval e = eval(deep);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.fault.message.find("nested deeper"), std::string::npos) << e.fault.message;
  const std::string ok = std::string(20, '[') + "1" + std::string(20, ']');
  EXPECT_DOUBLE_EQ(value_of(ok), 1.0);
}

}  // namespace
}  // namespace lcnc::gcode
