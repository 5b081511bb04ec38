#include "machine/config_keys.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "machine/machine_config.h"

namespace lcnc {
namespace {

const std::string kSource = LCNC_SOURCE_DIR;

const char* kMinimal = R"([machine]
period_us = 75
[axes.X]
min = 0
max = 100
max_velocity = 150
max_acceleration = 1000
)";

// kMinimal with `from` replaced by `to`, parsed as m.toml.
Result<MachineConfig> parse_replaced(const std::string& from, const std::string& to) {
  std::string text = kMinimal;
  text.replace(text.find(from), from.size(), to);
  return parse_machine_config(text, "m.toml");
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// docs/machine_config.md is the table as `lasercnc config --reference`
// prints it; regenerate it with that command when a key changes.
TEST(ConfigKeys, ReferenceDocIsTheTableAsPrinted) {
  const std::string doc = slurp(kSource + "/docs/machine_config.md");
  ASSERT_FALSE(doc.empty());
  EXPECT_EQ(doc, config_reference_markdown()) << "run: lasercnc config --reference > docs/machine_config.md";
}

TEST(ConfigKeys, EveryRowSaysWhatItDoesAndWhatIsAllowed) {
  for (const MachineKey& k : machine_keys()) {
    EXPECT_FALSE(k.doc.empty()) << k.table << "." << k.name;
    EXPECT_FALSE(allowed_text(k).empty()) << k.table << "." << k.name;
    EXPECT_EQ(k.get != nullptr, !k.range.none) << k.table << "." << k.name;
  }
  for (const AxisKey& k : axis_keys()) {
    EXPECT_FALSE(k.doc.empty()) << k.table << "." << k.name;
    EXPECT_FALSE(allowed_text(k).empty()) << k.table << "." << k.name;
    EXPECT_EQ(k.get != nullptr, !k.range.none) << k.table << "." << k.name;
  }
}

TEST(ConfigKeys, ReferenceNamesEachKeyOfTheShippedMachine) {
  const std::string ref = config_reference_markdown();
  for (const char* key : {"`period_us`", "`path_tolerance_mm`", "`startup_code`", "`max_jerk`",
                          "`magnitude_bits`", "`capacity`", "`s_max`", "`max_velocity`",
                          "`home_latch_velocity`", "`values`", "`variant`", "`diameter`"})
    EXPECT_NE(ref.find(key), std::string::npos) << key;
  EXPECT_NE(ref.find("| `period_us` | number | µs | 10 … 10000 µs | 75 |"), std::string::npos) << ref;
}

// The range of a key is validate()'s alone: the same words whether the value
// came from a file (then with its line and column) or was set in code.
TEST(ConfigKeys, OneRangeCheckForAFileAndForCode) {
  auto from_file = parse_replaced("period_us = 75", "period_us = 5");
  ASSERT_FALSE(from_file);
  EXPECT_EQ(from_file.error().message, "machine.period_us = 5; allowed 10 … 10000 µs");
  EXPECT_EQ(from_file.error().line, 2u);
  EXPECT_EQ(from_file.error().col, 13u);

  auto m = parse_machine_config(kMinimal, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  m->period_ns = 5'000;
  const Status in_code = validate(*m);
  ASSERT_FALSE(in_code);
  EXPECT_EQ(in_code.error().message, from_file.error().message);
}

TEST(ConfigKeys, AnAxisRangeErrorNamesTheLineOfTheKeyAndTheAxisUnit) {
  auto m = parse_replaced("max_acceleration = 1000", "max_acceleration = -1");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().message, "axes.X.max_acceleration = -1; allowed > 0 … 10000000 mm/s²");
  EXPECT_EQ(m.error().line, 7u);
}

// A value its member cannot hold is refused with the range, not stored cut.
TEST(ConfigKeys, ANegativePeriodOrAFractionalWidthIsRefusedWithTheRange) {
  auto p = parse_replaced("period_us = 75", "period_us = -5");
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().message, "machine.period_us = -5; allowed 10 … 10000 µs");
  auto b = parse_machine_config(std::string(kMinimal) + "[dda]\nmagnitude_bits = 4.5\n", "m.toml");
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("'dda.magnitude_bits' = 4.5 must be a whole number; allowed 1 … 16"),
            std::string::npos)
      << b.error().message;
}

TEST(ConfigKeys, UnknownKeyListsTheTablesKeys) {
  auto m = parse_machine_config("[machine]\nperiod = 75\n", "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigUnknownKey);
  EXPECT_NE(m.error().message.find("unknown key 'machine.period'; expected one of: name, period_us"),
            std::string::npos)
      << m.error().message;
}

}  // namespace
}  // namespace lcnc
