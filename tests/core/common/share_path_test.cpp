#include "common/share_path.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

namespace lcnc {
namespace {

// The shipped files are found where the build was made from, or where
// $LASERCNC_SHARE says (an installed tree); an empty variable is unset.
TEST(SharePath, TheSourceTreeOrWhereTheEnvironmentSays) {
  ::unsetenv("LASERCNC_SHARE");
  EXPECT_TRUE(std::filesystem::exists(share_path("machines/default.toml")));
  EXPECT_TRUE(std::filesystem::exists(share_path("modbus/register_map.toml")));
  ::setenv("LASERCNC_SHARE", "/opt/lasercnc/share", 1);
  EXPECT_EQ(share_path("machines/default.toml"), "/opt/lasercnc/share/machines/default.toml");
  ::setenv("LASERCNC_SHARE", "", 1);
  EXPECT_TRUE(std::filesystem::exists(share_path("machines/default.toml")));
  ::unsetenv("LASERCNC_SHARE");
}

}  // namespace
}  // namespace lcnc
