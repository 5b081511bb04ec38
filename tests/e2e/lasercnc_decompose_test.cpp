// End-to-end: `lasercnc decompose` on the shipped sample part and on bad
// drawings — report, table, pictures, and the exit codes of the CLI.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tests/e2e/e2e_support.h"

namespace {

using e2e::kSample;
using e2e::lasercnc;
namespace fs = std::filesystem;

const std::string kData = std::string(LCNC_SOURCE_DIR) + "/tests/data/dxf/";

TEST(LasercncDecompose, SamplePartWritesReportTableAndPictures) {
  const fs::path dir = e2e::temp_dir();
  const fs::path csv = dir / "table.csv", svg = dir / "paths.svg", acc = dir / "accel.svg";
  const e2e::CmdResult r = lasercnc("decompose " + kSample + " --speed 6m/min --step 0.05 --csv " +
                                    csv.string() + " --svg " + svg.string() + " --accel-svg " + acc.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("7 contours"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("6.00 m/min"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("|S1 + S2 - S|"), std::string::npos) << r.out;
  // the table: the paper's columns, one row per point of every contour
  const std::string table = e2e::slurp(csv);
  std::istringstream lines(table);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header.rfind("contour,i,x_mm,y_mm,p_mm,q_mm,t_s", 0), 0u) << header;
  std::size_t rows = 0;
  for (std::string l; std::getline(lines, l);) ++rows;
  EXPECT_GT(rows, 1000u);
  // S green, S1 blue, S2 red
  const std::string paths = e2e::slurp(svg);
  EXPECT_NE(paths.find("<svg"), std::string::npos);
  EXPECT_NE(paths.find("green"), std::string::npos);
  EXPECT_NE(paths.find("blue"), std::string::npos);
  EXPECT_NE(paths.find("red"), std::string::npos);
  EXPECT_NE(e2e::slurp(acc).find("<svg"), std::string::npos);
}

TEST(LasercncDecompose, UnreachableSpeedIsRefusedWithTheHighestFeasible) {
  const e2e::CmdResult r = lasercnc("decompose " + kSample + " --speed 30m/min --step 0.05");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E611"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the highest feasible is"), std::string::npos) << r.err;
}

TEST(LasercncDecompose, OpenAndCrossingContoursNameTheContourAndNothingIsWritten) {
  const fs::path csv = e2e::temp_dir() / "never.csv";
  e2e::CmdResult r = lasercnc("decompose " + kData + "open_contour.dxf --csv " + csv.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E603"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("contour"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(csv));
  r = lasercnc("decompose " + kData + "crossing_self.dxf --csv " + csv.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E604"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(csv));
}

TEST(LasercncDecompose, MalformedDrawingNamesItsLine) {
  const e2e::CmdResult r = lasercnc("decompose " + kData + "bad_number.dxf");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad_number.dxf:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("E601"), std::string::npos) << r.err;
}

TEST(LasercncDecompose, BadOptionsAreUsageErrors) {
  EXPECT_EQ(lasercnc("decompose").exit_code, 2);
  EXPECT_EQ(lasercnc("decompose " + kSample + " --step 0.0001").exit_code, 2);
  EXPECT_EQ(lasercnc("decompose " + kSample + " --speed fast").exit_code, 2);
  EXPECT_EQ(lasercnc("decompose " + kSample + " --mode other").exit_code, 2);
  EXPECT_EQ(lasercnc("decompose " + kSample + " --run-svg x.svg").exit_code, 2);  // needs --run
  EXPECT_EQ(lasercnc("decompose " + kSample + " --run --origin 10").exit_code, 2);
}

const std::string kStarLasercncDecompose =
    std::string(LCNC_SOURCE_DIR) + "/share/examples/star_decompose.dxf";

TEST(LasercncDecompose, RunCutsThePartWithTwoAxisGroupsAndDrawsTheAxisCurves) {
  const fs::path svg = e2e::temp_dir() / "axes.svg";
  const e2e::CmdResult r = lasercnc("decompose " + kStarLasercncDecompose + " --step 0.05 --run --fast " +
                                    "--origin 200,100 --run-svg " + svg.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("main X, Y ('default'), auxiliary P, Q ('aux_stage')"), std::string::npos) << r.out;
  // on the simulated clock: nothing under-ran, no wake-up measured
  EXPECT_NE(r.out.find("simulated clock: no RT wake-up measured"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("RT wake-up p99.9"), std::string::npos) << r.out;
  // both groups exact
  const std::size_t first = r.out.find("(exact)");
  ASSERT_NE(first, std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(exact)", first + 1), std::string::npos) << r.out;
  // the beam on the contour at the same instant, to the steps' resolution
  const std::size_t at = r.out.find("at the same instant: max ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_LE(std::stod(r.out.substr(at + 25)), 0.0015) << r.out;
  const std::string pic = e2e::slurp(svg);
  EXPECT_NE(pic.find("<polyline"), std::string::npos);
  EXPECT_NE(pic.find("auxiliary P"), std::string::npos);
}

TEST(LasercncDecompose, RunBeyondTheTravelIsRefusedNamingTheContour) {
  const e2e::CmdResult r =
      lasercnc("decompose " + kStarLasercncDecompose + " --step 0.05 --run --fast --origin 995,0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("E612"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("contour"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("periods"), std::string::npos) << r.out;  // nothing ran
}

}  // namespace
