// What the end-to-end tests share: running the lasercnc CLI as a user does
// (a real process, its stdout, stderr and exit code) in a temporary folder
// of the test's own.
#pragma once

#include <gtest/gtest.h>
#include <algorithm>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace e2e {

namespace fs = std::filesystem;

struct CmdResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / ("lasercnc_e2e_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::create_directories(d);
  return d;
}

// The repository's share/ folder and the sample part the DXF tests cut.
inline const std::string kShare = std::string(LCNC_SOURCE_DIR) + "/share";
inline const std::string kSample = kShare + "/examples/plate_decompose.dxf";

// A shared-memory name of this process and test: `prefix` + pid + test name.
inline std::string shm_name(const std::string& prefix) {
  return prefix + std::to_string(::getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// `text` written to `name` in the test's temporary folder.
inline fs::path write_program(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
}

// Runs `exe` with `args` (through the shell) as a user does.
inline CmdResult run_program(const std::string& exe, const std::string& args) {
  const fs::path dir = temp_dir();
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = exe + " " + args + " >" + out.string() + " 2>" + err.string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  CmdResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

inline CmdResult lasercnc(const std::string& args) { return run_program(LASERCNC_EXE, args); }

// A shared-memory segment name of the test's own, removed when the guard
// goes, whatever happened to the daemon that made it (killed, crashed, the
// test failed half-way).
class ShmGuard {
 public:
  explicit ShmGuard(std::string name) : name_(std::move(name)) {}
  ~ShmGuard() { shm_unlink(name_.c_str()); }
  ShmGuard(const ShmGuard&) = delete;
  ShmGuard& operator=(const ShmGuard&) = delete;
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  operator const std::string&() const noexcept { return name_; }  // NOLINT: stands for the name

 private:
  std::string name_;
};

// Segments this test process left in /dev/shm: names that begin with "lcnc"
// and carry "_<pid>" (the tests' naming).
inline std::vector<std::string> leaked_segments() {
  std::vector<std::string> out;
  const std::string mark = "_" + std::to_string(::getpid());
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/dev/shm", ec)) {
    const std::string n = e.path().filename().string();
    const std::size_t at = n.find(mark);
    if (n.starts_with("lcnc") && at != std::string::npos &&
        (at + mark.size() == n.size() || n[at + mark.size()] == '_'))
      out.push_back(n);
  }
  return out;
}

// Fails the run if a test left a segment behind.
class NoLeakedSegments : public ::testing::Environment {
 public:
  void TearDown() override {
    for (const std::string& n : leaked_segments())
      ADD_FAILURE() << "shared memory left behind: /dev/shm/" << n;
  }
};

// Starts args[0] (a path) with args as its argv, stdin from `in` (a file
// descriptor; −1: /dev/null) and stdout and stderr to the files given (the
// same one may be both): its pid, or −1.
inline pid_t spawn(std::vector<std::string> args, const fs::path& out, const fs::path& err, int in = -1) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (in >= 0)
    posix_spawn_file_actions_adddup2(&fa, in, 0);
  else
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (err == out)
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
  else
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  if (posix_spawn(&pid, args[0].c_str(), &fa, nullptr, argv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

// A lasercncd child process on its own segment (LASERCNCD_EXE), its stderr
// in a log file of the test's folder; `extra` are further arguments. It runs
// on the simulated clock at the wall clock's pace (--simulated-clock): jobs
// take their real time, commands come in the test's time, and a loaded
// computer slows the machine instead of running its buffer dry (with
// --hal, HAL's thread keeps the time).
class Daemon {
 public:
  explicit Daemon(std::string shm, std::vector<std::string> extra = {})
      : shm_(std::move(shm)), log_(temp_dir() / ("daemon_" + std::to_string(++count_) + ".log")) {
    std::vector<std::string> args = {LASERCNCD_EXE, "--shm", shm_};
    // with --hal, HAL's thread keeps the time (and LinuxCNC's real-time setup)
    const bool hal = std::find(extra.begin(), extra.end(), "--hal") != extra.end();
    args.push_back(hal ? "--no-realtime" : "--simulated-clock");
    args.insert(args.end(), extra.begin(), extra.end());
    // the work offsets in the test's own file, never the user's (unless the test names one)
    if (std::find(extra.begin(), extra.end(), "--parameter-file") == extra.end()) {
      args.push_back("--parameter-file");
      args.push_back((temp_dir() / ("daemon_" + std::to_string(count_) + ".var")).string());
    }
    pid_ = spawn(args, "/dev/null", log_);
  }
  ~Daemon() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
      shm_unlink(shm_.c_str());
    }
  }
  // Waits until `lasercnc status` reaches it.
  bool ready() const {
    for (int i = 0; i < 500; ++i) {
      if (lasercnc("status --shm " + shm_).exit_code == 0) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  // Sends a signal and waits for the exit; returns the exit code (-1: killed).
  // The segment is then removed — a daemon killed outright cannot — unless
  // the test wants what a crash leaves behind (keep_segment).
  int stop(int sig, bool keep_segment = false) {
    kill(pid_, sig);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    if (!keep_segment) shm_unlink(shm_.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  // Waits for the exit of a daemon that ends by itself.
  int wait_exit() {
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  [[nodiscard]] std::string log() const { return slurp(log_); }
  // Waits up to 2 s for `text` in the log: what the daemon prints after its
  // segment is up may come after ready() (which only sees the segment).
  [[nodiscard]] bool logged(const std::string& text) const {
    for (int i = 0; i < 200; ++i) {
      if (log().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

 private:
  static inline int count_ = 0;
  std::string shm_;
  fs::path log_;
  pid_t pid_ = -1;
};

// One row of the --trace CSV: t,x,y,z,a,b,c,power.
struct TraceRow {
  double t = 0, x = 0, y = 0, z = 0, a = 0, b = 0, c = 0, power = 0;
};

inline std::vector<TraceRow> read_trace(const fs::path& file) {
  std::vector<TraceRow> rows;
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) {
    ADD_FAILURE() << "empty trace " << file;
    return rows;
  }
  EXPECT_EQ(line, "t,x,y,z,a,b,c,power");
  while (std::getline(in, line)) {
    TraceRow r;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &r.t, &r.x, &r.y, &r.z, &r.a, &r.b, &r.c,
                    &r.power) != 8) {
      ADD_FAILURE() << "bad trace row: " << line;
      break;
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace e2e
