// The machine config's [kinematics]: the variant and offsets that the 5-axis
// kinematics use, checked like every other key.
#include <gtest/gtest.h>

#include <string>

#include "kinematics/five_axis.h"
#include "machine/machine_config.h"

namespace lcnc {
namespace {

const char* kAxis = "[axes.X]\nmin = 0\nmax = 100\nmax_velocity = 10\nmax_acceleration = 100\n";

TEST(KinematicsConfig, AbsentMeansTheDefaultHeadHeadGeometry) {
  auto m = parse_machine_config(kAxis, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->kinematics.variant, MachineVariant::HeadHead);
  EXPECT_EQ(m->kinematics.head_pivot_length_mm, FiveAxisGeometry{}.head_pivot_length_mm);
}

TEST(KinematicsConfig, VariantAndOffsetsAreRead) {
  const std::string text = std::string(kAxis) +
                           "[kinematics]\nvariant = \"table_table\"\n"
                           "table_a_pivot_mm = [400, 200, 80.5]\ntable_c_offset_mm = [0, 0, 30]\n"
                           "head_pivot_length_mm = 95\n";
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->kinematics.variant, MachineVariant::TableTable);
  EXPECT_EQ(m->kinematics.table_a_pivot_mm, Vec3(400, 200, 80.5));
  EXPECT_EQ(m->kinematics.table_c_offset_mm, Vec3(0, 0, 30));
  EXPECT_EQ(m->kinematics.head_pivot_length_mm, 95.0);
  // the kinematics the machine builds use them: at A = C = 0 the table's
  // workpiece origin is the pivot plus the offset
  const FiveAxisKinematics kin = kinematics_from(*m);
  EXPECT_EQ(kin.geometry().variant, MachineVariant::TableTable);
  const ToolPose tp = kin.forward((Pose() << 400, 200, 110.5, 0, 0, 0).finished());
  EXPECT_NEAR(tp.tip_mm.norm(), 0.0, 1e-9);
}

TEST(KinematicsConfig, TheDefaultMachineSaysHeadHead) {
  auto m = load_machine_config(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->kinematics.variant, MachineVariant::HeadHead);
  EXPECT_EQ(m->kinematics.head_c_to_a_mm, Vec3(0, 0, -80));
}

struct BadCase {
  const char* text;
  ErrorCode code;
  std::uint32_t line;
  const char* says;
};

class KinematicsConfigErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(KinematicsConfigErrors, NameTheKeyTheValueAndWhatIsAllowed) {
  const BadCase& b = GetParam();
  auto m = parse_machine_config(std::string(kAxis) + "[kinematics]\n" + b.text, "k.toml");
  ASSERT_FALSE(m) << b.text;
  EXPECT_EQ(m.error().code, b.code) << b.text;
  EXPECT_EQ(m.error().line, b.line) << m.error().to_string();
  EXPECT_NE(m.error().message.find(b.says), std::string::npos) << m.error().to_string();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, KinematicsConfigErrors,
    ::testing::Values(
        BadCase{"variant = \"head_table\"\n", ErrorCode::ConfigBadValue, 7,
                "allowed \"head_head\" or \"table_table\""},
        BadCase{"variant = 2\n", ErrorCode::ConfigBadValue, 7, "must be a string"},
        BadCase{"head_c_to_a_mm = [0, -80]\n", ErrorCode::ConfigBadValue, 7, "must be [x, y, z] in mm"},
        BadCase{"table_a_pivot_mm = [0, 0, \"z\"]\n", ErrorCode::ConfigBadValue, 7, "must be a number"},
        BadCase{"head_pivot_length_mm = 0\n", ErrorCode::ConfigBadValue, 7, "allowed > 0 … 10000 mm"},
        BadCase{"pivot = 3\n", ErrorCode::ConfigUnknownKey, 7, "unknown key 'kinematics.pivot'"}));

}  // namespace
}  // namespace lcnc
