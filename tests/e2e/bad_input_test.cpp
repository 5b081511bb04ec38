// Every program, every kind of bad input: a clear error on stderr that says
// where (file:line:col, or the option) and what, and a non-zero exit — 2 for
// a usage error, 1 for bad input — before anything moves or is written.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "e2e_support.h"

namespace {

using namespace e2e;

struct Case {
  const char* what;
  std::string exe;
  std::string args;
  int exit_code;
  std::string says;  // a part of stderr
};

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
}

TEST(BadInput, EveryProgramRefusesItWithWhereAndWhatAndANonZeroExit) {
  const std::string S = LCNC_SOURCE_DIR;
  const std::string bad_ngc = write("bad.ngc", "G21 G90\nG1 X10 F100 Q\n").string();
  const std::string bad_toml = write("bad.toml", "[machine]\nname = \"x\"\nperiod_us = -5\n").string();
  const std::string bad_csv = write("bad.csv", "hole,x_mm\n1,abc\n").string();
  const std::string bad_map = write("bad_map.toml", "version = 1\n[devices.x]\nunit_id = 900\n").string();
  const std::string out = (temp_dir() / "never.csv").string();
  const std::vector<Case> cases = {
      {"G-code with a bad word", LASERCNC_EXE, "run " + bad_ngc, 1, "bad.ngc:2:13: error E202"},
      {"G-code that is not there", LASERCNC_EXE, "run /nonexistent.ngc", 1, "E101"},
      {"G-code checked", LASERCNC_EXE, "check " + bad_ngc, 1, "bad.ngc:2:13"},
      {"machine config out of range", LASERCNC_EXE,
       "run " + S + "/share/examples/bracket.ngc --machine " + bad_toml, 1, "bad.toml:3:13: error E112"},
      {"DXF with a bad number", LASERCNC_EXE,
       "decompose " + S + "/tests/data/dxf/bad_number.dxf --csv " + out, 1, "bad_number.dxf:"},
      {"DXF that is no DXF", LASERCNC_EXE, "decompose " + S + "/tests/data/dxf/not_dxf.dxf --csv " + out, 1,
       "not_dxf.dxf"},
      {"hole table with a bad number", LASERCNC_EXE, "drill " + bad_csv, 1, "bad.csv:"},
      {"unknown command", LASERCNC_EXE, "fly", 2, "usage"},
      {"feed override out of range", LASERCNC_EXE,
       "run " + S + "/share/examples/bracket.ngc --feed-override 900", 2, "override"},
      {"a command with no daemon", LASERCNC_EXE, "send start --shm /lcnc_bad_input_none", 1,
       "E417 (RtShmLink): shared memory '/lcnc_bad_input_none': cannot open (is lasercncd running?)"},
      {"daemon: machine config out of range", LASERCNCD_EXE,
       "--machine " + bad_toml + " --shm /lcnc_bad_input_d", 1, "bad.toml:3:13: error E112"},
      {"daemon: bad Modbus endpoint", LASERCNCD_EXE, "--modbus bogus:1 --shm /lcnc_bad_input_d", 2,
       "--modbus 'bogus:1': unknown transport"},
      {"daemon: unknown option", LASERCNCD_EXE, "--frob", 2, "bad argument '--frob'"},
      {"devices: bad register map", LASERCNC_DEVICES_EXE, "--map " + bad_map + " --seconds 1", 1,
       "bad_map.toml"},
      {"devices: unknown option", LASERCNC_DEVICES_EXE, "--frob", 2, "unknown argument '--frob'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const CmdResult r = run_program(c.exe, c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_FALSE(fs::exists(out));  // nothing written for a drawing refused
}

}  // namespace
