// End to end, the operator's controls on a live lasercncd (simulated
// machine): touch-off and work offsets, MDI, single block, run from line,
// dry run and framing — sent with `lasercnc send` as an operator or the HMI
// would, the machine watched through the shared-memory status.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "daemon_status.h"
#include "e2e_support.h"
#include "rt/shm_interface.h"

namespace {

using namespace e2e;
using namespace std::chrono_literals;
namespace lshm = lcnc::shm;

CmdResult send(const std::string& shm, const std::string& what) {
  return lasercnc("send " + what + " --shm " + shm);
}

// The kernel's status straight from the segment, as the HMI reads it.
struct Watch {
  explicit Watch(const std::string& shm) : client(lshm::ShmClient::open(shm)) {}
  bool read(lshm::Status& st) {
    if (!client) return false;
    const bool ok = client->block().status.load_patiently(st, 100ms);
    if (ok) lshm::sanitize(st);
    return ok;
  }
  lcnc::Result<lshm::ShmClient> client;
};

// Waits until the machine is held at a program pause (single block, M0).
bool wait_pause(Watch& w, std::chrono::milliseconds t = 10s) {
  const auto until = std::chrono::steady_clock::now() + t;
  lshm::Status st;
  while (std::chrono::steady_clock::now() < until) {
    if (w.read(st) && st.state == lshm::MachineState::FeedHold && st.program_pause) return true;
    std::this_thread::sleep_for(2ms);
  }
  return false;
}

double at(const nlohmann::json& s, const char* what, int axis) { return s[what][axis].get<double>(); }

// Every status sample (1 ms apart) of the job just sent, from when the
// daemon says it is active to when it says it has ended (or `limit`).
template <typename F>
bool sample_job(lcnc::shm::ShmClient& c, F each, std::chrono::milliseconds limit = 60s) {
  const auto until = std::chrono::steady_clock::now() + limit;
  lcnc::shm::JobStatus job;
  lcnc::shm::Status st;
  bool seen_active = false;
  while (std::chrono::steady_clock::now() < until) {
    if (c.block().job.load_patiently(job, 100ms) && c.block().status.load_patiently(st, 100ms)) {
      lcnc::shm::sanitize(job);
      lcnc::shm::sanitize(st);
      if (job.job_active) {
        seen_active = true;
        each(st);
      } else if (seen_active) {
        return true;
      }
    }
    std::this_thread::sleep_for(1ms);
  }
  return false;
}

// Waits until a jog (or any motion) is over.
bool wait_idle(const std::string& shm) {
  for (const auto until = std::chrono::steady_clock::now() + 60s; std::chrono::steady_clock::now() < until;) {
    const nlohmann::json s = status(shm);
    if (s.is_object() && s["state"] == "idle" && !s["job_active"].get<bool>()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

// A daemon of the test's own, and its segment read as the HMI reads it.
class LasercncdJob : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(d.ready()) << d.log();
    w.emplace(shm);
    ASSERT_TRUE(w->client) << w->client.error().message;
  }
  // Waits for the job to end; the status then.
  nlohmann::json job_end() const {
    for (const auto until = std::chrono::steady_clock::now() + 60s;
         std::chrono::steady_clock::now() < until && status(shm)["job_active"].get<bool>();)
      std::this_thread::sleep_for(10ms);
    return status(shm);
  }
  const std::string shm = shm_name("/lcnc_op_");
  Daemon d{shm};
  std::optional<Watch> w;
};

TEST(LasercncdOperator, TouchOffSetsTheWorkZeroAndTheNextG0GoesThere) {
  const std::string shm = shm_name("/lcnc_op_");
  const fs::path params = temp_dir() / "offsets.var";
  {
    Daemon d(shm, {"--parameter-file", params.string()});
    ASSERT_TRUE(d.ready()) << d.log();
    ASSERT_EQ(send(shm, "jog X 100").exit_code, 0);
    ASSERT_TRUE(wait_idle(shm));
    ASSERT_EQ(send(shm, "mdi G0 Y40 --wait").exit_code, 0);
    // touch-off: here is X0 Y0 of G54
    CmdResult r = send(shm, "mdi G10 L20 P0 X0 Y0");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    nlohmann::json s = status(shm);
    EXPECT_NEAR(at(s, "position", 0), 100.0, 1e-9);
    EXPECT_NEAR(at(s, "work_position", 0), 0.0, 1e-9);
    EXPECT_NEAR(at(s, "work_position", 1), 0.0, 1e-9);
    EXPECT_NEAR(at(s, "work_offset", 1), 40.0, 1e-9);
    EXPECT_EQ(s["coord_system"], "G54");
    // away, then G0 X0 Y0 comes back to the touched-off point
    ASSERT_EQ(send(shm, "jog X 55").exit_code, 0);
    ASSERT_TRUE(wait_idle(shm));
    ASSERT_EQ(send(shm, "jog Y 10").exit_code, 0);
    ASSERT_TRUE(wait_idle(shm));
    s = status(shm);
    EXPECT_NEAR(at(s, "work_position", 0), 55.0, 1e-9);
    r = send(shm, "mdi G0 X0 Y0 --wait");
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    s = status(shm);
    EXPECT_NEAR(at(s, "position", 0), 100.0, 1e-9);
    EXPECT_NEAR(at(s, "position", 1), 40.0, 1e-9);
    // a second system: G55's zero touched off elsewhere, and selected
    ASSERT_EQ(send(shm, "mdi G0 X30 --wait").exit_code, 0);  // machine X 130
    ASSERT_EQ(send(shm, "mdi G10 L20 P2 X0").exit_code, 0);
    ASSERT_EQ(send(shm, "mdi G55").exit_code, 0);
    s = status(shm);
    EXPECT_EQ(s["coord_system"], "G55");
    EXPECT_NEAR(at(s, "work_position", 0), 0.0, 1e-9);
    EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
  }
  // kept: a daemon started afresh shows the same work system and zero
  Daemon d(shm, {"--parameter-file", params.string()});
  ASSERT_TRUE(d.ready()) << d.log();
  const nlohmann::json s = status(shm);
  EXPECT_EQ(s["coord_system"], "G55");
  EXPECT_NEAR(at(s, "work_offset", 0), 130.0, 1e-9);
  EXPECT_NEAR(at(s, "work_offset", 1), 0.0, 1e-9);  // G55's Y was not touched off
}

TEST(LasercncdOperator, MdiMovesInTheModesTheLastCommandLeft) {
  const std::string shm = shm_name("/lcnc_op_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  CmdResult r = send(shm, "mdi G1 X10 Y5 F3000 --wait");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("job done: MDI"), std::string::npos) << r.out;
  // G1 and F3000 carry on; then G91 makes the next words increments
  ASSERT_EQ(send(shm, "mdi G91").exit_code, 0);
  r = send(shm, "mdi X5 --wait");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  nlohmann::json s = status(shm);
  EXPECT_NEAR(at(s, "position", 0), 15.0, 1e-9);
  EXPECT_NEAR(at(s, "position", 1), 5.0, 1e-9);
  EXPECT_NE(s["modes"].get<std::string>().find("G91"), std::string::npos) << s["modes"];
  EXPECT_NE(s["modes"].get<std::string>().find("F3000 G1"), std::string::npos) << s["modes"];
  // a bad line: where and what, nothing moves
  r = send(shm, "mdi G1 X10 Q");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("MDI:1:"), std::string::npos) << r.err;
  // past the travel: refused before motion
  r = send(shm, "mdi G90 G0 X5000");
  EXPECT_EQ(r.exit_code, 1);
  s = status(shm);
  EXPECT_NEAR(at(s, "position", 0), 15.0, 1e-9);
  // refused while a job runs
  ASSERT_EQ(send(shm, "mdi G90 G1 X400 F600").exit_code, 0);
  r = send(shm, "mdi G0 X0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("mdi refused: a job is"), std::string::npos) << r.err;
  // the distance to go: to X 400, as far as the machine has still to move
  for (int i = 0; i < 1000; ++i) {
    s = status(shm);
    if (s["state"] == "running" && at(s, "distance_to_go", 0) > 1.0) break;
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_GT(at(s, "distance_to_go", 0), 1.0);
  EXPECT_NEAR(at(s, "distance_to_go", 0), 400.0 - at(s, "position", 0),
              1.0);  // the status and job blocks differ by a few periods
  EXPECT_NEAR(at(s, "distance_to_go", 1), 0.0, 1e-9);
  ASSERT_EQ(send(shm, "stop").exit_code, 0);
}

// `--wait` tells a move from an MDI command that does not move by the job
// status it reads after its answer: the daemon publishes the job its command
// began before the answer, so no move is taken for a command that is done.
TEST(LasercncdOperator, AnMdiMoveWithWaitReturnsAfterItsMoveNeverBefore) {
  const std::string shm = shm_name("/lcnc_op_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  for (int i = 0; i < 12; ++i) {
    const double x = (i % 2 == 0) ? 2.0 : 0.0;
    const CmdResult r = send(shm, "mdi G0 X" + std::to_string(x) + " --wait");
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    ASSERT_NE(r.out.find("job done: MDI"), std::string::npos) << "move " << i << ": " << r.out;
    const nlohmann::json s = status(shm);
    EXPECT_FALSE(s["job_active"].get<bool>()) << "move " << i;
    EXPECT_NEAR(at(s, "position", 0), x, 1e-9) << "move " << i;
  }
}

constexpr const char* kBlocks =
    "G21 G90 G64 P0.01\n"  // 1
    "G0 X10 Y10\n"         // 2
    "G1 X40 F6000\n"       // 3
    "G1 Y30\n"             // 4
    "G1 X10\n"             // 5
    "G0 X0 Y0\n"           // 6
    "M2\n";                // 7

TEST_F(LasercncdJob, SingleBlockStopsAfterEachBlock) {
  ASSERT_EQ(send(shm, "load " + write_program("blocks.ngc", kBlocks).string()).exit_code, 0);
  CmdResult r = send(shm, "start --single-block");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("single block"), std::string::npos) << r.out;
  const std::vector<std::array<double, 3>> stops = {{10, 10, 2}, {40, 10, 3}, {40, 30, 4}, {10, 30, 5}};
  for (const auto& [x, y, line] : stops) {
    ASSERT_TRUE(wait_pause(*w)) << "no stop after line " << line << "\n" << d.log();
    lshm::Status st;
    ASSERT_TRUE(w->read(st));
    EXPECT_NEAR(st.pos[0], x, 1e-9) << "line " << line;
    EXPECT_NEAR(st.pos[1], y, 1e-9) << "line " << line;
    EXPECT_EQ(st.line, static_cast<std::uint32_t>(line));
    // it stays there until resumed
    ASSERT_TRUE(wait_machine_time(shm, 0.1));
    ASSERT_TRUE(w->read(st));
    EXPECT_NEAR(st.pos[0], x, 1e-9);
    EXPECT_TRUE(st.program_pause);
    ASSERT_EQ(send(shm, "resume").exit_code, 0);
    std::this_thread::sleep_for(20ms);
  }
  // the last block runs to the end
  const nlohmann::json s = job_end();
  EXPECT_EQ(s["last_outcome"], "done") << s["message"];
  EXPECT_NEAR(at(s, "position", 0), 0.0, 1e-9);
}

TEST_F(LasercncdJob, RunFromLineStartsThereInTheProgramsModes) {
  // before line 6: G55 set to X+200 and selected, inches, incremental, a feed
  const char* program =
      "G21 G90 G64 P0.01\n"   // 1
      "G10 L2 P2 X200 Y50\n"  // 2
      "G55 G0 X0 Y0 Z1\n"     // 3
      "G20 G91 F100\n"        // 4  (100 in/min)
      "G1 X1\n"               // 5
      "G1 Y1\n"               // 6
      "G1 X-1\n"              // 7
      "G90 G21 G0 Z20\n"      // 8
      "M2\n";                 // 9
  ASSERT_EQ(send(shm, "load " + write_program("from_line.ngc", program).string()).exit_code, 0);
  ASSERT_EQ(send(shm, "mdi G53 G0 X10 Y10 Z5 --wait").exit_code, 0);
  // single block too: the first stop is the end of line 6 after the approach
  CmdResult r = send(shm, "start --from-line 6 --single-block");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("from line 6"), std::string::npos) << r.out;
  // line 6 starts where line 5 ended: X 200+25.4, Y 50, Z 1 — approached
  // across at Z5 (the higher), then down; nothing of lines 2-5 moved
  double min_z_across = 1e9;
  lshm::Status st;
  const auto until = std::chrono::steady_clock::now() + 10s;
  bool paused = false;
  while (std::chrono::steady_clock::now() < until && !paused) {
    if (w->read(st)) {
      if (st.pos[0] > 10.5 && st.pos[0] < 225.0) min_z_across = std::min(min_z_across, st.pos[2]);
      paused = st.state == lshm::MachineState::FeedHold && st.program_pause;
    }
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_TRUE(paused) << d.log();
  EXPECT_NEAR(st.pos[0], 225.4, 1e-9);
  EXPECT_NEAR(st.pos[1], 75.4, 1e-9);  // line 6: Y + 1 inch from Y 50
  EXPECT_NEAR(st.pos[2], 1.0, 1e-9);
  EXPECT_EQ(st.line, 6u);
  EXPECT_GE(min_z_across, 5.0 - 1e-9) << "the approach went below the higher Z";
  ASSERT_EQ(send(shm, "resume").exit_code, 0);
  ASSERT_TRUE(wait_pause(*w));
  ASSERT_TRUE(w->read(st));
  EXPECT_NEAR(st.pos[0], 200.0, 1e-9);  // line 7: X − 1 inch, still incremental inches
  EXPECT_EQ(st.line, 7u);
  ASSERT_EQ(send(shm, "resume").exit_code, 0);
  const nlohmann::json s = job_end();
  EXPECT_EQ(s["last_outcome"], "done") << s["message"];
  EXPECT_EQ(s["start_line"], 6);
  EXPECT_NEAR(at(s, "position", 2), 20.0, 1e-9);
  // a line past the last move: refused, nothing runs
  r = send(shm, "start --from-line 9");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("run from line 9"), std::string::npos) << r.err;
}

TEST_F(LasercncdJob, DryRunAndFramingKeepTheBeamOff) {
  const char* program =
      "G21 G90 G64 P0.01\n"  // 1
      "G0 X50 Y20\n"         // 2
      "M3 S80\n"             // 3
      "G1 X250 F12000\n"     // 4
      "G3 X250 Y120 J50\n"   // 5  (bulges to X 300)
      "G1 X50\n"             // 6
      "G1 Y20\n"             // 7
      "M5\n"                 // 8
      "G0 X0 Y0\n"           // 9
      "M2\n";                // 10
  ASSERT_EQ(send(shm, "load " + write_program("plate.ngc", program).string()).exit_code, 0);
  ASSERT_EQ(send(shm, "mdi G0 X20 Y5 --wait").exit_code, 0);
  // framing: the cuts' box X 50 … 300, Y 20 … 120, traced on its outline
  CmdResult r = send(shm, "frame");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("X 50.000 … 300.000, Y 20.000 … 120.000"), std::string::npos) << r.out;
  double lo_x = 1e9, hi_x = -1e9, lo_y = 1e9, hi_y = -1e9, max_power = 0.0, off_outline = 0.0;
  std::size_t on_outline = 0;
  EXPECT_TRUE(sample_job(*w->client, [&](const lshm::Status& st) {
    max_power = std::max<double>(max_power, st.power_pct);
    if (st.state == lshm::MachineState::Running && st.line >= 4 && st.line <= 7) {
      const double x = st.pos[0], y = st.pos[1];
      lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
      const double d_edge =
          std::min({std::abs(x - 50), std::abs(x - 300), std::abs(y - 20), std::abs(y - 120)});
      off_outline = std::max(off_outline, d_edge);
      ++on_outline;
    }
  }));
  EXPECT_GT(on_outline, 100u);
  EXPECT_LT(off_outline, 0.01) << "a framing sample off the box's outline";
  EXPECT_NEAR(lo_x, 50.0, 2.0);
  EXPECT_NEAR(hi_x, 300.0, 2.0);
  EXPECT_NEAR(lo_y, 20.0, 2.0);
  EXPECT_NEAR(hi_y, 120.0, 2.0);
  EXPECT_EQ(max_power, 0.0);
  nlohmann::json s = job_end();
  EXPECT_EQ(s["last_outcome"], "done") << s["message"];
  EXPECT_NEAR(at(s, "position", 0), 20.0, 1e-9);  // back where it began
  EXPECT_NEAR(at(s, "position", 1), 5.0, 1e-9);

  // the dry run: the program's moves, the beam never on; the real run lights it
  const auto peak_power = [&](const std::string& how) {
    const CmdResult started = send(shm, "start" + how);
    EXPECT_EQ(started.exit_code, 0) << started.err;
    double peak = 0.0;
    EXPECT_TRUE(
        sample_job(*w->client, [&](const lshm::Status& st) { peak = std::max<double>(peak, st.power_pct); }));
    return peak;
  };
  EXPECT_EQ(peak_power(" --dry-run"), 0.0);
  s = status(shm);
  EXPECT_EQ(s["last_outcome"], "done") << s["message"];
  EXPECT_TRUE(s["dry_run"].get<bool>());
  EXPECT_GT(peak_power(""), 50.0);
}

}  // namespace

namespace {

// A parameter file that cannot be read stops the daemon at its start with
// where and what: no job may run from offsets that are not the machine's.
TEST(LasercncdOperator, ABadParameterFileIsRefusedAtStart) {
  const fs::path params = temp_dir() / "bad.var";
  std::ofstream(params) << "5221 100\n5222 forty\n";
  const CmdResult r = run_program(
      LASERCNCD_EXE, "--shm " + shm_name("/lcnc_op_") + " --no-realtime --parameter-file " + params.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.var:2:"), std::string::npos) << r.err;
}

// State that is not stored is not reported as stored. A parameter file that
// can never be written stops the daemon at its start (it once answered a
// G10 done, showed the offset, and the next G54 move ignored it). The
// status shows the offsets as read back from the file, and a move goes where
// it says. (A file that can no longer be written fails the reading that
// set the offsets: ParameterFile.OffsetsThatCannotBeKeptFailTheReadingThatSetThem;
// the tests run as root here, whom no mode bit stops writing.)
TEST(LasercncdOperator, AnOffsetThatCannotBeKeptIsRefusedNotAcknowledged) {
  const CmdResult r =
      run_program(LASERCNCD_EXE, "--shm " + shm_name("/lcnc_op_") + " --no-realtime --parameter-file " +
                                     (temp_dir() / "no_such_folder" / "p.var").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("E114"), std::string::npos) << r.err;

  const std::string shm = shm_name("/lcnc_op_");
  const fs::path folder = temp_dir() / "params";
  fs::create_directories(folder);
  Daemon d(shm, {"--parameter-file", (folder / "p.var").string()});
  ASSERT_TRUE(d.ready()) << d.log();
  ASSERT_EQ(send(shm, "mdi G10 L2 P1 X5").exit_code, 0);
  EXPECT_NE(slurp(folder / "p.var").find("5221\t5\n"), std::string::npos);  // stored
  EXPECT_NEAR(at(status(shm), "work_offset", 0), 5.0, 1e-9);                // and so shown
  const CmdResult move = send(shm, "mdi G54 G0 X1 --wait");
  EXPECT_EQ(move.exit_code, 0) << move.out << move.err;
  EXPECT_NEAR(at(status(shm), "position", 0), 6.0, 1e-9);  // G54 X1 = machine 5 + 1
}

}  // namespace
