// End to end: `lasercnc decompose` bounds its work before allocating. Each
// input that once took minutes and gigabytes (or aborted with bad_alloc) is
// run under a virtual-memory limit and a timeout, so a regression fails here
// instead of eating the machine, and must end with a clear error.
#include <gtest/gtest.h>

#include <string>

#include "tests/e2e/e2e_support.h"

namespace {

using e2e::kSample;

const std::string kMetres = std::string(LCNC_SOURCE_DIR) + "/tests/data/dxf/plate_in_metres.dxf";

// 512 MiB of address space and 30 s: the refusals need a few MB and well
// under a second; the old code needed 0.8 GB to several GB.
// Under AddressSanitizer the address space is its shadow's: no ulimit -v
// there (the plain build's run holds the memory bound).
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kMemoryBound = "";
#else
constexpr const char* kMemoryBound = "ulimit -v 524288 && ";
#endif

e2e::CmdResult bounded(const std::string& args) {
  return e2e::run_program(std::string(kMemoryBound) + "exec timeout 30 " + LASERCNC_EXE, "decompose " + args);
}

TEST(LasercncDecomposeBounds, AHugeSpeedIsRefusedWithWhatTheAxesReach) {
  const e2e::CmdResult r = bounded(kSample + " --speed 1e6");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("E611"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reach together"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("340.00 m/min"), std::string::npos) << r.err;
}

TEST(LasercncDecomposeBounds, ASpeedAboveTheAxesIsRefusedAtOnce) {
  const e2e::CmdResult r = bounded(kSample + " --speed 1000m/min");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("E611"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1000.00 m/min"), std::string::npos) << r.err;
}

TEST(LasercncDecomposeBounds, APartWhoseHeaderSaysMetresIsRefusedByItsPoints) {
  const e2e::CmdResult r = bounded(kMetres + " --csv " + (e2e::temp_dir() / "t.csv").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("E613"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("71.3 M points"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("$INSUNITS"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(e2e::temp_dir() / "t.csv"));
  // read in mm, as drawn, the same file decomposes
  const e2e::CmdResult ok = bounded(kMetres + " --units mm --step 0.05");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(LasercncDecomposeBounds, ARunTooLongForItsPeriodsIsRefusedBeforeItStarts) {
  const e2e::CmdResult r = bounded(kSample + " --step 0.05 --speed 0.5mm/s --run --origin 200,200");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("E613"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("periods"), std::string::npos) << r.err;
}

}  // namespace
