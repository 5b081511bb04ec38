// End to end: the CLI's output files (common/output_file.h) — an output that is
// an input or another output is refused, a refused or failed run leaves every
// target as it was and creates nothing, a write error is an error exit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace {

using namespace e2e;

const std::string kPlate = kShare + "/examples/plate_decompose.dxf";
// A short job: a few millimetres, well inside the default machine's travel.
const std::string kProgram = "G21 G90\nG1 X2 Y1 F1200\nG1 X0 Y0\nM30\n";
const std::string kRun = " --no-progress --fast";

fs::path write_output_files(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// The names in `dir` (the CLI's own stdout/stderr captures left out).
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n != "stdout.txt" && n != "stderr.txt") names.insert(n);
  }
  return names;
}

TEST(OutputFiles, RunRefusesATraceThatIsTheProgramItselfOrALinkToIt) {
  const fs::path dir = temp_dir();
  const fs::path prog = write_output_files(dir / "p.ngc", kProgram);
  fs::create_symlink(prog, dir / "sym.ngc");
  fs::create_hard_link(prog, dir / "hard.ngc");
  for (const fs::path& trace : {prog, dir / "sym.ngc", dir / "hard.ngc", dir / "." / "p.ngc"}) {
    const CmdResult r = lasercnc("run " + prog.string() + kRun + " --trace " + trace.string());
    EXPECT_EQ(r.exit_code, 2) << trace << "\n" << r.err;
    EXPECT_NE(r.err.find("E102"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(prog), kProgram) << "the program was overwritten through " << trace;
  }
  EXPECT_EQ(listing(dir), (std::set<std::string>{"p.ngc", "sym.ngc", "hard.ngc"}));
  // the machine file is an input as well
  const fs::path machine = dir / "m.toml";
  fs::copy_file(kShare + "/machines/default.toml", machine);
  const std::string before = slurp(machine);
  const CmdResult r = lasercnc("run " + prog.string() + kRun + " --machine " + machine.string() +
                               " --trace " + machine.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(slurp(machine), before);
}

// A run reads more than its program: each subroutine file a call opens,
// the machine's parameter file (read at the start, written at the end). Its
// outputs may be none of them — by path, link or hard link — and a refused
// output leaves every input byte-identical (a trace over a subroutine once
// replaced it; over the parameter file, lost every work offset).
struct CallingJob {
  fs::path dir = temp_dir();
  fs::path prog, sub, machine, params;
  std::map<fs::path, std::string> before;  // every input's bytes
  CallingJob() {
    prog = write_output_files(dir / "p.ngc", "G21 G90\no<mysub> call [2]\nG10 L2 P1 X1\nM30\n");
    sub = write_output_files(dir / "mysub.ngc",
                             "o<mysub> sub\nG1 X#1 Y1 F1200\nG1 X0 Y0\no<mysub> endsub\nM2\n");
    std::string cfg = slurp(kShare + "/machines/default.toml");
    cfg.replace(cfg.find("[machine]\n"), 10, "[machine]\nparameter_file = \"jobs.var\"\n");
    machine = write_output_files(dir / "m.toml", cfg);
    params = dir / "jobs.var";
    const CmdResult r = lasercnc("run " + prog.string() + kRun + " --machine " + machine.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;  // the parameter file now exists
    for (const fs::path& f : {prog, sub, machine, params}) before[f] = slurp(f);
  }
  // Each input as it was, and `check` still reads the program.
  void expect_intact(const std::string& how) const {
    for (const auto& [f, bytes] : before) EXPECT_EQ(slurp(f), bytes) << f << " changed by " << how;
    const CmdResult r = lasercnc("check " + prog.string() + " --machine " + machine.string());
    EXPECT_EQ(r.exit_code, 0) << how << "\n" << r.err;
  }
  // `lasercnc run --trace out` and `lasercnc check --moves out`: both refused.
  void expect_refused(const fs::path& out) const {
    const std::string m = " --machine " + machine.string();
    const CmdResult run = lasercnc("run " + prog.string() + kRun + m + " --trace " + out.string());
    EXPECT_EQ(run.exit_code, 2) << out << "\n" << run.err;
    EXPECT_NE(run.err.find("E102"), std::string::npos) << run.err;
    const CmdResult check = lasercnc("check " + prog.string() + m + " --moves " + out.string());
    EXPECT_EQ(check.exit_code, 2) << out << "\n" << check.err;
    EXPECT_NE(check.err.find("E102"), std::string::npos) << check.err;
    expect_intact(out.string());
  }
};

TEST(OutputFiles, NoOutputIsASubroutineFileOrTheParameterFileTheRunReads) {
  const CallingJob job;
  job.expect_refused(job.sub);
  job.expect_refused(job.params);
  fs::create_symlink(job.sub, job.dir / "sub_link.ngc");
  job.expect_refused(job.dir / "sub_link.ngc");
  fs::create_hard_link(job.params, job.dir / "params_hard.var");
  job.expect_refused(job.dir / "params_hard.var");
  // a parameter file not written yet is where the run will write it
  fs::remove(job.dir / "params_hard.var");
  fs::remove(job.params);
  const std::string m = " --machine " + job.machine.string();
  const CmdResult r = lasercnc("run " + job.prog.string() + kRun + m + " --trace " + job.params.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(job.params));
}

// The property: any path that reaches one of a run's inputs — as given, with
// ./ and ../ in it, through a symbolic link to it or to its folder, through
// a hard link — is refused as an output, and nothing is changed.
TEST(OutputFiles, EveryPathToAnyInputIsRefusedAsAnOutput) {
  const CallingJob job;
  fs::create_directory(job.dir / "deeper");
  fs::create_directory_symlink(job.dir, job.dir / "dir_link");
  std::mt19937 rng(20261207);
  const std::vector<fs::path> inputs{job.prog, job.sub, job.machine, job.params};
  for (int k = 0; k < 16; ++k) {
    const fs::path in = inputs[rng() % inputs.size()];
    const std::string name = in.filename().string();
    fs::path out;
    switch (rng() % 5) {
      case 0: out = in; break;
      case 1: out = job.dir / "." / name; break;
      case 2: out = job.dir / "deeper" / ".." / name; break;
      case 3: out = job.dir / "dir_link" / name; break;
      default: {
        out = job.dir / ("link_" + std::to_string(k));
        if (rng() % 2 == 0)
          fs::create_symlink(in, out);
        else
          fs::create_hard_link(in, out);
      }
    }
    SCOPED_TRACE(out.string() + " -> " + in.string());
    job.expect_refused(out);
  }
}

TEST(OutputFiles, ARefusedRunLeavesTheOldTraceByteIdenticalAndCreatesNothing) {
  const fs::path dir = temp_dir();
  const fs::path prog = write_output_files(dir / "p.ngc", kProgram);
  const std::string old = "t,x,y,z,a,b,c,power\nthe previous run's trace\n";
  const fs::path trace = write_output_files(dir / "x.csv", old);
  // no laser source on that port: refused before anything moves
  CmdResult r = lasercnc("run " + prog.string() + " --no-progress --trace " + trace.string() +
                         " --laser tcp:127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(slurp(trace), old);
  // a new target is not created either
  r = lasercnc("run " + prog.string() + " --no-progress --trace " + (dir / "new.csv").string() +
               " --laser tcp:127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(listing(dir), (std::set<std::string>{"p.ngc", "x.csv"}));
}

TEST(OutputFiles, ARunThatEndsReplacesTheTraceWholeAndLeavesNoTemporaryFile) {
  const fs::path dir = temp_dir();
  const fs::path prog = write_output_files(dir / "p.ngc", kProgram);
  const fs::path trace = write_output_files(dir / "x.csv", "old\n");
  fs::permissions(trace, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  const fs::path link = dir / "link.csv";
  fs::create_symlink(trace, link);
  const CmdResult r = lasercnc("run " + prog.string() + kRun + " --trace " + link.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string t = slurp(trace);
  EXPECT_EQ(t.rfind("t,x,y,z,a,b,c,power\n", 0), 0u) << t.substr(0, 80);
  EXPECT_GT(t.size(), 100u);
  EXPECT_TRUE(fs::is_symlink(link)) << "the link is kept, the file it names replaced";
  EXPECT_EQ(fs::status(trace).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(listing(dir), (std::set<std::string>{"p.ngc", "x.csv", "link.csv"}));
}

TEST(OutputFiles, ATraceThatCannotBeWrittenIsAnErrorNamingTheFileAndTheCause) {
  const fs::path dir = temp_dir();
  const fs::path prog = write_output_files(dir / "p.ngc", kProgram);
  const CmdResult r = lasercnc("run " + prog.string() + kRun + " --trace /dev/full");
  EXPECT_NE(r.exit_code, 0) << r.out;
  EXPECT_NE(r.err.find("/dev/full"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("E103"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  // a directory that cannot be written: refused before anything moves
  const CmdResult r2 = lasercnc("run " + prog.string() + kRun + " --trace /proc/no_such_dir/trace.csv");
  EXPECT_EQ(r2.exit_code, 1);
  EXPECT_NE(r2.err.find("trace.csv"), std::string::npos) << r2.err;
}

TEST(OutputFiles, DrillRefusesATraceThatIsItsTable) {
  const fs::path dir = temp_dir();
  const fs::path table = dir / "holes.csv";
  fs::copy_file(kShare + "/examples/holes.csv", table);
  const std::string before = slurp(table);
  const CmdResult r = lasercnc("drill " + table.string() + kRun + " --trace " + table.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("E102"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(table), before);
}

TEST(OutputFiles, DecomposeRefusesAnOutputThatIsTheDrawingOrAnotherOutput) {
  const fs::path dir = temp_dir();
  const fs::path part = dir / "part.dxf";
  fs::copy_file(kPlate, part);
  const std::string before = slurp(part);
  CmdResult r = lasercnc("decompose " + part.string() + " --step 0.05 --svg " + part.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("E102"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(part), before);
  r = lasercnc("decompose " + part.string() + " --step 0.05 --csv " + (dir / "a").string() + " --svg " +
               (dir / "." / "a").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("E102"), std::string::npos) << r.err;
  EXPECT_EQ(listing(dir), (std::set<std::string>{"part.dxf"}));
}

TEST(OutputFiles, ARefusedDecomposeRunWritesNoneOfItsOutputs) {
  const fs::path dir = temp_dir();
  const std::string old = "an older table\n";
  const fs::path csv = write_output_files(dir / "a.csv", old);
  // the part at the machine's origin corner leaves the main axes' travel:
  // refused before anything moves
  const CmdResult r = lasercnc("decompose " + kPlate + " --step 0.05 --csv " + csv.string() + " --svg " +
                               (dir / "a.svg").string() + " --run --origin -1000,-1000");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("E612"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(csv), old);
  EXPECT_EQ(listing(dir), (std::set<std::string>{"a.csv"}));
}

// `--moves -` writes through the command's standard output, also when the
// shell sent it to a regular file: what the shell wrote before and after
// stays, and the file is not replaced (nor /dev/stdout itself).
TEST(OutputFiles, ADashIsTheStandardOutputEvenWhenItIsARedirectedFile) {
  const fs::path dir = temp_dir();
  const fs::path prog = write_output_files(dir / "p.ngc", kProgram);
  const fs::path out = dir / "out.txt";
  const std::string cmd = "{ echo before; " + std::string(LASERCNC_EXE) + " check " + prog.string() +
                          " --moves -; echo after; } >" + out.string() + " 2>/dev/null </dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(out), "before\n2 feed 2 1 0 0 0 0\n3 feed 0 0 0 0 0 0\nafter\n");
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
}

}  // namespace
