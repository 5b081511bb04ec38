// End to end: lasercncd hosts the planner and RT threads on the simulated
// machine; `lasercnc status` and `lasercnc send` drive it through the
// shared-memory segment, as an HMI would — real processes, real POSIX shm.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <pthread.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

#include "daemon_status.h"
#include "e2e_support.h"
#include "rt/shm_interface.h"

namespace {

using namespace e2e;
using namespace std::chrono_literals;

bool wait_state(const std::string& shm, const std::string& state, std::chrono::milliseconds t = 5000ms) {
  const auto until = std::chrono::steady_clock::now() + t;
  while (std::chrono::steady_clock::now() < until) {
    const nlohmann::json s = status(shm);
    if (s.is_object() && s["state"] == state) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

const char* kShortJob =
    "G21 G90 G64 P0.01\n"
    "G0 X10 Y10\n"
    "M3 S60\n"
    "G1 X30 F6000\n"
    "G1 Y25\n"
    "G1 X10\n"
    "G1 Y10\n"
    "M5\n"
    "G0 X12 Y12\n"
    "M2\n";

TEST(Lasercncd, RunsAJobSentByTheCliAndReportsIt) {
  const std::string shm = shm_name("/lcnc_e2e_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  EXPECT_EQ(status(shm)["state"], "idle");
  // a bad program: refused with file:line:col, nothing loaded
  const fs::path bad = write_program("bad.ngc", "G21 G90\nG1 X10 Y10 F1000\nG2 X20 Y0 R2\nM2\n");
  CmdResult r = lasercnc("send load " + bad.string() + " --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.ngc:3:"), std::string::npos) << r.err;
  r = lasercnc("send start --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no program loaded"), std::string::npos) << r.err;
  // a good one runs to its end
  const fs::path good = write_program("square.ngc", kShortJob);
  r = lasercnc("send load " + good.string() + " --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("10 lines"), std::string::npos) << r.out;
  r = lasercnc("send start --wait --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("job done"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 underruns"), std::string::npos) << r.out;
  // the daemon checked the job's motion from the RT's trace
  EXPECT_NE(r.out.find("every axis within its limits"), std::string::npos) << r.out;
  const nlohmann::json s = status(shm);
  EXPECT_EQ(s["state"], "idle");
  EXPECT_NEAR(s["position"][0].get<double>(), 12.0, 1e-9);
  EXPECT_NEAR(s["position"][1].get<double>(), 12.0, 1e-9);
  EXPECT_EQ(s["jobs_ended"], 1);
  EXPECT_EQ(s["axes_mask"], 0b101111);  // X Y Z A C: the default machine has no B
  EXPECT_EQ(s["underruns"], 0);
  // it runs again from where the machine stands
  r = lasercnc("send start --wait --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(status(shm)["jobs_ended"], 2);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
  EXPECT_FALSE(fs::exists("/dev/shm" + shm));  // removed on a clean shutdown
}

// The daemon reads a private copy of the program, but its subroutine files
// are looked for beside the original, as for the CLI.
TEST(Lasercncd, ASubroutineFileBesideTheProgramIsFound) {
  const std::string shm = shm_name("/lcnc_e2e_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  fs::create_directories(temp_dir() / "subs_beside");
  write_program("subs_beside/pierce_square.ngc",
                "o<pierce_square> sub\nG0 X#1 Y#1\nM3 S60\nG1 X[#1 + 10] F6000\nG1 Y[#1 + 10]\n"
                "M5\no<pierce_square> endsub\n");
  const fs::path job =
      write_program("subs_beside/job.ngc",
                    "G21 G90 G64 P0.01\no<pierce_square> call [10]\no<pierce_square> call [30]\nM2\n");
  CmdResult r = lasercnc("send load " + job.string() + " --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = lasercnc("send start --wait --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json s = status(shm);
  EXPECT_NEAR(s["position"][0].get<double>(), 40.0, 1e-9);
  EXPECT_NEAR(s["position"][1].get<double>(), 40.0, 1e-9);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// A hole table loaded like a program (the HMI sends the process database's
// holes so): built into the drilling job, checked, run; a bad row is
// refused with its line.
TEST(Lasercncd, RunsAHoleTableAsADrillingJob) {
  const std::string shm = shm_name("/lcnc_e2e_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const std::string header =
      "hole,x_mm,y_mm,z_mm,a_deg,c_deg,feed_mm_min,layer_feed_mm,layer_count,total_depth_mm,power_pct,"
      "start_radius_mm,end_radius_mm,radius_turns,scan_speed_mm_s,wedge_speed_rpm,beam_offset_mm,process,"
      "shape\n";
  const fs::path table =
      write_program("holes.csv", header +
                                     "1,100,100,20,0,0,600,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n"
                                     "2,130,100,20,30,45,600,0.05,2,0.1,70,0.2,0.8,2,150,6000,0,circle,\n");
  CmdResult r = lasercnc("send load " + table.string() + " --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 lines"), std::string::npos) << r.out;  // a line per hole
  r = lasercnc("send start --wait --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("job done"), std::string::npos) << r.out;
  EXPECT_EQ(status(shm)["jobs_ended"], 1);
  // a row out of the travel: refused naming its line, the good table stays loaded
  // hole 7 at X 999.9: its pattern leaves the travel
  const fs::path bad =
      write_program("bad_holes.csv", header +
                                         "1,100,100,20,0,0,600,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n"
                                         "7,999.9,100,20,0,0,600,0.1,2,0.2,80,0.5,0.5,1,200,3000,0,helix,\n");
  r = lasercnc("send load " + bad.string() + " --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad_holes.csv:3"), std::string::npos) << r.err;
  EXPECT_NE(status(shm)["program"].get<std::string>().find("holes.csv"), std::string::npos);
  // nor does a bad G-code program unload it: the next start drills the table again
  const fs::path bad_ngc = write_program("bad.ngc", "G21 G90\nG1 X10 F100 Q\n");
  r = lasercnc("send load " + bad_ngc.string() + " --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.ngc:2:13"), std::string::npos) << r.err;
  r = lasercnc("send start --wait --shm " + shm);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("job done"), std::string::npos) << r.out;
  EXPECT_EQ(status(shm)["jobs_ended"], 2);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

TEST(Lasercncd, HoldResumeEStopResetAndJog) {
  const std::string shm = shm_name("/lcnc_e2e_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path prog =
      write_program("long.ngc", "G21 G90\nG0 X10 Y10\nM3 S50\nG1 X300 F1200\nG1 Y200\nG1 X10\nM5\nM2\n");
  ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm).exit_code, 0);
  ASSERT_EQ(lasercnc("send start --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "running"));
  ASSERT_EQ(lasercnc("send hold --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "feed hold"));
  ASSERT_TRUE(wait_machine_time(shm, 0.3));  // the ramp (0.2 s) is over: at rest
  const double x_held = status(shm)["position"][0].get<double>();
  ASSERT_TRUE(wait_machine_time(shm, 0.1));
  EXPECT_EQ(status(shm)["position"][0].get<double>(), x_held);
  ASSERT_EQ(lasercnc("send resume --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "running"));
  // jog refused while running
  CmdResult r = lasercnc("send jog X 5 --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("jog refused"), std::string::npos) << r.err;
  ASSERT_EQ(lasercnc("send estop --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "e-stop"));
  nlohmann::json s = status(shm);
  EXPECT_EQ(s["fault"], "emergency stop");
  const double x_stop = s["position"][0].get<double>();
  ASSERT_TRUE(wait_machine_time(shm, 0.05));
  EXPECT_EQ(status(shm)["position"][0].get<double>(), x_stop);
  ASSERT_EQ(lasercnc("send reset --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "idle"));
  EXPECT_EQ(status(shm)["job_active"], false);
  // jog: an exact distance
  ASSERT_EQ(lasercnc("send jog X -5.5 --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_machine_time(shm, 0.05));
  ASSERT_TRUE(wait_state(shm, "idle"));
  EXPECT_NEAR(status(shm)["position"][0].get<double>(), x_stop - 5.5, 1e-9);
  // bad commands: a clear answer, nothing changed
  r = lasercnc("send override 500 --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("allowed 0"), std::string::npos) << r.err;
  r = lasercnc("send jog B 1 --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no axis B"), std::string::npos) << r.err;
  r = lasercnc("send jog Q 1 --shm " + shm);
  EXPECT_EQ(r.exit_code, 2);
  r = lasercnc("send fly --shm " + shm);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NEAR(status(shm)["feed_override_target"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// M0 in a program: the daemon's job stops there, at rest, says so, and goes
// on with `send resume`.
TEST(Lasercncd, AProgramPauseWaitsForResume) {
  const std::string shm = shm_name("/lcnc_e2e_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path prog = write_program("pause.ngc", "G21 G90\nG1 X20 F1200\nM0\nG1 X40\nM2\n");
  ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm).exit_code, 0);
  ASSERT_EQ(lasercnc("send start --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "feed hold"));
  nlohmann::json s = status(shm);
  EXPECT_TRUE(s["program_pause"].get<bool>());
  EXPECT_EQ(s["line"], 3);
  EXPECT_NEAR(s["position"][0].get<double>(), 20.0, 1e-9);
  ASSERT_TRUE(wait_machine_time(shm, 0.3));
  EXPECT_NEAR(status(shm)["position"][0].get<double>(), 20.0, 1e-9);  // it waits
  const CmdResult text = lasercnc("status --shm " + shm);
  EXPECT_NE(text.out.find("program pause (M0/M1/M60) at line 3"), std::string::npos) << text.out;
  ASSERT_EQ(lasercnc("send resume --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "idle", 20000ms));
  EXPECT_EQ(status(shm)["last_outcome"], "done");
  s = status(shm);
  EXPECT_FALSE(s["program_pause"].get<bool>());
  EXPECT_NEAR(s["position"][0].get<double>(), 40.0, 1e-9);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

TEST(Lasercncd, SecondDaemonRefusedStaleSegmentRecovered) {
  const std::string shm = shm_name("/lcnc_e2e_");
  {
    Daemon first(shm);
    ASSERT_TRUE(first.ready()) << first.log();
    Daemon second(shm);
    EXPECT_EQ(second.wait_exit(), 1);
    EXPECT_NE(second.log().find("already owned by running process"), std::string::npos) << second.log();
    EXPECT_EQ(first.stop(SIGKILL, true), -1);  // crashes: the segment stays behind
  }
  ASSERT_TRUE(fs::exists("/dev/shm" + shm));
  const CmdResult r = lasercnc("status --shm " + shm);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("stale"), std::string::npos) << r.err;
  Daemon again(shm);
  ASSERT_TRUE(again.ready()) << again.log();
  EXPECT_TRUE(again.logged("recovered a stale segment")) << again.log();
  EXPECT_EQ(again.stop(SIGTERM), 0);
}

// The daemon killed outright in the middle of a job: the CLI says the link
// is gone within a second; a new daemon takes the stale segment over and
// comes up at rest — idle, no job, nothing moving, no program until one is
// loaded anew.
TEST(Lasercncd, KilledMidJobTheRestartedDaemonComesUpAtRest) {
  const std::string shm = shm_name("/lcnc_e2e_");
  const fs::path prog = write_program("long.ngc", "G21 G90\nM3 S50\nG1 X300 F600\nM5\nM2\n");
  {
    Daemon first(shm);
    ASSERT_TRUE(first.ready()) << first.log();
    ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm).exit_code, 0);
    ASSERT_EQ(lasercnc("send start --shm " + shm).exit_code, 0);
    for (const auto deadline = std::chrono::steady_clock::now() + 30s;
         std::chrono::steady_clock::now() < deadline && status(shm)["position"][0].get<double>() < 2.0;)
      std::this_thread::sleep_for(10ms);
    EXPECT_EQ(status(shm)["state"], "running");
    EXPECT_EQ(first.stop(SIGKILL, true), -1);
    const auto killed = std::chrono::steady_clock::now();
    const CmdResult r = lasercnc("status --shm " + shm);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("stale"), std::string::npos) << r.err;
    // at once: the status sees the dead owner, it waits for nothing (a
    // bound a loaded computer keeps too)
    EXPECT_LT(std::chrono::steady_clock::now() - killed, std::chrono::seconds(5));
  }
  Daemon again(shm);
  ASSERT_TRUE(again.ready()) << again.log();
  EXPECT_TRUE(again.logged("recovered a stale segment")) << again.log();
  const nlohmann::json a = status(shm);
  EXPECT_EQ(a["state"], "idle");
  EXPECT_EQ(a["job_active"], false);
  ASSERT_TRUE(wait_machine_time(shm, 0.1));
  EXPECT_EQ(status(shm)["position"], a["position"]);  // not moving
  // and a start needs a program loaded anew
  const CmdResult s = lasercnc("send start --shm " + shm);
  EXPECT_EQ(s.exit_code, 1);
  EXPECT_NE(s.err.find("no program loaded"), std::string::npos) << s.err;
  EXPECT_EQ(again.stop(SIGTERM), 0);
}

// Any process of the group can write the segment. One that leaves the
// command ring's indices corrupt (here: the tail pushed 2^40 ahead, as a
// crashed or hostile sender might) must not hang the daemon in its drain
// (before the check: 2^40 garbage commands) — the daemon drops the ring,
// says so, and answers the next command.
TEST(Lasercncd, ACorruptCommandRingIsDroppedAndTheDaemonAnswersOn) {
  const std::string shm = shm_name("/lcnc_e2e_");
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  {
    const int fd = shm_open(shm.c_str(), O_RDWR, 0);
    ASSERT_GE(fd, 0);
    void* p = mmap(nullptr, sizeof(lcnc::shm::ShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    ASSERT_NE(p, MAP_FAILED);
    auto* block = static_cast<lcnc::shm::ShmBlock*>(p);
    // the ring's layout: head_ at 0, tail_ one cache line on (rt/spsc_ring.h)
    auto* tail = reinterpret_cast<std::atomic<std::uint64_t>*>(reinterpret_cast<char*>(&block->commands) +
                                                               lcnc::rt::kCacheLine);
    tail->fetch_add(std::uint64_t{1} << 40);
    munmap(p, sizeof(lcnc::shm::ShmBlock));
  }
  std::this_thread::sleep_for(100ms);
  const CmdResult r = lasercnc("send override 120 --shm " + shm);
  EXPECT_EQ(r.exit_code, 0) << r.err << d.log();
  // the command is taken when send returns; the status shows it from the
  // next publish on, which a loaded machine can delay
  double target = 0.0;
  for (const auto until = std::chrono::steady_clock::now() + 2s; std::chrono::steady_clock::now() < until;
       std::this_thread::sleep_for(5ms)) {
    target = status(shm)["feed_override_target"].get<double>();
    if (std::abs(target - 1.2) <= 1e-12) break;
  }
  EXPECT_NEAR(target, 1.2, 1e-12);
  EXPECT_NE(d.log().find("command ring's indices were corrupt"), std::string::npos) << d.log();
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// ---- the e-stop's own path, loads off the command thread ----------------

// The segment as a client process maps it (the test is one more sender).
lcnc::shm::ShmClient client(const std::string& shm) {
  auto c = lcnc::shm::ShmClient::open(shm);
  EXPECT_TRUE(static_cast<bool>(c)) << c.error().to_string();
  return std::move(c).value();
}

// Sends a raw command frame as a sender that bypasses `lasercnc send`'s own
// checks would; its seq.
std::uint32_t send_frame(lcnc::shm::ShmClient& c, lcnc::shm::CommandType type, const std::string& text = {},
                         double value = 0.0, std::uint8_t axis = 0, std::uint64_t request_id = 0,
                         std::uint32_t uid = 0) {
  lcnc::shm::Command cmd;
  cmd.type = type;
  cmd.value = value;
  cmd.axis = axis;
  cmd.request_id = request_id;
  cmd.sender_uid = uid;
  cmd.sender_gid = uid;
  std::snprintf(cmd.text, sizeof cmd.text, "%s", text.c_str());
  return c.send(cmd);
}

lcnc::shm::Answer wait_answer(lcnc::shm::ShmClient& c, std::uint32_t seq,
                              std::chrono::milliseconds t = 5000ms) {
  lcnc::shm::Answer a;
  const auto until = std::chrono::steady_clock::now() + t;
  while (!c.answer(seq, a) && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(1ms);
  return a;
}

// A jog of 200 mm (seconds at the jog speed) under way; then `lasercnc send
// estop` stops it: the daemon answers e-stop and the axis stands still short
// of the jog's end. How long the e-stop took, the CLI's start-up included.
// (How soon is the real-time path's own matter, measured on an unloaded
// machine by LasercncdEStop.ReachesTheKernelWithinItsBound; here the e-stop
// must act whatever else the daemon is asked meanwhile.)
std::chrono::steady_clock::duration expect_estop_stops_a_jog(const std::string& shm,
                                                             const std::function<void()>& while_busy = {}) {
  EXPECT_EQ(lasercnc("send jog X 200 --shm " + shm).exit_code, 0);
  EXPECT_TRUE(wait_state(shm, "jog"));
  if (while_busy) while_busy();
  const auto t0 = std::chrono::steady_clock::now();
  const CmdResult r = run_program(std::string("timeout 10 ") + LASERCNC_EXE, "send estop --shm " + shm);
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = status(shm);
  EXPECT_EQ(s["state"], "e-stop");
  const double x = s["position"][0].get<double>();
  EXPECT_LT(x, 200.0);
  EXPECT_TRUE(wait_machine_time(shm, 0.05));
  EXPECT_EQ(status(shm)["position"][0].get<double>(), x);  // not moving
  return took;
}

// The e-stop from `lasercnc send estop` to the RT kernel within kEStopWithin
// (the kernel itself takes it in the next period,
// RtKernelControl.EStopWordActsInTheNextPeriod), plus the CLI's own
// start-up. Label realtime: run alone, after the other tests.
constexpr auto kEStopWithin = 250ms;
TEST(LasercncdEStop, ReachesTheKernelWithinItsBound) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const auto took = expect_estop_stops_a_jog(shm);
  EXPECT_LT(took, kEStopWithin + 500ms) << std::chrono::duration<double>(took).count() << " s";
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// (a) The daemon asked to load a FIFO nobody writes (a sender that skips
// `lasercnc send`'s check): the FIFO is refused without blocking, and the
// e-stop stops a running jog meanwhile.
TEST(LasercncdEStop, ActsWhileALoadOfAFifoIsAsked) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path fifo = temp_dir() / "pipe.ngc";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  auto c = client(shm);
  std::uint32_t seq = 0;
  expect_estop_stops_a_jog(shm, [&] { seq = send_frame(c, lcnc::shm::CommandType::Load, fifo.string()); });
  const lcnc::shm::Answer a = wait_answer(c, seq);
  EXPECT_EQ(a.seq, seq);
  EXPECT_NE(std::string(a.message).find("named pipe"), std::string::npos) << a.message;
  // the CLI refuses it itself, without sending
  const CmdResult r = run_program(std::string("timeout 10 ") + LASERCNC_EXE,
                                  "send load " + fifo.string() + " --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("named pipe"), std::string::npos) << r.err;
  // a directory likewise
  const lcnc::shm::Answer dir =
      wait_answer(c, send_frame(c, lcnc::shm::CommandType::Load, temp_dir().string()));
  EXPECT_NE(std::string(dir.message).find("a directory"), std::string::npos) << dir.message;
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// (b) Another process holds the senders' lock (here: this test process, a
// live one): the e-stop needs no lock; other commands give up after their
// --timeout with a clear message instead of hanging.
TEST(LasercncdEStop, ActsWhileAnotherProcessHoldsTheSendersLock) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  auto c = client(shm);
  pthread_mutex_t* lock = &c.block().senders.lock;
  bool locked = false;
  expect_estop_stops_a_jog(shm, [&] { locked = pthread_mutex_lock(lock) == 0; });
  ASSERT_TRUE(locked);
  const auto t0 = std::chrono::steady_clock::now();
  const CmdResult r = run_program(std::string("timeout 10 ") + LASERCNC_EXE,
                                  "send override 50 --timeout 0.3 --shm " + shm.name());
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("senders' lock"), std::string::npos) << r.err;
  EXPECT_LT(took, 3.0);
  pthread_mutex_unlock(lock);
  EXPECT_EQ(lasercnc("send override 50 --shm " + shm.name()).exit_code, 0);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// (c) A flood of commands from another sender while the e-stop is sent.
TEST(LasercncdEStop, ActsDuringAFloodOfCommands) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  auto c = client(shm);
  std::atomic<bool> flooding{true};
  std::thread flood;
  expect_estop_stops_a_jog(shm, [&] {
    flood = std::thread([&] {
      while (flooding) (void)send_frame(c, lcnc::shm::CommandType::Override, {}, 1.0);
    });
    std::this_thread::sleep_for(50ms);
  });
  flooding = false;
  flood.join();
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// (d) A big program being loaded: the e-stop acts, and the command thread
// answers other commands meanwhile.
TEST(LasercncdEStop, ActsWhileABigProgramLoads) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path big = temp_dir() / "big.ngc";
  {
    std::ofstream out(big);
    out << "G21 G90\nG1 F3000\n";
    for (int i = 0; i < 400000; ++i) out << "G1 X" << (10 + i % 50) << " Y" << (10 + (i / 50) % 50) << "\n";
    out << "M2\n";
  }
  auto c = client(shm);
  std::uint32_t seq = 0;
  expect_estop_stops_a_jog(shm, [&] { seq = send_frame(c, lcnc::shm::CommandType::Load, big.string()); });
  const CmdResult r = lasercnc("send override 80 --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const lcnc::shm::Answer a = wait_answer(c, seq, 60s);
  EXPECT_EQ(a.code, 0) << a.message;
  EXPECT_NE(std::string(a.message).find("400003 lines"), std::string::npos) << a.message;
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// --timeout: more than 0, at most an hour; 1e10 used to overflow into an
// instant "no answer".
TEST(Lasercncd, TimeoutOutOfRangeIsAUsageError) {
  for (const char* t : {"1e10", "0", "-1", "nan", "3601"}) {
    const CmdResult r = lasercnc(std::string("send stop --timeout ") + t + " --shm /lcnc_e2e_nobody_here");
    EXPECT_EQ(r.exit_code, 2) << t << ": " << r.err;
    EXPECT_NE(r.err.find("at most 3600"), std::string::npos) << r.err;
  }
}

// ---- what a load reads, what a job runs --------------------------------

// The job runs the program as it was checked at its load: the file
// rewritten afterwards (here: beyond the travel) changes nothing.
TEST(Lasercncd, RunsTheProgramAsLoadedWhateverTheFileBecomes) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path prog = write_program("edited.ngc", kShortJob);
  ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm.name()).exit_code, 0);
  std::ofstream(prog) << "G21 G90\nG1 X5 F3000\nG1 X9999\nM2\n";  // E304 at line 3
  CmdResult r = lasercnc("send start --wait --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("job done"), std::string::npos) << r.out;
  nlohmann::json s = status(shm);
  EXPECT_NEAR(s["position"][0].get<double>(), 12.0, 1e-9);  // kShortJob's end
  // replaced while it runs: the same
  ASSERT_EQ(lasercnc("send jog X -2 --shm " + shm.name()).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "idle"));
  auto job =
      std::async(std::launch::async, [&] { return lasercnc("send start --wait --shm " + shm.name()); });
  std::ofstream(prog.string() + ".new") << "G21 G90\nG1 X9999 F3000\nM2\n";
  fs::rename(prog.string() + ".new", prog);
  r = job.get();
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NEAR(status(shm)["position"][0].get<double>(), 12.0, 1e-9);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// A file that is not a program is refused without its bytes in the answer
// (the daemon may read what its sender may not); the sender's uid, the
// program folders limit what may be loaded.
TEST(Lasercncd, LoadsOnlyProgramsTheSenderMayReadAndNeverEchoesOtherFiles) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  const fs::path dir = temp_dir() / "programs";
  fs::create_directories(dir);
  Daemon d(shm, {"--programs", dir.string()});
  ASSERT_TRUE(d.ready()) << d.log();
  // shadow-like text, and binary
  const fs::path secret = write_program("programs/shadow.ngc", "root:$6$s3cr3tHASH:19000:0:99999:7:::\n");
  CmdResult r = lasercnc("send load " + secret.string() + " --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a G-code program"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("s3cr3t"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("root"), std::string::npos) << r.err;
  const fs::path bin = dir / "blob.ngc";
  std::ofstream(bin, std::ios::binary) << std::string(
      "G1\x7f"
      "ELF\x02\x01\x01\x00s3cr3t",
      16);
  r = lasercnc("send load " + bin.string() + " --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a G-code program"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("s3cr3t"), std::string::npos) << r.err;
  // outside the program folders
  const fs::path outside = write_program("outside.ngc", kShortJob);
  r = lasercnc("send load " + outside.string() + " --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("outside the program folders"), std::string::npos) << r.err;
  // a file its sender may not read (mode 0600, root's; the sender uid 65534)
  const fs::path mine = write_program("programs/root_only.ngc", kShortJob);
  fs::permissions(mine, fs::perms::owner_read | fs::perms::owner_write);
  auto c = client(shm);
  lcnc::shm::Answer a =
      wait_answer(c, send_frame(c, lcnc::shm::CommandType::Load, mine.string(), 0.0, 0, 0, 65534));
  EXPECT_NE(a.code, 0);
  EXPECT_NE(std::string(a.message).find("may not read"), std::string::npos) << a.message;
  // and a program in the folder loads
  r = lasercnc("send load " + mine.string() + " --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// Every file a daemon job or MDI command reads passes the load's policy —
// inside the program folders, readable by the sender — subroutine files as
// much as the program: a less-privileged sender runs no file it may not
// read, and no message shows what such a file holds. The property:
// subroutine names by MDI and by a loaded caller from uid 65534 (each name
// by both routes, then 16 random), each refused, the machine still.
TEST(Lasercncd, ASubroutineFileIsReadOnlyUnderTheLoadsPolicy) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  const fs::path dir = temp_dir() / "programs";
  const fs::path out = temp_dir() / "outside";
  fs::create_directories(dir);
  fs::create_directories(out);
  Daemon d(shm, {"--programs", dir.string()});
  ASSERT_TRUE(d.ready()) << d.log();
  // each file defines its sub under every name a call may give it (a path
  // included), so only the policy, never the name's lookup, keeps it from
  // running
  const auto sub_text = [](const std::vector<std::string>& names) {
    std::string text = "(s3cr3t of " + names.front() + ")\n";
    for (const std::string& n : names) text += "o<" + n + "> sub\nG1 X7 F600\no<" + n + "> endsub\n";
    return text + "M2\n";
  };
  std::ofstream(dir / "root_only.ngc") << sub_text({"root_only", "../programs/root_only"});
  fs::permissions(dir / "root_only.ngc", fs::perms::owner_read | fs::perms::owner_write);
  std::ofstream(out / "outer.ngc") << sub_text({"outer", (out / "outer").string(), "../outside/outer"});
  fs::create_symlink(out / "outer.ngc", dir / "link_out.ngc");
  std::ofstream(dir / "shared.ngc") << sub_text({"shared"});
  auto c = client(shm);
  const auto as_nobody = [&](lcnc::shm::CommandType t, const std::string& text) {
    return wait_answer(c, send_frame(c, t, text, 0.0, 0, 0, 65534));
  };
  const auto caller = [&](const std::string& name) {
    const fs::path p = dir / ("call_" + std::to_string(std::hash<std::string>{}(name)) + ".ngc");
    std::ofstream(p) << "G21 G90\no<" << name << "> call\nM2\n";
    return p;
  };
  // the positive control: a readable subroutine in the folder, for nobody
  lcnc::shm::Answer a = as_nobody(lcnc::shm::CommandType::Load, caller("shared").string());
  EXPECT_EQ(a.code, 0) << a.message;
  // the findings: MDI of an absolute path and of ../, a loaded program
  // calling a root-only file and one behind a link out of the folder
  const std::vector<std::string> names{(out / "outer").string(),
                                       "../outside/outer",
                                       "../programs/root_only",
                                       "root_only",
                                       "link_out",
                                       "/etc/passwd"};
  std::mt19937 rng(7);
  for (std::size_t k = 0; k < 2 * names.size() + 16; ++k) {
    // every name by either route, then 16 random ones
    const bool every = k < 2 * names.size();
    const std::string& name = every ? names[k / 2] : names[rng() % names.size()];
    const bool mdi = every ? k % 2 == 0 : rng() % 2 == 0;
    SCOPED_TRACE((mdi ? "mdi o<" : "load of a call of o<") + name + ">");
    a = mdi ? as_nobody(lcnc::shm::CommandType::Mdi, "o<" + name + "> call")
            : as_nobody(lcnc::shm::CommandType::Load, caller(name).string());
    EXPECT_NE(a.code, 0) << a.message;
    EXPECT_EQ(std::string(a.message).find("s3cr3t"), std::string::npos) << a.message;
    EXPECT_EQ(std::string(a.message).find("root:"), std::string::npos) << a.message;
  }
  const nlohmann::json s = status(shm.name());
  EXPECT_EQ(s["position"][0].get<double>(), 0.0) << "nothing ran";
  EXPECT_FALSE(s["job_active"].get<bool>());
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// A load whose check would run for hours (an endless loop on a machine
// whose work budget allows 100,000 h) holds no one up: stop cancels it —
// answered as cancelled, and the next load goes through — and SIGTERM ends
// the daemon at once, whatever its loader is doing (systemd's stop).
TEST(Lasercncd, ALongLoadIsCancelledByStopAndSigtermEndsTheDaemonDuringOne) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  std::string cfg = slurp(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
  cfg.replace(cfg.find("[machine]\n"), 10, "[machine]\nprogram_time_limit_h = 100000\n");
  const fs::path machine = write_program("patient.toml", cfg);
  const fs::path endless =
      write_program("endless.ngc", "G21 G90 F6000\no1 while [1]\nG1 X10\nG1 X0\no1 endwhile\nM2\n");
  Daemon d(shm, {"--machine", machine.string()});
  ASSERT_TRUE(d.ready()) << d.log();
  auto c = client(shm);
  const std::uint32_t load = send_frame(c, lcnc::shm::CommandType::Load, endless.string());
  // the load is in progress: a second one is refused for it (an event, not a wait)
  const auto load_in_progress = [&] {
    const lcnc::shm::Answer other =
        wait_answer(c, send_frame(c, lcnc::shm::CommandType::Load, endless.string()));
    return std::string(other.message).find("another load is in progress") != std::string::npos;
  };
  EXPECT_TRUE(load_in_progress());
  lcnc::shm::Answer a;
  EXPECT_FALSE(c.answer(load, a)) << a.message;
  EXPECT_EQ(lasercnc("send stop --shm " + shm.name()).exit_code, 0);
  a = wait_answer(c, load, 10s);  // bounds a failure only
  EXPECT_EQ(a.seq, load);
  EXPECT_NE(a.code, 0);
  EXPECT_NE(std::string(a.message).find("cancelled"), std::string::npos) << a.message;
  const fs::path fine = write_program("fine.ngc", kShortJob);
  CmdResult r = lasercnc("send load " + fine.string() + " --shm " + shm.name());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // again, and SIGTERM meanwhile
  (void)send_frame(c, lcnc::shm::CommandType::Load, endless.string());
  EXPECT_TRUE(load_in_progress());
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ figures  ] SIGTERM during a load: the daemon ended in %.3f s\n", took);
  EXPECT_LT(took, 5.0);  // about 0.01 s; the bound is far inside systemd's stop timeout (90 s)
}

// ---- answers ---------------------------------------------------------------

// Twenty senders at once: each gets its own answer.
TEST(Lasercncd, ConcurrentSendersEachGetTheirOwnAnswer) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  std::vector<std::future<CmdResult>> clients;
  const fs::path dir = temp_dir();
  for (int i = 0; i < 20; ++i)
    clients.push_back(std::async(std::launch::async, [&, i] {
      // each its own output files (run_program's are the test's, one set)
      const fs::path out = dir / ("out_" + std::to_string(i)), err = dir / ("err_" + std::to_string(i));
      const std::string cmd = std::string("timeout 20 ") + LASERCNC_EXE + " send override " +
                              std::to_string(100 + i) + " --shm " + shm.name() + " >" + out.string() + " 2>" +
                              err.string() + " </dev/null";
      const int st = std::system(cmd.c_str());
      return CmdResult{WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(out), slurp(err)};
    }));
  for (int i = 0; i < 20; ++i) {
    const CmdResult r = clients[i].get();
    EXPECT_EQ(r.exit_code, 0) << i << ": " << r.err;
    EXPECT_NE(r.out.find("override " + std::to_string(100 + i) + " %"), std::string::npos)
        << i << ": " << r.out;
  }
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// A request sent again with its id (a retry after no answer) is answered,
// not executed again: one jog, not two.
TEST(Lasercncd, ARetriedRequestIsExecutedOnce) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  auto c = client(shm);
  const std::uint64_t id = 0x5eed0000'00000001ull;
  const lcnc::shm::Answer first = wait_answer(c, send_frame(c, lcnc::shm::CommandType::Jog, {}, 1.0, 0, id));
  ASSERT_EQ(first.code, 0) << first.message;
  ASSERT_TRUE(wait_state(shm, "idle"));
  const lcnc::shm::Answer again = wait_answer(c, send_frame(c, lcnc::shm::CommandType::Jog, {}, 1.0, 0, id));
  EXPECT_EQ(again.code, 0);
  EXPECT_STREQ(again.message, first.message);
  ASSERT_TRUE(wait_machine_time(shm, 0.1));
  ASSERT_TRUE(wait_state(shm, "idle"));
  EXPECT_NEAR(status(shm)["position"][0].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// A stopped job is no job done: `send start --wait` exits 3 and says where
// it stopped; the status says "stopped", not 100 %.
TEST(Lasercncd, AStoppedJobIsReportedStopped) {
  const e2e::ShmGuard shm(shm_name("/lcnc_e2e_"));
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path prog = write_program("long.ngc", "G21 G90\nM3 S50\nG1 X300 F1200\nM5\nM2\n");
  ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm.name()).exit_code, 0);
  auto job =
      std::async(std::launch::async, [&] { return lasercnc("send start --wait --shm " + shm.name()); });
  ASSERT_TRUE(wait_state(shm, "running"));
  std::this_thread::sleep_for(200ms);
  ASSERT_EQ(lasercnc("send stop --shm " + shm.name()).exit_code, 0);
  const CmdResult r = job.get();
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.out.find("job stopped at line 3"), std::string::npos) << r.out;
  const nlohmann::json s = status(shm);
  EXPECT_EQ(s["last_outcome"], "stopped");
  EXPECT_LT(s["progress"].get<double>(), 1.0);
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

// Every test removes the segments it made, also when a daemon is killed.
TEST(Lasercncd, AKilledDaemonsSegmentIsRemovedByTheTest) {
  const std::string shm = shm_name("/lcnc_e2e_");
  {
    Daemon d(shm);
    ASSERT_TRUE(d.ready()) << d.log();
    EXPECT_EQ(d.stop(SIGKILL), -1);
  }
  EXPECT_FALSE(fs::exists("/dev/shm" + shm));
}

// A supervisor (a test, systemd, a package script) may send SIGTERM the
// moment the segment appears, while the daemon is still starting its
// threads: that too is a clean shutdown (exit 0, segment removed), never a
// death by the signal's default action.
TEST(Lasercncd, SigtermTheMomentTheSegmentAppearsIsACleanShutdown) {
  for (int round = 0; round < 5; ++round) {
    const std::string shm = shm_name("/lcnc_e2e_") + "_" + std::to_string(round);
    Daemon d(shm);
    const auto until = std::chrono::steady_clock::now() + 10s;
    while (!fs::exists("/dev/shm" + shm) && std::chrono::steady_clock::now() < until) {
    }
    ASSERT_TRUE(fs::exists("/dev/shm" + shm)) << d.log();
    EXPECT_EQ(d.stop(SIGTERM, /*keep_segment=*/true), 0) << "round " << round << ": " << d.log();
    EXPECT_FALSE(fs::exists("/dev/shm" + shm)) << "round " << round;
    shm_unlink(shm.c_str());
  }
}

const auto* const kNoLeaks = ::testing::AddGlobalTestEnvironment(new e2e::NoLeakedSegments);

// A command the kernel cannot take is refused, never answered as done. With
// --hal and no HAL component loaded nothing takes the kernel's commands, so
// its ring of 16 fills: the 17th hold, a resume, a stop are refused. (An
// e-stop never waits in the ring: the CLI's, the HMI's and, when the ring is
// full, the Modbus slave's go through the e-stop word.)
TEST(Lasercncd, ACommandTheKernelCannotTakeIsRefusedNotAnsweredAsDone) {
  const std::string shm = shm_name("/lcnc_e2e_");
  struct Unlink {
    std::string name;
    ~Unlink() { shm_unlink(name.c_str()); }
  } hal_segment{shm + ".hal"};  // the daemon's segment for the component, left by its SIGKILL
  Daemon d(shm, {"--hal", "--machine", std::string(LCNC_SOURCE_DIR) + "/share/hal/sim/machine.toml"});
  ASSERT_TRUE(d.ready()) << d.log();
  for (int i = 0; i < 16; ++i) {
    const CmdResult r = lasercnc("send hold --shm " + shm);
    ASSERT_EQ(r.exit_code, 0) << i << ": " << r.out << r.err;
  }
  for (const char* c : {"hold", "resume", "stop"}) {
    const CmdResult r = lasercnc(std::string("send ") + c + " --shm " + shm);
    EXPECT_NE(r.exit_code, 0) << c;
    EXPECT_NE((r.out + r.err).find(std::string(c) + " refused: the kernel has not taken the 16 commands"),
              std::string::npos)
        << r.out << r.err;
  }
}

// The simulated clock is the simulated machine's: with --hal, HAL's thread
// keeps the time, and asking for both is a usage error.
TEST(Lasercncd, TheSimulatedClockIsRefusedWithHal) {
  const CmdResult r = run_program(LASERCNCD_EXE, "--simulated-clock --hal --shm /lcnc_e2e_never");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("HAL's thread keeps the time"), std::string::npos) << r.err;
}

TEST(Lasercncd, StatusWithoutDaemonSaysSo) {
  const CmdResult r = lasercnc("status --shm /lcnc_e2e_nobody_here");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no daemon"), std::string::npos) << r.err;
}

}  // namespace
