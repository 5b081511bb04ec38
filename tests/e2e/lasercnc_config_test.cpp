// `lasercnc config --reference`: the machine config's keys as Markdown, the
// same text as docs/machine_config.md.
#include <gtest/gtest.h>

#include "e2e_support.h"

namespace {

using namespace e2e;

TEST(LasercncConfig, ReferencePrintsTheDocsFile) {
  const CmdResult r = lasercnc("config --reference");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, slurp(fs::path(LCNC_SOURCE_DIR) / "docs" / "machine_config.md"));
  EXPECT_NE(r.out.find("### `[axes.<L>]`"), std::string::npos);
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(LasercncConfig, WithoutReferenceIsAUsageError) {
  const CmdResult r = lasercnc("config");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("config takes --reference"), std::string::npos) << r.err;
}

}  // namespace
