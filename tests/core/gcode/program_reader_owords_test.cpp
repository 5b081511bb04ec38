// O-words as LinuxCNC runs them: subroutines (defined in the program, later in
// it, or in their own file on the search path), if/elseif/else, while, do,
// repeat, break and continue, and the errors that name the line and label.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::segments;

std::vector<double> xs(const std::vector<Segment>& segs) {
  std::vector<double> v;
  for (const Segment& s : segs) v.push_back(s.end[0]);
  return v;
}

TEST(ProgramOWords, WhileLoopRunsWhileItsConditionHolds) {
  const auto segs = segments(
      "#1 = 0\nO100 while [#1 LT 3]\n  G1 X[#1 * 10 + 20] F600\n  #1 = [#1 + 1]\n"
      "O100 endwhile\nG1 X99\n");
  EXPECT_EQ(xs(segs), (std::vector<double>{20, 30, 40, 99}));
  // false at once: the body is never read, not even its unsupported code
  EXPECT_EQ(xs(segments("O1 while [0]\nG38.2 X5\nO1 endwhile\nG1 X50 F600\n")), (std::vector<double>{50}));
}

TEST(ProgramOWords, IfElseIfElseRunsOneBranch) {
  const std::string body =
      "O7 if [#1 EQ 1]\n G1 X11 F600\nO7 elseif [#1 EQ 2]\n G1 X22 F600\n"
      "O7 elseif [#1 EQ 3]\n G1 X33 F600\nO7 else\n G1 X44 F600\nO7 endif\nG1 X99\n";
  for (int v = 1; v <= 4; ++v) {
    const auto segs = segments("#1 = " + std::to_string(v) + "\n" + body);
    ASSERT_EQ(segs.size(), 2u) << v;
    EXPECT_DOUBLE_EQ(segs[0].end[0], 11.0 * v);
    EXPECT_DOUBLE_EQ(segs[1].end[0], 99.0);
  }
  // branches not taken are not read: a code outside the subset is no error there
  EXPECT_EQ(xs(segments("O7 if [1]\nG1 X20 F600\nO7 else\nG38.2 X5\nO7 endif\n")), (std::vector<double>{20}));
}

TEST(ProgramOWords, DoRepeatBreakAndContinue) {
  // do runs once though its condition is false
  EXPECT_EQ(xs(segments("O1 do\nG1 X20 F600\nO1 while [0]\n")), (std::vector<double>{20}));
  EXPECT_EQ(xs(segments("#1 = 0\nO1 do\n#1 = [#1 + 1]\nG1 X[#1 * 10 + 10] F600\n"
                        "O1 while [#1 LT 3]\n")),
            (std::vector<double>{20, 30, 40}));
  EXPECT_EQ(xs(segments("#1 = 20\nO2 repeat [3]\nG1 X#1 F600\n#1 = [#1 + 5]\nO2 endrepeat\n")),
            (std::vector<double>{20, 25, 30}));
  EXPECT_TRUE(segments("O2 repeat [0]\nG1 X20 F600\nO2 endrepeat\n").empty());
  // break leaves at 3; continue skips the move of 2
  EXPECT_EQ(xs(segments("#1 = 0\nO3 while [1]\n#1 = [#1 + 1]\nO4 if [#1 EQ 2]\n"
                        "O3 continue\nO4 endif\nO5 if [#1 GT 3]\nO3 break\nO5 endif\n"
                        "G1 X[#1 * 10 + 10] F600\nO3 endwhile\nG1 X99\n")),
            (std::vector<double>{20, 40, 99}));
}

TEST(ProgramOWords, SubroutinesTakeArgumentsRestoreThemAndReturnAValue) {
  const auto segs = segments(
      "o<square> sub\n"
      "  #<half> = [#1 / 2]\n"
      "  G1 X[#2 + #<half>] F600\n"
      "  G1 X[#2 - #<half>]\n"
      "o<square> endsub [#1 * 3]\n"
      "#1 = 7\n"
      "o<square> call [20] [50]\n"
      "G1 X#1\n"              // #1 is the caller's again
      "G1 X[#<_value>]\n"     // 60: what the call returned
      "o<later> call [30]\n"  // defined further down: found forward, as LinuxCNC does
      "M2\n"
      "o<later> sub\nG1 X#1\no<later> endsub\n");
  EXPECT_EQ(xs(segs), (std::vector<double>{60, 40, 7, 60, 30}));
  // a local of the caller is not seen inside the call
  const Diagnostic d = expect_error("#<depth> = 2\no<s> sub\nG1 X#<depth> F600\no<s> endsub\no<s> call\n",
                                    ErrorCode::GcodeSyntax, 3, 5);
  EXPECT_MENTIONS(d, "#<depth>");
  // return leaves the call, whatever the label on it (LinuxCNC's retval.ngc)
  EXPECT_EQ(xs(segments("o100 sub\no110 if [#1 GT 0]\no110 return [#1 * 2]\no110 endif\n"
                        "o100 endsub [5]\no100 call [20]\nG1 X#<_value> F600\n"
                        "o100 call [0]\nG1 X#<_value>\n")),
            (std::vector<double>{40, 5}));
}

TEST(ProgramOWords, SubroutineFilesAreFoundBesideTheProgramAndOnTheSearchPath) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("lcnc_owords_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "subs");
  auto write = [](const fs::path& p, const std::string& text) { std::ofstream(p) << text; };
  write(dir / "job.ngc", "G21 G90 F600\no<beside> call [20]\no<deep> call [30]\no<beside> call [40]\nM2\n");
  write(dir / "beside.ngc", "%\n(a sub of its own)\no<beside> sub\nG1 X#1\no<beside> endsub\n%\n");
  write(dir / "subs" / "deep.ngc", "o<deep> sub\nG1 Y#1\nG38.2 X1\no<deep> endsub\n");
  MachineConfig m = test::test_machine();
  m.subroutine_path = {(dir / "subs").string()};
  auto reader = ProgramReader::open((dir / "job.ngc").string(), m, test::start_at());
  ASSERT_TRUE(reader);
  Segment s;
  ASSERT_EQ((*reader)->next(s), ProgramReader::Next::Segment);
  EXPECT_DOUBLE_EQ(s.end[0], 20.0);
  EXPECT_EQ(s.line, 4u);  // beside.ngc's line 4
  ASSERT_EQ((*reader)->next(s), ProgramReader::Next::Segment);
  EXPECT_DOUBLE_EQ(s.end[1], 30.0);
  // the error in the called file names that file and its line
  ASSERT_EQ((*reader)->next(s), ProgramReader::Next::Error);
  const Diagnostic& d = (*reader)->error();
  EXPECT_EQ(d.file, (dir / "subs" / "deep.ngc").string());
  EXPECT_EQ(d.line, 3u);
  EXPECT_EQ(d.code, ErrorCode::GcodeUnknownCode);

  // without the search path the call is not found, and the error is at the call
  m.subroutine_path.clear();
  const Result<ProgramSummary> r = check_program((dir / "job.ngc").string(), m, test::start_at());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::GcodeFlow);
  EXPECT_EQ(r.error().file, (dir / "job.ngc").string());
  EXPECT_EQ(r.error().line, 3u);
  EXPECT_MENTIONS(r.error(), "deep.ngc");
  fs::remove_all(dir);
}

// A subroutine's name is a name: o</abs/file> and o<../x> would read files
// from anywhere (the daemon ran a root-only file so); refused at the call,
// and nothing of the file is read.
TEST(ProgramOWords, ASubroutineNameThatIsAPathIsRefusedAtTheCall) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("lcnc_owords_path_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "progs");
  std::ofstream(dir / "outside.ngc") << "o<outside> sub\nG1 X5 F600\no<outside> endsub\n";
  for (const std::string& name : {(dir / "outside").string(), std::string("../outside"), std::string("."),
                                  std::string(".."), std::string("progs\\..\\outside")}) {
    SCOPED_TRACE(name);
    std::ofstream(dir / "progs" / "job.ngc") << "G21 G90\no<" << name << "> call\nM2\n";
    const Result<ProgramSummary> r =
        check_program((dir / "progs" / "job.ngc").string(), test::test_machine(), test::start_at());
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().line, 2u);
    EXPECT_EQ(r.error().file, (dir / "progs" / "job.ngc").string());
    EXPECT_MENTIONS(r.error(), "a subroutine's name is a path");
  }
  fs::remove_all(dir);
}

// ReaderOptions::file_policy is asked before a subroutine file is opened;
// its refusal is the reading's error at the call, and the file is not read
// (a file of something else would otherwise be quoted in a syntax error).
TEST(ProgramOWords, TheFilePolicyIsAskedBeforeASubroutineFileIsRead) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("lcnc_owords_policy_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "job.ngc") << "G21 G90 F600\no<open> call\no<secret> call\nM2\n";
  std::ofstream(dir / "open.ngc") << "o<open> sub\nG1 X1\no<open> endsub\n";
  std::ofstream(dir / "secret.ngc") << "ROOTSECRET\n";
  ReaderOptions o = test::start_at();
  std::vector<std::string> asked;
  o.file_policy = [&](const std::string& path) -> Status {
    asked.push_back(fs::path(path).filename().string());
    if (fs::path(path).filename() == "secret.ngc")
      return make_error(ErrorCode::FileNotFound, "the sender (uid 65534) may not read it", path);
    return {};
  };
  const Result<ProgramSummary> r = check_program((dir / "job.ngc").string(), test::test_machine(), o);
  ASSERT_FALSE(r);
  EXPECT_EQ(asked, (std::vector<std::string>{"open.ngc", "secret.ngc"}));
  EXPECT_EQ(r.error().line, 3u);
  EXPECT_MENTIONS(r.error(), "may not read it");
  EXPECT_EQ(r.error().to_string().find("ROOTSECRET"), std::string::npos) << r.error().to_string();
  // a program held in memory has no folder: its calls look on the search
  // path alone, never in the working folder
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  const Diagnostic d = expect_error("o<open> call\n", ErrorCode::GcodeFlow, 1, 1);
  EXPECT_MENTIONS(d, "not found");
  fs::current_path(cwd);
  fs::remove_all(dir);
}

TEST(ProgramOWords, MismatchesAndOpenStructuresAreErrorsAtTheirLine) {
  Diagnostic d = expect_error("G1 X20 F600\nO100 endwhile\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "O100 endwhile");
  d = expect_error("O1 if [1]\nO2 while [1]\nO1 endif\n", ErrorCode::GcodeFlow, 3, 1);
  EXPECT_MENTIONS(d, "O2 while (line 2) is the one open");
  d = expect_error("G1 X20 F600\nO1 if [0]\nG1 X30\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "O1 endif");
  d = expect_error("G1 X20 F600\nO1 if [1]\nG1 X30\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "still open");
  d = expect_error("G1 X20 F600\no<nowhere> call\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "O<nowhere> not found");
  d = expect_error("O1 return\n", ErrorCode::GcodeFlow, 1, 1);
  EXPECT_MENTIONS(d, "outside a subroutine");
  d = expect_error("o<a> sub\no<b> sub\no<b> endsub\no<a> endsub\no<a> call\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "inside subroutine");
  d = expect_error("o<a> sub\no<a> endsub\no<a> sub\no<a> endsub\n", ErrorCode::GcodeFlow, 3, 1);
  EXPECT_MENTIONS(d, "first is on line 1");
  d = expect_error("o<r> sub\no<r> call\no<r> endsub\no<r> call\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "at most 10 calls");
  d = expect_error("O1 whilst [1]\n", ErrorCode::GcodeSyntax, 1, 4);
  EXPECT_MENTIONS(d, "'WHILST'");
  d = expect_error("O1 if [1] G1 X5\n", ErrorCode::GcodeSyntax, 1, 11);
  EXPECT_MENTIONS(d, "only bracketed values");
  d = expect_error("O1 if\n", ErrorCode::GcodeSyntax, 1, 1);
  EXPECT_MENTIONS(d, "one bracketed value");
  d = expect_error("G1 X20 F600\nO1 if [#<nope>]\nO1 endif\n", ErrorCode::GcodeSyntax, 2, 8);
  EXPECT_MENTIONS(d, "#<nope>");
}

TEST(ProgramOWords, AnEndlessLoopWithoutMotionIsAnErrorNotAHang) {
  const Diagnostic d =
      expect_error("G1 X20 F600\nO1 while [1]\n#1 = [#1 + 1]\nO1 endwhile\n", ErrorCode::GcodeFlow, 4, 1);
  EXPECT_MENTIONS(d, "endless loop");
}

// A loop that moves, dwells or pauses without end runs into the reading's
// work budget (MachineConfig::program_segment_limit, program_time_limit_s):
// an error at the line the loop stands on, so `check` always ends.
TEST(ProgramOWords, AnEndlessLoopThatMovesRunsIntoTheWorkBudget) {
  MachineConfig m = test::test_machine();
  m.program_segment_limit = 5000;
  Diagnostic d = expect_error("G1 X20 F600\nO1 while [1]\nG1 X10\nG1 X20\nO1 endwhile\n",
                              ErrorCode::GcodeWorkBudget, 4, 1, test::start_at(), m);
  EXPECT_MENTIONS(d, "program_segment_limit");
  d = expect_error("O1 repeat [1000000000000]\nG4 P0\nO1 endrepeat\n", ErrorCode::GcodeWorkBudget, 2, 1,
                   test::start_at(), m);
  d = expect_error("O1 do\nM0\nO1 while [1]\n", ErrorCode::GcodeWorkBudget, 2, 1, test::start_at(), m);
  // machine time: 10 mm at F60 is 10 s; a minute's budget ends within 7 moves
  m.program_segment_limit = 200e6;
  m.program_time_limit_s = 60.0;
  d = expect_error("G1 X0 F60\nO1 while [1]\nG1 X10\nG1 X0\nO1 endwhile\n", ErrorCode::GcodeWorkBudget, 4, 1,
                   test::start_at(), m);
  EXPECT_MENTIONS(d, "program_time_limit_h");
  // within the budget: runs whole
  EXPECT_EQ(segments("O1 repeat [2]\nG1 X30 F600\nG1 X40\nO1 endrepeat\n", test::start_at(), m).size(), 4u);
}

// The property: random loops — while, do-while, repeat; bodies that move,
// dwell, pause, compute, call a subroutine, nest — each ends, with the
// budget's error or the one for loops without motion, never a hang.
TEST(ProgramOWords, EveryEndlessLoopEndsWithAnError) {
  MachineConfig m = test::test_machine();
  m.program_segment_limit = 2000;
  m.program_time_limit_s = 3600.0;
  std::mt19937 rng(38);
  const char* bodies[] = {"G1 X10\nG1 X20\n",
                          "G4 P0\n",
                          "M0\n",
                          "M1\n",
                          "#1 = [#1 + 1]\n",
                          "o<step> call\n",
                          "G0 X15\nG4 P0.5\n",
                          "O9 repeat [3]\nG1 X12\nG1 X20\nO9 endrepeat\n",
                          "O8 if [#1 LT 0]\nG1 X1\nO8 endif\n"};
  for (int k = 0; k < 24; ++k) {
    const std::string body = bodies[rng() % std::size(bodies)];
    std::string loop;
    switch (rng() % 3) {
      case 0: loop = "O1 while [1]\n" + body + "O1 endwhile\n"; break;
      case 1: loop = "O1 do\n" + body + "O1 while [1]\n"; break;
      default: loop = "O1 repeat [1000000000000000]\n" + body + "O1 endrepeat\n"; break;
    }
    const std::string program = "o<step> sub\nG1 X11\no<step> endsub\nG1 X20 F600\n" + loop + "M2\n";
    SCOPED_TRACE(program);
    const test::Run r = test::run(program, test::start_at(), m);
    ASSERT_EQ(r.last, ProgramReader::Next::Error);
    EXPECT_TRUE(r.error.code == ErrorCode::GcodeWorkBudget || r.error.code == ErrorCode::GcodeFlow)
        << r.error.to_string();
    EXPECT_GE(r.error.line, 5u) << r.error.to_string();  // in the loop (or the sub it calls)
    EXPECT_LE(r.segments.size(), 2000u);
  }
}

// Another thread's cancel ends a reading at its next line.
TEST(ProgramOWords, ACancelledReadingEndsAtItsNextLine) {
  std::atomic<bool> cancel{false};
  ReaderOptions o = test::start_at();
  o.cancel = &cancel;
  auto reader = ProgramReader::from_string("G1 X20 F600\nO1 while [1]\nG1 X10\nG1 X20\nO1 endwhile\n",
                                           "test.ngc", test::test_machine(), o);
  Segment s;
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(reader->next(s), ProgramReader::Next::Segment);
  cancel = true;
  ProgramReader::Next n = ProgramReader::Next::Segment;
  for (int i = 0; i < 10 && n == ProgramReader::Next::Segment; ++i) n = reader->next(s);
  ASSERT_EQ(n, ProgramReader::Next::Error);
  EXPECT_EQ(reader->error().code, ErrorCode::GcodeCancelled);
}

}  // namespace
}  // namespace lcnc
