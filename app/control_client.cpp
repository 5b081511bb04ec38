#include "app/control_client.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/cli_values.h"
#include "app/json_text.h"
#include "app/rt_text.h"
#include "common/error.h"
#include "geom/pose.h"
#include "machine/machine_config.h"
#include "rt/shm_interface.h"

namespace lcnc::app {
namespace {

std::string segment_name(const ClientOptions& o) {
  return o.shm_name.empty() ? shm::kDefaultName : o.shm_name;
}

// The daemon's segment, or an error printed and nullopt.
std::optional<shm::ShmClient> connect(const ClientOptions& o) {
  Result<shm::ShmClient> c = shm::ShmClient::open(segment_name(o));
  if (!c) {
    std::fprintf(stderr, "lasercnc: no daemon: %s\n", c.error().to_string().c_str());
    return std::nullopt;
  }
  if (!c->owner_alive()) {
    std::fprintf(stderr, "lasercnc: the daemon that owned %s is gone (stale segment)\n",
                 segment_name(o).c_str());
    return std::nullopt;
  }
  return std::move(c).value();
}

bool read_both(shm::ShmBlock& b, shm::Status& st, shm::JobStatus& job) {
  constexpr std::chrono::milliseconds kPatience{100};
  if (!b.status.load_patiently(st, kPatience) || !b.job.load_patiently(job, kPatience)) return false;
  shm::sanitize(st);
  shm::sanitize(job);
  return true;
}

std::optional<int> axis_index(const std::string& s) {
  if (s.size() != 1) return std::nullopt;
  for (int i = 0; i < kAxisCount; ++i)
    if (std::toupper(static_cast<unsigned char>(s[0])) == kAxisLetters[i]) return i;
  return std::nullopt;
}

// What the sender can say of a program file before the daemon reads it: it
// exists, this user can read it, it is a regular file. Opened without
// blocking, so a FIFO is told apart, not waited on. Empty if fine.
std::string local_file_problem(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return std::strerror(errno);
  struct stat st {};
  const bool stat_ok = fstat(fd, &st) == 0;
  close(fd);
  if (!stat_ok) return std::strerror(errno);
  if (S_ISREG(st.st_mode)) return {};
  if (S_ISDIR(st.st_mode)) return "it is a directory";
  if (S_ISFIFO(st.st_mode)) return "it is a named pipe (FIFO)";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "it is a device";
  return "it is not a regular file";
}

const char* coord_system_name(std::uint8_t index) {
  return index < kWorkOffsetNames.size() ? kWorkOffsetNames[index] : "?";
}

const char* outcome_name(shm::JobOutcome o) {
  switch (o) {
    case shm::JobOutcome::None: return "";
    case shm::JobOutcome::Done: return "done";
    case shm::JobOutcome::Stopped: return "stopped";
    case shm::JobOutcome::EStopped: return "e-stopped";
    case shm::JobOutcome::Failed: return "failed";
  }
  return "";
}

// This request's own id: the same in every retry of it, unlike anyone
// else's (the process id, and random bits for the rest).
std::uint64_t new_request_id() {
  std::random_device rd;
  const std::uint64_t r = (std::uint64_t{rd()} << 16) ^ rd();
  const std::uint64_t id = (static_cast<std::uint64_t>(getpid()) << 40) ^ r;
  return id == 0 ? 1 : id;
}

}  // namespace

std::string format_status(const shm::Status& st, const shm::JobStatus& job, bool json) {
  if (json) {
    nlohmann::json j;
    j["state"] = state_name(st.state);
    j["program_pause"] = st.program_pause;  // held at M0/M1/M60: `send resume` goes on
    j["input_wait"] = st.input_wait;        // held by M66 for this input (−1: none)
    j["fault"] = st.fault == 0 ? "" : std::string(error_summary(static_cast<ErrorCode>(st.fault)));
    j["fault_axis"] = st.fault_axis >= 0 ? std::string(1, kAxisLetters[st.fault_axis]) : "";
    j["line"] = st.line;
    j["position"] = st.pos;
    {
      std::array<double, 6> work{};
      for (int i = 0; i < kAxisCount; ++i) work[i] = st.pos[i] - job.work_offset[i];
      j["work_position"] = work;  // machine − work_offset, mm / deg
    }
    j["work_offset"] = job.work_offset;
    j["distance_to_go"] = job.distance_to_go;  // X Y Z to the end of the move, mm
    j["coord_system"] = coord_system_name(job.coord_system);
    j["modes"] = job.modes;
    j["mdi"] = job.mdi;
    j["single_block"] = job.single_block;
    j["dry_run"] = job.dry_run;
    j["start_line"] = job.start_line;
    j["position_steps"] = st.pos_steps;
    j["homed_mask"] = st.homed_mask;
    j["axes_mask"] = st.axes_mask;
    j["feed_override"] = st.feed_override;
    j["feed_override_target"] = st.feed_override_target;
    j["buffer_fill"] = st.buffer_fill;
    j["underruns"] = st.underruns;
    j["starvations"] = st.starvations;
    j["periods"] = st.periods;
    j["machine_time_s"] = st.machine_time_s;
    j["power_pct"] = st.power_pct;
    j["outputs"] = st.outputs;  // P0 … P7 in bits 0 … 7, gas M7 bit 8, M8 bit 9
    j["latency_us"] = {{"p50", st.latency_p50_us}, {"p99", st.latency_p99_us}, {"max", st.latency_max_us}};
    j["program"] = job.program;
    j["job_active"] = job.job_active;
    j["progress"] = job.progress;
    j["jobs_ended"] = job.jobs_ended;
    j["last_cycle_time_s"] = job.last_cycle_time_s;
    j["last_fault"] = job.last_fault;
    j["last_outcome"] = outcome_name(job.last_outcome);
    j["last_line"] = job.last_line;
    j["message"] = job.message;
    return json_text(j) + "\n";
  }
  std::string out;
  char buf[512];
  const auto add = [&](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    out += buf;
  };
  std::string fault;
  if (st.fault != 0) {
    fault = std::string(" — ") + std::string(error_summary(static_cast<ErrorCode>(st.fault)));
    if (st.fault_axis >= 0) fault += std::string(" (axis ") + kAxisLetters[st.fault_axis] + ")";
  }
  out += std::string("state      ") + state_name(st.state) +
         (st.program_pause && job.job_active && job.single_block
              ? " — single block: stopped after line " + std::to_string(st.line) +
                    ": send resume to run the next block"
          : st.program_pause
              ? " — program pause (M0/M1/M60) at line " + std::to_string(st.line) + ": send resume to go on"
              : std::string()) +
         (st.input_wait >= 0 ? " — waiting for input P" + std::to_string(st.input_wait) + " (M66) at line " +
                                   std::to_string(st.line)
                             : std::string()) +
         fault + "\n";
  out += "position  ";
  for (int i = 0; i < kAxisCount; ++i)  // "?": not homed
    if ((st.axes_mask >> i) & 1u)
      add(" %c %.3f%s", kAxisLetters[i], st.pos[i], (st.homed_mask >> i) & 1u ? "" : "?");
  add("\nwork %-5s", coord_system_name(job.coord_system));
  for (int i = 0; i < kAxisCount; ++i)
    if ((st.axes_mask >> i) & 1u) add(" %c %.3f", kAxisLetters[i], st.pos[i] - job.work_offset[i]);
  add("\nmodes      %s", job.modes);
  add("\noverride   %.0f %% (target %.0f %%)   buffer %u   line %u\n", st.feed_override * 100.0,
      st.feed_override_target * 100.0, st.buffer_fill, st.line);
  out += std::string("program    ") + (job.program[0] ? job.program : "(none)") +
         (job.job_active ? " (running)" : "");
  add("  %.1f %%\n", job.progress * 100.0);
  add("underruns  %llu   decelerations for a low buffer %llu   machine time %.3f s\n",
      static_cast<unsigned long long>(st.underruns), static_cast<unsigned long long>(st.starvations),
      st.machine_time_s);
  add("RT latency p50 %.0f us, p99 %.0f us, max %.1f us\n", st.latency_p50_us, st.latency_p99_us,
      st.latency_max_us);
  if (job.message[0]) out += std::string("last       ") + job.message + "\n";
  return out;
}

int client_status(const ClientOptions& options) {
  auto client = connect(options);
  if (!client) return 1;
  shm::Status st;
  shm::JobStatus job;
  if (!read_both(client->block(), st, job)) {
    std::fprintf(stderr, "lasercnc: the status is being rewritten too often to read\n");
    return 1;
  }
  std::fputs(format_status(st, job, options.json).c_str(), stdout);
  return 0;
}

int client_send(const std::vector<std::string>& args, const ClientOptions& options) {
  if (args.empty()) {
    std::fprintf(stderr, "lasercnc send: missing command\n");
    return 2;
  }
  const std::string& cmd = args[0];
  shm::Command c;
  const auto need = [&](std::size_t n, const char* what) {
    if (args.size() == n + 1) return true;
    std::fprintf(stderr, "lasercnc send %s: expects %s\n", cmd.c_str(), what);
    return false;
  };
  if (cmd == "load") {
    if (!need(1, "a program file")) return 2;
    std::error_code ec;
    const std::string path = std::filesystem::absolute(args[1], ec).string();
    if (path.size() >= sizeof c.text) {
      std::fprintf(stderr, "lasercnc send load: path longer than %zu bytes\n", sizeof c.text - 1);
      return 2;
    }
    if (const std::string why = local_file_problem(path); !why.empty()) {
      std::fprintf(stderr, "lasercnc send load: cannot load '%s': %s; expected a readable regular file\n",
                   path.c_str(), why.c_str());
      return 1;
    }
    c.type = shm::CommandType::Load;
    std::snprintf(c.text, sizeof c.text, "%s", path.c_str());
  } else if (cmd == "mdi") {
    if (args.size() < 2) {
      std::fprintf(stderr, "lasercnc send mdi: expects a line of G-code, e.g. mdi \"G1 X10 F600\"\n");
      return 2;
    }
    std::string text;
    for (std::size_t i = 1; i < args.size(); ++i) text += (i > 1 ? " " : "") + args[i];
    if (text.size() >= sizeof c.text) {
      std::fprintf(stderr, "lasercnc send mdi: a line of at most %zu bytes\n", sizeof c.text - 1);
      return 2;
    }
    c.type = shm::CommandType::Mdi;
    std::snprintf(c.text, sizeof c.text, "%s", text.c_str());
  } else if (cmd == "frame") {
    if (!need(0, "no argument")) return 2;
    c.type = shm::CommandType::Frame;
  } else if (cmd == "start" || cmd == "hold" || cmd == "resume" || cmd == "stop" || cmd == "estop" ||
             cmd == "reset") {
    if (!need(0, "no argument")) return 2;
    c.type = cmd == "start"    ? shm::CommandType::Start
             : cmd == "hold"   ? shm::CommandType::Hold
             : cmd == "resume" ? shm::CommandType::Resume
             : cmd == "stop"   ? shm::CommandType::Stop
             : cmd == "estop"  ? shm::CommandType::EStop
                               : shm::CommandType::Reset;
    if (c.type == shm::CommandType::Start) {
      c.value = options.from_line;
      c.axis = static_cast<std::uint8_t>((options.single_block ? shm::kStartSingleBlock : 0) |
                                         (options.dry_run ? shm::kStartDryRun : 0));
    }
  } else if (cmd == "override") {
    if (!need(1, "a percentage (0 … 150)")) return 2;
    const auto v = parse_number(args[1]);
    if (!v) {
      std::fprintf(stderr, "lasercnc send override: '%s' is not a number\n", args[1].c_str());
      return 2;
    }
    c.type = shm::CommandType::Override;
    c.value = *v / 100.0;
  } else if (cmd == "jog") {
    if (!need(2, "an axis and a distance, e.g. jog X 10")) return 2;
    const auto a = axis_index(args[1]);
    const auto v = parse_number(args[2]);
    if (!a || !v) {
      std::fprintf(stderr, "lasercnc send jog: expects an axis (X Y Z A B C) and a distance\n");
      return 2;
    }
    c.type = shm::CommandType::Jog;
    c.axis = static_cast<std::uint8_t>(*a);
    c.value = *v;
  } else if (cmd == "home") {
    if (!need(1, "an axis")) return 2;
    const auto a = axis_index(args[1]);
    if (!a) {
      std::fprintf(stderr, "lasercnc send home: '%s' is not an axis (X Y Z A B C)\n", args[1].c_str());
      return 2;
    }
    c.type = shm::CommandType::Home;
    c.axis = static_cast<std::uint8_t>(*a);
  } else {
    std::fprintf(stderr,
                 "lasercnc send: unknown command '%s' (load, start, hold, resume, stop, estop, "
                 "reset, override, jog, home, mdi, frame)\n",
                 cmd.c_str());
    return 2;
  }
  auto client = connect(options);
  if (!client) return 1;
  shm::ShmBlock& b = client->block();
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(options.timeout_s));
  const auto left = [&] {
    return std::max(std::chrono::steady_clock::duration::zero(), deadline - std::chrono::steady_clock::now());
  };
  shm::Status st;
  shm::JobStatus job;
  if (c.type == shm::CommandType::EStop) {
    // its own path: the e-stop word, read by the RT kernel every period —
    // neither the senders' lock nor the daemon's command thread in between
    client->request_estop();
    for (;;) {
      if (b.status.load(st) && st.state == shm::MachineState::EStop) break;
      if (left() == std::chrono::steady_clock::duration::zero() || !client->owner_alive()) {
        std::fprintf(stderr, "lasercnc send estop: requested, but the kernel's status does not show it\n");
        return 1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::printf("e-stop\n");
    return 0;
  }
  if (!read_both(b, st, job)) return 1;
  const std::uint32_t ended_before = job.jobs_ended;
  c.request_id = new_request_id();
  c.sender_uid = static_cast<std::uint32_t>(getuid());
  c.sender_gid = static_cast<std::uint32_t>(getgid());
  // a full queue or a busy lock: tried again with the same request id until
  // the deadline (a request that got through is not executed twice)
  while ((c.seq = client->send(
              c, std::min<std::chrono::nanoseconds>(left(), shm::ShmClient::kDefaultLockTimeout))) == 0) {
    if (left() == std::chrono::steady_clock::duration::zero()) {
      std::fprintf(stderr,
                   "lasercnc send %s: not sent within %g s: the daemon's command queue is full or "
                   "another sender holds the senders' lock\n",
                   cmd.c_str(), options.timeout_s);
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  shm::Answer answer;
  while (!client->answer(c.seq, answer)) {
    if (left() == std::chrono::steady_clock::duration::zero() || !client->owner_alive()) {
      std::fprintf(stderr, "lasercnc send %s: no answer from the daemon\n", cmd.c_str());
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (answer.code != 0) {
    std::fprintf(stderr, "lasercnc: %s\n", answer.message);
    return 1;
  }
  std::printf("%s\n", answer.message);
  const bool moves = c.type == shm::CommandType::Start || c.type == shm::CommandType::Mdi ||
                     c.type == shm::CommandType::Frame;
  if (options.wait && moves) {
    // an MDI command that does not move is done with its answer
    if (read_both(b, st, job) && job.jobs_ended == ended_before && !job.job_active) return 0;
    while (!(read_both(b, st, job) && job.jobs_ended != ended_before && !job.job_active)) {
      if (!client->owner_alive()) {
        std::fprintf(stderr, "lasercnc: the daemon died during the job\n");
        return 1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    std::printf("%s\n", job.message);
    // 3: the job did not run to its end (stopped, e-stopped, failed)
    return job.last_outcome == shm::JobOutcome::Done && job.last_fault == 0 ? 0 : 3;
  }
  return 0;
}

}  // namespace lcnc::app
