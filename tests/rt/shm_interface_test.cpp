#include "rt/shm_interface.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <grp.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstring>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace lcnc::shm {
namespace {

std::string unique_name(const char* tag) {
  return "/lasercnc_test_" + std::string(tag) + "_" + std::to_string(getpid());
}

TEST(ShmInterface, ClientInAnotherProcessSeesStatusAndSendsCommands) {
  const std::string name = unique_name("xproc");
  auto owner = ShmOwner::create(name);
  ASSERT_TRUE(owner) << owner.error().to_string();
  Status st;
  st.state = MachineState::Running;
  st.line = 42;
  st.pos[0] = 12.5;
  owner->block().status.store(st);

  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // the "HMI": read status, send a command, exit with a verdict
    auto client = ShmClient::open(name);
    if (!client) _exit(10);
    Status seen;
    if (!client->block().status.load(seen) || seen.line != 42 || seen.pos[0] != 12.5) _exit(11);
    if (!client->owner_alive()) _exit(12);
    Command c;
    c.type = CommandType::Override;
    c.value = 1.25;
    c.seq = 7;
    if (!client->block().commands.try_push(c)) _exit(13);
    _exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  Command got;
  ASSERT_TRUE(owner->block().commands.try_pop(got));
  EXPECT_EQ(got.type, CommandType::Override);
  EXPECT_DOUBLE_EQ(got.value, 1.25);
  EXPECT_EQ(got.seq, 7u);
}

// Several sender processes (HMIs, `lasercnc send`) at once: every command
// arrives whole, each with its own sequence number; a sender that dies
// holding the senders' lock blocks nobody.
TEST(ShmInterface, ManySendersInManyProcessesTakeTurnsWithUniqueNumbers) {
  constexpr int kSenders = 4, kEach = 300;
  const std::string name = unique_name("senders");
  auto owner = ShmOwner::create(name);
  ASSERT_TRUE(owner) << owner.error().to_string();
  std::vector<pid_t> kids;
  for (int k = 0; k < kSenders; ++k) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      auto client = ShmClient::open(name);
      if (!client) _exit(10);
      for (int i = 0; i < kEach; ++i) {
        Command c;
        c.type = CommandType::Jog;
        c.axis = static_cast<std::uint8_t>(k);
        c.value = i;
        while (client->send(c) == 0) std::this_thread::sleep_for(std::chrono::microseconds(50));  // full
      }
      _exit(0);
    }
    kids.push_back(pid);
  }
  std::set<std::uint32_t> seqs;
  std::array<int, kSenders> next{};  // each sender's commands arrive in its order
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (seqs.size() < static_cast<std::size_t>(kSenders * kEach) &&
         std::chrono::steady_clock::now() < until) {
    Command c;
    if (!owner->block().commands.try_pop(c)) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));
      continue;
    }
    EXPECT_TRUE(seqs.insert(c.seq).second) << "seq " << c.seq << " twice";
    ASSERT_LT(c.axis, kSenders);
    EXPECT_EQ(c.value, next[c.axis]++);
  }
  for (pid_t p : kids) {
    int st = 0;
    waitpid(p, &st, 0);
    EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  }
  EXPECT_EQ(seqs.size(), static_cast<std::size_t>(kSenders * kEach));
  EXPECT_EQ(seqs.count(0u), 0u);
  // a sender killed while it holds the lock
  const pid_t dead = fork();
  ASSERT_GE(dead, 0);
  if (dead == 0) {
    auto client = ShmClient::open(name);
    if (!client) _exit(10);
    pthread_mutex_lock(&client->block().senders.lock);
    _exit(0);  // dies holding it
  }
  waitpid(dead, nullptr, 0);
  auto client = ShmClient::open(name);
  ASSERT_TRUE(client);
  Command c;
  c.type = CommandType::Stop;
  EXPECT_NE(client->send(c), 0u);  // recovered, not blocked
  EXPECT_NE(client->send(c), 0u);
}

TEST(ShmInterface, SegmentIsMode0660AndVersioned) {
  const std::string name = unique_name("mode");
  auto owner = ShmOwner::create(name);
  ASSERT_TRUE(owner);
  const int fd = shm_open(name.c_str(), O_RDONLY, 0);
  ASSERT_GE(fd, 0);
  struct stat s {};
  ASSERT_EQ(fstat(fd, &s), 0);
  close(fd);
  EXPECT_EQ(s.st_mode & 0777, 0660u);
  EXPECT_EQ(owner->block().header.version, kVersion);
  EXPECT_EQ(owner->block().header.owner_pid, getpid());
}

// Mode 0660 means something only for a user outside the owner's group: a
// child process that gives up root for nobody:nogroup cannot open the
// segment (and says why), while the owner's side can.
TEST(ShmInterface, AUserOutsideTheGroupIsRefused) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to become another user (CI runs as root)";
  const std::string name = unique_name("others");
  auto owner = ShmOwner::create(name);
  ASSERT_TRUE(owner);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (setgroups(0, nullptr) != 0 || setgid(65534) != 0 || setuid(65534) != 0) _exit(10);
    auto c = ShmClient::open(name);
    if (c) _exit(11);  // opened: the mode did not protect it
    if (c.error().message.find("ermission") == std::string::npos) _exit(12);
    _exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "10: could not drop root, 11: opened, 12: no reason given";
  EXPECT_TRUE(ShmClient::open(name));
}

// What another process of the group may leave in the blocks: texts without
// their NUL, a bool byte of 0xFF, an axis index of 100. A reader's copy,
// sanitized, reads within its fields.
TEST(ShmInterface, ABlockWrittenWithAnythingIsSafeToReadOnceSanitized) {
  JobStatus j;
  std::memset(static_cast<void*>(&j), 'A', sizeof j);
  std::memset(static_cast<void*>(&j.job_active), 0xFF, 1);
  sanitize(j);
  EXPECT_EQ(std::strlen(j.message), sizeof j.message - 1);
  EXPECT_EQ(std::strlen(j.program), sizeof j.program - 1);
  std::uint8_t b = 0;
  std::memcpy(&b, &j.job_active, 1);
  EXPECT_EQ(b, 1u);
  Event e;
  std::memset(static_cast<void*>(&e), 'B', sizeof e);
  sanitize(e);
  EXPECT_EQ(std::strlen(e.text), sizeof e.text - 1);
  Status st;
  st.fault_axis = 100;
  sanitize(st);
  EXPECT_EQ(st.fault_axis, -1);
  st.fault_axis = 2;
  sanitize(st);
  EXPECT_EQ(st.fault_axis, 2);
}

TEST(ShmInterface, SecondOwnerIsRefusedWhileTheFirstLives) {
  const std::string name = unique_name("twice");
  auto first = ShmOwner::create(name);
  ASSERT_TRUE(first);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    auto second = ShmOwner::create(name);
    _exit(second ? 1 : (second.error().message.find("already owned") != std::string::npos ? 0 : 2));
  }
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(ShmInterface, StaleSegmentOfACrashedOwnerIsRecovered) {
  const std::string name = unique_name("stale");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // an owner that dies without cleaning up
    auto owner = ShmOwner::create(name);
    _exit(owner ? 0 : 1);  // _exit: no destructor, the segment stays
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_EQ(WEXITSTATUS(status), 0);
  {
    auto client = ShmClient::open(name);
    ASSERT_TRUE(client);
    EXPECT_FALSE(client->owner_alive());  // the HMI can tell the link is lost
  }
  auto owner = ShmOwner::create(name);
  ASSERT_TRUE(owner) << owner.error().to_string();
  EXPECT_TRUE(owner->recovered_stale());
  Status st;
  EXPECT_TRUE(owner->block().status.load(st));
  EXPECT_EQ(st.state, MachineState::Idle);  // comes up safe, not moving
}

TEST(ShmInterface, OpeningWithoutADaemonSaysSo) {
  auto client = ShmClient::open(unique_name("none"));
  ASSERT_FALSE(client);
  EXPECT_NE(client.error().message.find("is lasercncd running?"), std::string::npos);
}

}  // namespace
}  // namespace lcnc::shm
