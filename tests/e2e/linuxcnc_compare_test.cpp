// LaserCNC's canonical moves against LinuxCNC's own interpreter (rs274ngc,
// through linuxcnc-uspace's `gcode` module): every one of LinuxCNC's sample
// programs both accept, and the project's own, must give the same moves —
// kinds, end points and arc centres within 1e-6 mm, arc planes and turns.
// tests/e2e/compare_with_linuxcnc.py does the comparing and writes the table.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace e2e {
namespace {

const fs::path kSource = LCNC_SOURCE_DIR;
const fs::path kNcfiles = "/usr/share/linuxcnc/ncfiles";

std::string programs_under(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == ".ngc") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  std::string list;
  for (const std::string& f : files) list += " '" + f + "'";
  return list;
}

TEST(LinuxcncCanonicalMoves, TheSampleProgramsAndOursGiveLinuxCNCsMoves) {
  ASSERT_TRUE(fs::is_directory(kNcfiles)) << "linuxcnc-uspace is not installed (scripts/deps.sh)";
  const fs::path table = temp_dir() / "linuxcnc_compare.md";
  const std::string args =
      (kSource / "tests/e2e/compare_with_linuxcnc.py").string() + " " + LASERCNC_EXE + " " +
      (kSource / "tests/data/machines/ncfiles_wide.toml").string() + programs_under(kNcfiles) +
      programs_under(kSource / "tests/data/linuxcnc_compare") + " '" +
      (kSource / "share/examples/bracket.ngc").string() + "' '" +
      (kSource / "share/hal/sim/sample.ngc").string() + "' '" +
      (kSource / "tests/vectors/plate.ngc").string() + "' --at-least 164 --tool-table " +
      (kSource / "tests/data/machines/ncfiles_tools.tbl").string() + " --table " + table.string();
  const CmdResult r = run_program("/usr/bin/python3", args);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err << slurp(table);
  EXPECT_NE(r.out.find("0 differ; 0 refused by LinuxCNC alone"), std::string::npos) << r.out;
  // the programs with motion are there, compared move by move
  const std::string t = slurp(table);
  for (const char* row : {"| flowsnake.ngc | 3076 | same",
                          "| arcspiral.ngc | 1003 | same",
                          "| loops_and_subs.ngc | 65 | same",
                          "| arcs_all_planes.ngc | 16 | same",
                          "| inch_incremental.ngc | 7 | same",
                          "| bracket.ngc | 31 | same",
                          "| offsets_and_tools.ngc | 36 | same",
                          "| 3D_Chips.ngc | 4684 | same",
                          "| offsets.ngc | 5 | same",
                          "| canned_cycles.ngc | 111 | same",
                          "| polar_coordinates.ngc | 23 | same",
                          "| hole-circle.ngc | 20 | same",
                          "| spiral.ngc | 804 | same",
                          "| tort.ngc | 268 | same",
                          "| cutter_comp.ngc | 67 | same",
                          "| comp.ngc | 45 | same",
                          "| useful-subroutines.ngc | 60 | same",
                          "| toplevel.ngc | 1 | same",
                          "| gmoccapy_2_tools_with_cutter_radius_compensation.ngc | 15 | same",
                          "| spiral_arcs.ngc | 17 | same",
                          "| override_switches.ngc | 10 | same"}) {
    EXPECT_NE(t.find(row), std::string::npos) << row << "\n" << t;
  }
}

}  // namespace
}  // namespace e2e
