// lasercnc-devices end to end: start the executable, read where it put the
// devices from its output, talk to the laser over Modbus TCP and to the
// probe over its serial pty, then stop it with SIGTERM. Skipped (with the
// reason) when the executable has not been built, e.g. when only
// drivers_tests was.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

#include "drivers/serial/probe_client.h"
#include "modbus_test_support.h"

extern char** environ;

namespace lcnc::drivers {
namespace {

using namespace testing;

const std::string kExe = std::string(LCNC_BINARY_DIR) + "/app/lasercnc-devices";

TEST(LasercncDevicesApp, StartsTheDevicesAndStopsOnSigterm) {
  if (::access(kExe.c_str(), X_OK) != 0) GTEST_SKIP() << kExe << " not built";
  int out[2];
  ASSERT_EQ(::pipe(out), 0);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&fa, out[0]);
  char* argv[] = {const_cast<char*>(kExe.c_str()), const_cast<char*>("--seconds"), const_cast<char*>("30"),
                  nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, kExe.c_str(), &fa, nullptr, argv, environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  ::close(out[1]);
  // A failed assertion below must not leave the devices running.
  struct Reaper {
    pid_t pid;
    ~Reaper() {
      if (pid > 0 && ::kill(pid, SIGKILL) == 0) ::waitpid(pid, nullptr, 0);
    }
  } reaper{pid};

  // Read until the banner's last line (bounded: 5 s).
  std::string text;
  const auto end = std::chrono::steady_clock::now() + 5s;
  while (text.find("stopping after") == std::string::npos && std::chrono::steady_clock::now() < end) {
    pollfd p{out[0], POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    char buf[512];
    const ssize_t n = ::read(out[0], buf, sizeof buf);
    if (n <= 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  // "  laser_source         unit 2  tcp 127.0.0.1:40123" and
  // "  probe_3d             serial /dev/pts/7 (…)" (no std::regex: gcc 12
  // warns inside it under ASan at -O2)
  const std::size_t laser_at = text.find("laser_source");
  const std::size_t tcp_at = text.find("tcp 127.0.0.1:", laser_at);
  ASSERT_TRUE(laser_at != std::string::npos && tcp_at != std::string::npos) << text;
  const std::size_t serial_at = text.find("serial /dev/");
  ASSERT_NE(serial_at, std::string::npos) << text;
  const std::size_t path_at = serial_at + 7;
  const std::string probe_path = text.substr(path_at, text.find(' ', path_at) - path_at);

  Endpoint ep;
  ep.port = static_cast<std::uint16_t>(std::stoi(text.substr(tcp_at + 14)));
  ModbusMaster m(shipped("laser_source"), quick_master(ep));
  ASSERT_TRUE(m.start().ok());
  auto rated = m.read("rated_power_w").get();
  ASSERT_TRUE(rated.ok()) << rated.error().to_string();
  EXPECT_EQ(rated.value(), 50.0);

  ProbeClientConfig pc;
  pc.device = probe_path;
  ProbeClient client(shipped("probe_3d"), pc);
  ASSERT_TRUE(client.open().ok());
  auto point = client.measure();
  EXPECT_TRUE(point.ok()) << point.error().to_string();
  m.stop();
  client.close();

  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  reaper.pid = 0;
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  ::close(out[0]);
}

}  // namespace
}  // namespace lcnc::drivers
