// End to end: lasercncd hosts the planner and RT threads on the simulated
// machine; `lasercnc status` and `lasercnc send` drive it through the
// shared-memory segment, as an HMI would — real processes, real POSIX shm.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

extern char** environ;

#include "e2e_support.h"
#include "rt/shm_interface.h"

namespace {

using namespace e2e;
using namespace std::chrono_literals;

std::string shm_name() {
  return "/lcnc_e2e_" + std::to_string(getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

nlohmann::json status(const std::string& shm) {
  const CmdResult r = lasercnc("status --json --shm " + shm);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out, nullptr, false);
}

bool wait_state(const std::string& shm, const std::string& state, std::chrono::milliseconds t = 5000ms) {
  const auto until = std::chrono::steady_clock::now() + t;
  while (std::chrono::steady_clock::now() < until) {
    const nlohmann::json s = status(shm);
    if (s.is_object() && s["state"] == state) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

fs::path write_program(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
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
  const std::string shm = shm_name();
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

// A hole table loaded like a program (the HMI sends the process database's
// holes so): built into the drilling job, checked, run; a bad row is
// refused with its line.
TEST(Lasercncd, RunsAHoleTableAsADrillingJob) {
  const std::string shm = shm_name();
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const std::string header =
      "hole,x_mm,y_mm,z_mm,a_deg,c_deg,feed_mm_min,layer_feed_mm,layer_count,total_depth_mm,power_pct,"
      "start_radius_mm,end_radius_mm,radius_turns,scan_speed_mm_s,wedge_speed_rpm,beam_offset_mm,process,shape\n";
  const fs::path table = write_program("holes.csv", header +
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
  const fs::path bad = write_program("bad_holes.csv", header +
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
  const std::string shm = shm_name();
  Daemon d(shm);
  ASSERT_TRUE(d.ready()) << d.log();
  const fs::path prog = write_program("long.ngc",
                                      "G21 G90\nG0 X10 Y10\nM3 S50\nG1 X300 F1200\nG1 Y200\nG1 X10\nM5\nM2\n");
  ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm).exit_code, 0);
  ASSERT_EQ(lasercnc("send start --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "running"));
  ASSERT_EQ(lasercnc("send hold --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "feed hold"));
  std::this_thread::sleep_for(300ms);  // the ramp (0.2 s) is over: at rest
  const double x_held = status(shm)["position"][0].get<double>();
  std::this_thread::sleep_for(100ms);
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
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(status(shm)["position"][0].get<double>(), x_stop);
  ASSERT_EQ(lasercnc("send reset --shm " + shm).exit_code, 0);
  ASSERT_TRUE(wait_state(shm, "idle"));
  EXPECT_EQ(status(shm)["job_active"], false);
  // jog: an exact distance
  ASSERT_EQ(lasercnc("send jog X -5.5 --shm " + shm).exit_code, 0);
  std::this_thread::sleep_for(50ms);
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

TEST(Lasercncd, SecondDaemonRefusedStaleSegmentRecovered) {
  const std::string shm = shm_name();
  {
    Daemon first(shm);
    ASSERT_TRUE(first.ready()) << first.log();
    Daemon second(shm);
    EXPECT_EQ(second.wait_exit(), 1);
    EXPECT_NE(second.log().find("already owned by running process"), std::string::npos)
        << second.log();
    EXPECT_EQ(first.stop(SIGKILL), -1);  // crashes: the segment stays behind
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
  const std::string shm = shm_name();
  const fs::path prog = write_program("long.ngc", "G21 G90\nM3 S50\nG1 X300 F600\nM5\nM2\n");
  {
    Daemon first(shm);
    ASSERT_TRUE(first.ready()) << first.log();
    ASSERT_EQ(lasercnc("send load " + prog.string() + " --shm " + shm).exit_code, 0);
    ASSERT_EQ(lasercnc("send start --shm " + shm).exit_code, 0);
    for (int i = 0; i < 300 && status(shm)["position"][0].get<double>() < 2.0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(status(shm)["state"], "running");
    EXPECT_EQ(first.stop(SIGKILL), -1);
    const auto killed = std::chrono::steady_clock::now();
    const CmdResult r = lasercnc("status --shm " + shm);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("stale"), std::string::npos) << r.err;
    EXPECT_LT(std::chrono::steady_clock::now() - killed, std::chrono::seconds(1));
  }
  Daemon again(shm);
  ASSERT_TRUE(again.ready()) << again.log();
  EXPECT_TRUE(again.logged("recovered a stale segment")) << again.log();
  const nlohmann::json a = status(shm);
  EXPECT_EQ(a["state"], "idle");
  EXPECT_EQ(a["job_active"], false);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
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
  const std::string shm = shm_name();
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
  for (const auto until = std::chrono::steady_clock::now() + 2s;
       std::chrono::steady_clock::now() < until; std::this_thread::sleep_for(5ms)) {
    target = status(shm)["feed_override_target"].get<double>();
    if (std::abs(target - 1.2) <= 1e-12) break;
  }
  EXPECT_NEAR(target, 1.2, 1e-12);
  EXPECT_NE(d.log().find("command ring's indices were corrupt"), std::string::npos) << d.log();
  EXPECT_EQ(d.stop(SIGTERM), 0) << d.log();
}

TEST(Lasercncd, StatusWithoutDaemonSaysSo) {
  const CmdResult r = lasercnc("status --shm /lcnc_e2e_nobody_here");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no daemon"), std::string::npos) << r.err;
}

}  // namespace
