#include "app/daemon.h"

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <thread>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "app/cnc_modbus_host.h"
#include "app/framing.h"
#include "app/job_outcome.h"
#include "app/job_session.h"
#include "app/machine_files.h"
#include "app/planner_feed.h"
#include "app/program_loader.h"
#include "app/program_snapshot.h"
#include "app/recent_requests.h"
#include "app/rt_text.h"
#include "app/run_job.h"
#include "drivers/sim_machine.h"
#include "gcode/program_reader.h"
#include "plan/motion_check.h"
#include "plan/path_check.h"
#include "plan/program_source.h"
#include "rt/hal_block.h"
#include "rt/kernel_control.h"
#include "rt/rt_kernel.h"
#include "rt/shm_command.h"
#include "rt/shm_interface.h"

namespace lcnc::app {
namespace {

constexpr auto kTick = std::chrono::microseconds(500);         // control loop period
constexpr auto kModbusPublish = std::chrono::milliseconds(5);  // status to the Modbus slave
constexpr auto kKernelSettle = std::chrono::seconds(1);  // longest wait for the kernel to take a command

template <std::size_t N>
void copy_text(char (&dst)[N], const std::string& src) {
  std::snprintf(dst, N, "%s", src.c_str());
}

std::shared_ptr<spdlog::logger> logger() {
  static const std::shared_ptr<spdlog::logger> l = [] {
    auto existing = spdlog::get("lasercncd");
    return existing ? existing : spdlog::stderr_color_mt("lasercncd");
  }();
  return l;
}

// What a command frame may ask of `m`: its axes, its override range.
shm::CommandLimits command_limits(const MachineConfig& m) {
  shm::CommandLimits l;
  l.max_override = m.max_feed_override;
  for (int i = 0; i < kAxisCount; ++i)
    if (m.axes[i].present) l.axes_mask |= 1u << i;
  return l;
}

// $XDG_DATA_HOME/lasercnc/lasercncd.var (~/.local/share/lasercnc/…), its
// folder made if missing. A user without a home of its own (a system user
// whose service sets no XDG_DATA_HOME) gets a file in the temporary folder
// for this run only, and `warning` says so.
std::string default_parameter_file(std::string& warning) {
  std::filesystem::path dir;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x != nullptr && *x == '/') {
    dir = x;
  } else if (const char* h = std::getenv("HOME"); h != nullptr && *h == '/') {
    dir = std::filesystem::path(h) / ".local/share";
  }
  std::error_code ec;
  if (!dir.empty()) {
    dir /= "lasercnc";
    std::filesystem::create_directories(dir, ec);
    if (!ec) return (dir / "lasercncd.var").string();
  }
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path(ec) / ("lasercncd-" + std::to_string(getpid()) + ".var");
  warning =
      "no folder for the work offsets (" +
      (dir.empty() ? std::string("neither XDG_DATA_HOME nor HOME is set") : "cannot make " + dir.string()) +
      "): they are kept in " + tmp.string() + " for this run only; give --parameter-file FILE to keep them";
  return tmp.string();
}

// Whether the parameter file can be written where it is: the file, or for
// a new one its folder, writable by this process.
Status parameter_file_writable(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  const bool exists = fs::exists(p, ec);
  const std::string target = exists ? path : dir.string();
  if ((exists || fs::is_directory(dir, ec)) && ::access(target.c_str(), W_OK) == 0) return {};
  return make_error(ErrorCode::ParameterFileBad,
                    std::string("the parameter file cannot be written: ") +
                        (exists                      ? "it is not writable"
                         : fs::is_directory(dir, ec) ? "its folder " + dir.string() + " is not writable"
                                                     : "its folder " + dir.string() + " does not exist") +
                        "; expected a file lasercncd may write (--parameter-file FILE), so that the work "
                        "offsets and tools a job or MDI command sets are kept",
                    path);
}

// The work offsets and modes from the parameter file: an empty reading
// from `at` in `modes`.
Result<ReaderModes> read_work(const MachineConfig& machine, const Pose& at, const std::string& modes) {
  ReaderOptions ropt;
  ropt.start = at;
  ropt.modes = modes;
  auto reader = ProgramReader::from_string("", "parameters", machine, ropt);
  Segment seg;
  if (reader->next(seg) == ProgramReader::Next::Error) return reader->error();
  return reader->modes();
}

}  // namespace

struct Daemon::Impl {
  MachineConfig machine;
  const shm::CommandLimits limits = command_limits(machine);  // what a frame may ask of it
  shm::ShmOwner shm;
  std::array<std::int64_t, kAxisCount> start_steps{};
  // The kernel's position buffer, log and trace (the RT's, for the job's
  // check): the daemon's own beside its RT thread on the simulated machine;
  // with --hal, those of the HAL segment, whose kernel is the HAL
  // component's.
  struct OwnRings {
    rt::PositionBuffer buffer;
    rt::RtLogRing log;
    rt::TraceRing trace;
  };
  std::unique_ptr<OwnRings> own;
  std::optional<shm::HalSegment> hal;
  rt::PositionBuffer* buffer = nullptr;
  rt::RtLogRing* rt_log = nullptr;
  rt::TraceRing* trace = nullptr;
  std::unique_ptr<drivers::SimMachine> sim;
  std::unique_ptr<rt::RtKernel> rt_kernel;        // the simulated machine's
  std::unique_ptr<rt::KernelControl> hal_kernel;  // --hal: the component's, through the port
  rt::KernelControl* kernel = nullptr;
  bool hal_attached_seen = false;
  std::unique_ptr<PlannerFeed> feed;
  std::unique_ptr<CncModbusHost> modbus;  // the PLC/MES slave, when asked for
  bool realtime = true;
  rt::RtClock clock = rt::RtClock::Wall;
  std::vector<std::string> program_dirs;  // canonical; empty: anywhere

  // the job
  std::shared_ptr<const ProgramSnapshot> program;  // loaded, checked; null if none
  // What the active (or last) job runs: the loaded program, or an MDI
  // command's or the framing's own text.
  std::shared_ptr<const ProgramSnapshot> running;
  std::uint64_t running_segments = 0;
  // The modes the next MDI command starts in: what the last one left (a
  // program's end sets them back to the parameter file's work system).
  std::string mdi_modes;
  std::string mdi_end_modes;  // the running MDI command's, kept once it ends
  // Bumped whenever a job or MDI command may have changed the offsets in
  // the parameter file: the program loaded is checked again before a start.
  std::uint64_t params_gen = 0;
  std::uint64_t loaded_gen = 0;
  bool job_active = false;
  bool start_pending = false;  // planning ahead, the kernel not yet started
  bool stop_sent = false;      // the planner stopped short of a soft limit
  std::uint32_t jobs_ended_seen = 0;
  std::int64_t job_time_start_ns = 0;
  // The job's own check (plan/motion_check.h, plan/path_check.h): every
  // period the RT traced from the job's start, measured against the axis
  // limits and the program's path; a job that breaks one has failed,
  // whatever else it did.
  std::unique_ptr<JobCheck> job_check;
  std::uint64_t next_period = 0;  // the trace's next record, to see lost ones
  std::uint64_t job_underruns_start = 0;
  shm::JobStatus job{};

  Impl(MachineConfig m, shm::ShmOwner owner) : machine(std::move(m)), shm(std::move(owner)) {}

  // The axes present and not homed, "X Y"; empty when all are.
  std::string unhomed() const {
    std::string out;
    const std::uint32_t homed = kernel->homed_mask();
    for (int i = 0; i < kAxisCount; ++i) {
      if (!machine.axes[i].present || (homed >> i & 1u) != 0) continue;
      if (!out.empty()) out += ' ';
      out += kAxisLetters[i];
    }
    return out;
  }

  Pose position() const {
    Pose p = Pose::Zero();
    for (int i = 0; i < kAxisCount; ++i)
      if (machine.axes[i].present)
        p[i] = static_cast<double>(kernel->position_steps(i)) / machine.axes[i].steps_per_unit;
    return p;
  }

  // The answer to a command of the shm ring, in the slot its sender polls
  // (and, for the HMIs that read it, as the job status's last answer).
  void ack(const shm::Command& c, const Ack& a) {
    shm::Answer ans;
    ans.seq = c.seq;
    ans.code = a.ok ? 0 : static_cast<std::uint16_t>(a.code);
    copy_text(ans.message, a.message);
    job.ack_seq = c.seq;
    job.ack_code = ans.code;
    copy_text(job.message, a.message);
    // the job status first: a sender that has its answer reads the job the
    // command began (`send mdi --wait` tells a move from a command that
    // does not move by the job's flag)
    shm.block().job.store(job);
    shm.block().answers[c.seq % shm::kAnswerSlots].store(ans);
    log_ack(a);
    recent.remember(c.request_id, a);
  }

  // Requests answered lately: a retry gets the first answer, not a second run.
  RecentRequests recent;
  static void log_ack(const Ack& a) {
    if (a.ok) {
      logger()->info("{}", a.message);
    } else {
      logger()->warn("{}", a.message);
    }
  }

  void event(shm::Severity severity, std::uint16_t code, std::uint32_t line, std::uint32_t seq,
             const std::string& text) {
    shm::Event e;
    e.period = kernel->periods();
    e.code = code;
    e.severity = severity;
    e.state = kernel->state();
    e.line = line;
    e.command_seq = seq;
    copy_text(e.text, text);
    // A full event ring (no HMI reading) drops the oldest news: the status
    // and job blocks still tell the state.
    (void)shm.block().events.try_push(e);
  }

  CheckedJob loaded;                // the program loaded (`program`), as last checked
  Pose loaded_from = Pose::Zero();  // where the machine stood for that check

  // Who a command's files are read for: its sender, in the program folders.
  FileAccess access_for(const shm::Command& c) const {
    return FileAccess{c.sender_uid, c.sender_gid, program_dirs};
  }

  // A load in progress on the loader thread: at most one; the command
  // thread answers it once done (finish_load).
  std::unique_ptr<ProgramLoad> pending;

  // A load in progress is given up (the operator stops, or the daemon ends):
  // however long its program's loops would run, the loader ends at once.
  void cancel_load() {
    if (pending) pending->cancel();
  }

  void begin_load(const shm::Command& c) {
    pending = std::make_unique<ProgramLoad>(c, machine, position(), params_gen, access_for(c));
  }

  // The load done: what it checked becomes the program (or, refused, what
  // was loaded before stays loaded); its sender gets the answer.
  void finish_load(bool wait) {
    if (!pending) return;
    if (!wait && !pending->done()) return;
    pending->join();
    std::unique_ptr<ProgramLoad> l = std::move(pending);
    Ack a;
    Result<CheckedJob>& checked = l->checked();
    if (!checked) {
      a = Ack{false, checked.error().code, "load: " + checked.error().to_string()};
    } else {
      program = l->snapshot();
      loaded = std::move(checked).value();
      loaded_from = l->start();
      loaded_gen = l->params_gen();
      const ProgramSummary& s = loaded.summary;
      copy_text(job.program, program->name());
      job.lines = s.lines;
      job.segments = s.segments;
      job.progress = 0.0;
      char msg[256];
      std::snprintf(msg, sizeof msg, "loaded %s: %u lines, %llu segments, path %.3f mm",
                    program->name().c_str(), s.lines, static_cast<unsigned long long>(s.segments),
                    s.path_length_mm);
      a = Ack{true, ErrorCode::Ok, msg};
    }
    ack(l->command(), a);
    for (const shm::Command& r : l->repeats) ack(r, a);
  }

  // Executes a command (from the shm ring or the Modbus slave) and says what
  // came of it, once the kernel has taken what the command asked of it: the
  // sender that has its answer reads the state it brought (a jog's Jog, a
  // hold's FeedHold), never the one before.
  Ack handle(const shm::Command& c) {
    Ack a = execute(c);
    settle_kernel();
    return a;
  }

  // Waits for the kernel to take the commands pushed to it; bounded, for a
  // kernel that no longer runs (its HAL thread stopped): then the answer goes
  // out as it is and the status shows the state as it stands.
  void settle_kernel() const {
    if (hal && hal->attached() == 0) return;
    const auto until = std::chrono::steady_clock::now() + kKernelSettle;
    while (!kernel->commands_taken() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::microseconds(50));
  }

  Ack execute(const shm::Command& c) {
    follow_job();  // a job the kernel has just ended is over for this command too
    const shm::MachineState st = kernel->state();
    const auto refuse = [](const std::string& why) { return Ack{false, ErrorCode::RtRefused, why}; };
    if (lcnc::Status f = shm::check_command_frame(c, limits); !f) return refuse(f.error().message);
    const std::string axis_text(1, kAxisLetters[c.axis < kAxisCount ? c.axis : 0]);
    switch (c.type) {
      case shm::CommandType::Load:
        // the shm ring's loads go to the loader thread (drain_commands);
        // the Modbus slave has none
        return refuse("load refused: a load comes through the command ring");
      case shm::CommandType::Start: {
        if (pending) return refuse("start refused: a program is being loaded");
        if (std::optional<Ack> no = refuse_motion("start", st)) return *no;
        if (!program) return refuse("start refused: no program loaded");
        ReaderOptions ropt;
        ropt.start = position();
        ropt.start_line = static_cast<std::uint32_t>(c.value);
        ropt.single_block = (c.axis & shm::kStartSingleBlock) != 0;
        ropt.laser_off = (c.axis & shm::kStartDryRun) != 0;
        const bool plain = ropt.start_line == 0 && !ropt.single_block && !ropt.laser_off;
        if (loaded.drill_segments && !plain)
          return refuse(
              "start refused: run from line, single block and dry run are for G-code "
              "programs; " +
              program->name() + " is a hole table");
        // the copy that was checked runs; checked again from here if the
        // machine has moved (jog, home) or the offsets may have changed since,
        // or with the options asked for
        if (ropt.start != loaded_from || loaded_gen != params_gen || !plain) {
          Result<CheckedJob> checked = check_job(*program, machine, ropt);
          if (!checked) return Ack{false, checked.error().code, "start: " + checked.error().to_string()};
          if (!plain) return begin_job(program, *checked, ropt, false);
          loaded = std::move(checked).value();
          loaded_from = ropt.start;
          loaded_gen = params_gen;
        }
        return begin_job(program, loaded, ropt, false);
      }
      case shm::CommandType::Hold:
        if (!push({rt::RtCommandType::Hold, 0, 0.0})) return ring_full("hold");
        return Ack{true, ErrorCode::Ok, "hold"};
      case shm::CommandType::Resume:
        if (!push({rt::RtCommandType::Resume, 0, 0.0})) return ring_full("resume");
        return Ack{true, ErrorCode::Ok, "resume"};
      case shm::CommandType::Stop:
        cancel_load();
        if (!push({rt::RtCommandType::Stop, 0, 0.0})) return ring_full("stop");
        return Ack{true, ErrorCode::Ok, "stop"};
      case shm::CommandType::EStop:
        cancel_load();
        // a full ring: the e-stop's own word, one atomic add the kernel
        // reads every period (never refused)
        if (!push({rt::RtCommandType::EStop, 0, 0.0}))
          shm.block().estop.requests.fetch_add(1, std::memory_order_release);
        return Ack{true, ErrorCode::RtEstop, "e-stop"};
      case shm::CommandType::Reset:
        cancel_load();
        if (st != shm::MachineState::EStop) return refuse("reset refused: not in e-stop");
        if (!push({rt::RtCommandType::Reset, 0, 0.0})) return ring_full("reset");
        return Ack{true, ErrorCode::Ok, "reset"};
      case shm::CommandType::Override: {
        kernel->set_feed_override(c.value);
        char msg[64];
        std::snprintf(msg, sizeof msg, "override %g %%", c.value * 100.0);
        return Ack{true, ErrorCode::Ok, msg};
      }
      case shm::CommandType::Jog: {
        if (st != shm::MachineState::Idle || job_active)
          return refuse(std::string("jog refused: the machine is ") + state_name(st));
        if (!push({rt::RtCommandType::Jog, static_cast<std::int8_t>(c.axis), c.value}))
          return ring_full("jog");
        char msg[96];
        std::snprintf(msg, sizeof msg, "jog %s %+g", axis_text.c_str(), c.value);
        return Ack{true, ErrorCode::Ok, msg};
      }
      case shm::CommandType::Home: {
        if (st != shm::MachineState::Idle || job_active)
          return refuse(std::string("home refused: the machine is ") + state_name(st));
        if (!push({rt::RtCommandType::Home, static_cast<std::int8_t>(c.axis), 0.0})) return ring_full("home");
        return Ack{true, ErrorCode::Ok, "home " + axis_text};
      }
      case shm::CommandType::Mdi: return mdi(c, st);
      case shm::CommandType::Frame: return frame(st);
      case shm::CommandType::Count: break;
    }
    return refuse("bad command frame");
  }

  // A command for the kernel; false when its ring is full (16 commands it
  // has not taken: its thread is not running, or a HAL thread has stopped).
  bool push(const rt::RtCommand& c) { return kernel->command(c); }
  static Ack ring_full(const char* what) {
    return Ack{false, ErrorCode::RtRefused,
               std::string(what) +
                   " refused: the kernel has not taken the 16 commands before it (is its "
                   "thread running?)"};
  }

  // Why `what` may not move the machine now; nothing if it may.
  std::optional<Ack> refuse_motion(const char* what, shm::MachineState st) const {
    const auto refuse = [what](const std::string& why) {
      return Ack{false, ErrorCode::RtRefused, std::string(what) + " refused: " + why};
    };
    if (pending) return refuse("a program is being loaded");
    if (hal && hal->attached() == 0)
      return refuse("no HAL component runs the kernel (loadrt lasercnc segment=" + shm.name() +
                    ", addf lasercnc.update to a thread, start)");
    if (const std::string u = unhomed(); !u.empty())
      return refuse("not homed: " + u + " (home every axis, or set [machine] allow_unhomed)");
    if (job_active) return refuse(st == shm::MachineState::Idle ? "a job is starting" : "a job is running");
    if (st != shm::MachineState::Idle) return refuse(std::string("the machine is ") + state_name(st));
    return std::nullopt;
  }

  // The job: `snap` as `checked` from `ropt.start`, planned and run. An MDI
  // command or the framing (`mdi`) leaves the loaded program as it is.
  Ack begin_job(std::shared_ptr<const ProgramSnapshot> snap, const CheckedJob& checked,
                const ReaderOptions& asked, bool mdi) {
    const ReaderOptions ropt = reading_of(*snap, asked);
    const JobSource source = checked.drill_segments
                                 ? JobSource::segments(checked.drill_segments, snap->name(), ropt.start)
                                 : JobSource::program(snap->path(), ropt);
    Result<std::unique_ptr<PathCheck>> path = source.path_check(machine);
    if (!path) return Ack{false, path.error().code, "start: " + snap->rename(path.error()).to_string()};
    source.start(*feed);
    running = std::move(snap);
    running_segments = checked.summary.segments;
    job_active = true;
    start_pending = true;
    stop_sent = false;
    job.job_active = true;
    job.progress = 0.0;
    job.mdi = mdi;
    job.single_block = ropt.single_block;
    job.dry_run = ropt.laser_off;
    job.start_line = ropt.start_line;
    job_time_start_ns = kernel->machine_time_ns();
    job_underruns_start = kernel->underruns();
    drain_trace();  // what came before the job is not the job's
    {
      std::array<std::int64_t, kAxisCount> at{};
      for (int i = 0; i < kAxisCount; ++i) at[i] = kernel->position_steps(i);
      job_check =
          std::make_unique<JobCheck>(machine, std::move(path).value(), at, job_time_start_ns, next_period);
    }
    std::string how;
    if (ropt.start_line > 0) how += ", from line " + std::to_string(ropt.start_line);
    if (ropt.single_block) how += ", single block (resume runs the next)";
    if (ropt.laser_off) how += ", dry run: the beam off";
    return Ack{true, ErrorCode::Ok, (mdi ? "running " : "started ") + running->name() + how};
  }

  // MDI: one line of G-code, in the modes the last command left, from here.
  // One that does not move (G10 L20, G55, F600) is done at once.
  Ack mdi(const shm::Command& c, shm::MachineState st) {
    const std::string text(c.text, strnlen(c.text, sizeof c.text));
    std::size_t b = text.find_first_not_of(" \t");
    if (b == std::string::npos) return Ack{false, ErrorCode::RtRefused, "mdi refused: no G-code"};
    if (std::optional<Ack> no = refuse_motion("mdi", st)) return *no;
    Result<std::shared_ptr<const ProgramSnapshot>> snap =
        ProgramSnapshot::from_text("MDI", text + "\n", access_for(c));
    if (!snap) return Ack{false, snap.error().code, "mdi: " + snap.error().to_string()};
    ReaderOptions ropt;
    ropt.start = position();
    ropt.modes = mdi_modes;
    ropt.keep_parameters = true;  // a G10 that does not move is kept by this reading
    Result<CheckedJob> checked = check_job(**snap, machine, ropt);
    ++params_gen;
    if (!checked) return Ack{false, checked.error().code, "mdi: " + checked.error().to_string()};
    const std::string shown = text.substr(b);
    if (checked->summary.segments == 0) {
      mdi_modes = checked->summary.end.block;
      refresh_work();  // what is stored, read back: the status never shows what is not
      return Ack{true, ErrorCode::Ok, "mdi " + shown + ": done"};
    }
    mdi_end_modes = checked->summary.end.block;
    Ack a = begin_job(*snap, *checked, ropt, true);
    if (a.ok) a.message = "mdi " + shown + ": running";
    return a;
  }

  // Framing: the loaded program's X Y extents (of its cuts, else of all its
  // moves) traced at the Z where the machine stands, with the beam off, at
  // half the slower of X's and Y's top speed; then back to where it began.
  Ack frame(shm::MachineState st) {
    if (std::optional<Ack> no = refuse_motion("frame", st)) return *no;
    if (!program) return Ack{false, ErrorCode::RtRefused, "frame refused: no program loaded"};
    const Pose here = position();
    const Framing f = framing_program(loaded.summary, program->name(), here, machine);
    Result<std::shared_ptr<const ProgramSnapshot>> snap =
        ProgramSnapshot::from_text("framing", f.program, FileAccess{});
    if (!snap) return Ack{false, snap.error().code, "frame: " + snap.error().to_string()};
    ReaderOptions ropt;
    ropt.start = here;
    ropt.laser_off = true;
    Result<CheckedJob> checked = check_job(**snap, machine, ropt);
    if (!checked) return Ack{false, checked.error().code, "frame: " + checked.error().to_string()};
    mdi_end_modes = mdi_modes;  // framing leaves the MDI modes as they are
    Ack a = begin_job(*snap, *checked, ropt, true);
    if (a.ok) {
      char msg[200];
      std::snprintf(msg, sizeof msg, "framing %s: X %.3f … %.3f, Y %.3f … %.3f mm, beam off",
                    program->name().c_str(), f.lo[0], f.hi[0], f.lo[1], f.hi[1]);
      a.message = msg;
    }
    return a;
  }

  // The work coordinates the HMIs and `lasercnc status` show: the offsets,
  // work system and modes as `m` (a reading's end) left them.
  void publish_work(const ReaderModes& m) {
    for (int i = 0; i < kAxisCount; ++i) job.work_offset[i] = m.offsets[i];
    job.coord_system = static_cast<std::uint8_t>(m.coord_system);
    job.inch = m.inch;
    copy_text(job.modes, m.block);
  }

  // The same, read afresh from the parameter file (after a program).
  void refresh_work() {
    Result<ReaderModes> m = read_work(machine, position(), mdi_modes);
    if (!m) {
      logger()->warn("lasercncd: the work offsets: {}", m.error().to_string());
      return;
    }
    publish_work(*m);
  }

  // Why a load may not begin now; nothing if it may.
  std::optional<Ack> refuse_load(const shm::Command& c) {
    follow_job();
    const auto refuse = [](const std::string& why) { return Ack{false, ErrorCode::RtRefused, why}; };
    if (lcnc::Status f = shm::check_command_frame(c, limits); !f) return refuse(f.error().message);
    if (job_active) return refuse("load refused: a job is running (stop it first)");
    if (pending)
      return refuse("load refused: another load is in progress (" + std::string(pending->command().text) +
                    ")");
    return std::nullopt;
  }

  // The HMIs' and the CLI's commands: at most a ring's worth per tick (the
  // ring is in shared memory; a sender can keep it full, not keep the
  // daemon from its other work). A ring found corrupt is dropped by the
  // ring itself and reported here.
  void drain_commands() {
    auto& ring = shm.block().commands;
    shm::Command c;
    for (std::size_t n = 0; n < ring.kCapacity && ring.try_pop(c); ++n) {
      if (pending && c.request_id != 0 && c.request_id == pending->command().request_id) {
        pending->repeats.push_back(c);  // answered with the load it repeats
        continue;
      }
      if (const Ack* first = recent.find(c.request_id)) {  // a retry: answered, not executed again
        ack(c, *first);
        continue;
      }
      if (c.type == shm::CommandType::Load) {
        if (std::optional<Ack> refused = refuse_load(c)) {
          ack(c, *refused);
        } else {
          begin_load(c);  // answered when done
        }
        continue;
      }
      ack(c, handle(c));
    }
    if (ring.resyncs() != command_resyncs) {
      command_resyncs = ring.resyncs();
      const std::string why =
          "the command ring's indices were corrupt (a sender wrote past its turn): "
          "its contents dropped, " +
          std::to_string(command_resyncs) + " so far";
      logger()->error("lasercncd: {}", why);
      event(shm::Severity::Error, static_cast<std::uint16_t>(ErrorCode::RtRefused), 0, 0, why);
    }
  }
  std::uint64_t command_resyncs = 0;

  // The PLC/MES side: commands taken with the shm ring's rules, the status
  // published every kModbusPublish.
  void serve_modbus() {
    modbus->drain([this](const shm::Command& c) {
      Ack a = handle(c);
      a.message = "modbus: " + a.message;
      log_ack(a);
      return a;
    });
    const auto now = std::chrono::steady_clock::now();
    if (now < next_publish) return;
    shm::Status st;
    if (shm.block().status.load(st) && modbus->publish(st)) next_publish = now + kModbusPublish;
  }
  std::chrono::steady_clock::time_point next_publish{};

  // The kernel's log: to stderr and, as events, to the HMI.
  void drain_rt_log() {
    rt::RtLogRecord r;
    while (rt_log->try_pop(r)) {
      const RtLogLine line = describe_rt_log(r, machine);
      if (line.warning) {
        logger()->warn("{}", line.text);
      } else {
        logger()->info("{}", line.text);
      }
      event(r.code == rt::RtLogCode::Fault ? shm::Severity::Error
            : line.warning                 ? shm::Severity::Warning
                                           : shm::Severity::Info,
            line.code, r.line, 0, line.text);
    }
  }

  // The RT's trace: into the job's check while a job runs (times from the
  // job's start; idle periods before it are skipped), else dropped.
  void drain_trace() {
    rt::TraceRecord r;
    bool moved = false;
    while (trace->try_pop(r)) {
      moved = true;
      trace_last = r;
      if (job_check) job_check->add(r);
      next_period = r.period + 1;
    }
    if (moved) publish_distance_to_go();
  }
  rt::TraceRecord trace_last{};

  // From the last traced position to the end of its programmed move.
  void publish_distance_to_go() {
    job.distance_to_go = {};
    if (!job_active || !job_check || !trace_last.on_path) return;
    const std::optional<Vec3> end = job_check->path().segment_end(trace_last.segment);
    if (!end) return;
    for (int i = 0; i < 3; ++i)
      if (machine.axes[i].present)
        job.distance_to_go[i] =
            (*end)[i] - static_cast<double>(trace_last.pos_steps[i]) / machine.axes[i].steps_per_unit;
  }

  // --hal: says when the component attaches and when its process goes.
  void follow_hal() {
    if (!hal) return;
    const pid_t pid = hal->attached();
    if ((pid != 0) == hal_attached_seen) return;
    hal_attached_seen = pid != 0;
    if (pid != 0) {
      logger()->info("lasercncd: the HAL component (process {}) runs the kernel; unhomed: {}", pid,
                     unhomed().empty() ? "none" : unhomed());
    } else {
      logger()->error("lasercncd: the HAL component has gone: no kernel runs");
      if (job_active) {
        feed->abort();
        job_active = false;
        start_pending = false;
        job_check.reset();
        job.job_active = false;
        job.last_outcome = shm::JobOutcome::Failed;
        job.last_fault = static_cast<std::uint16_t>(ErrorCode::RtShmLink);
        const char* msg = "job failed: the HAL component that ran the kernel has gone (rtapi_app ended)";
        copy_text(job.message, msg);
        event(shm::Severity::Error, job.last_fault, 0, 0, msg);
      }
    }
  }

  // Starts the kernel on a job once it is planned far enough ahead; ends the
  // job when the kernel says so.
  void follow_job() {
    if (!job_active) return;
    if (start_pending && feed->prefilled()) {
      start_pending = !push({rt::RtCommandType::StartJob, 0, 0.0});  // a full ring: again next tick
    }
    if (feed->stopped_short() && !stop_sent) stop_sent = push({rt::RtCommandType::Stop, 0, 0.0});
    if (running_segments > 0)
      job.progress = std::min(1.0, kernel->current_segment() / static_cast<double>(running_segments));
    const std::uint32_t ended = kernel->jobs_ended();
    const bool estopped = kernel->state() == shm::MachineState::EStop;
    if (ended == jobs_ended_seen && !estopped) return;
    jobs_ended_seen = ended;
    drain_trace();
    JobEnd end;
    if (job_check) {
      job_check->finish();
      end.breaches = job_check->breaches();
      // the control thread starved of the CPU: the guard still held every entry
      if (job_check->motion().gaps() > 0)
        logger()->warn(
            "job check: the RT trace lost records; those periods were held to the increment guard only");
      job_check.reset();
    }
    feed->abort();  // a stopped job: the planner stops; a finished one has
    const PlannedJob& planned = feed->result();
    for (const Diagnostic& w : planned.warnings) logger()->warn("job: {}", w.to_string());
    job_active = false;
    start_pending = false;
    const rt::RtFault f = kernel->fault();
    job.job_active = false;
    job.distance_to_go = {};
    job.jobs_ended = ended;
    job.last_cycle_time_s = static_cast<double>(kernel->machine_time_ns() - job_time_start_ns) * 1e-9;
    job.last_underruns = kernel->underruns() - job_underruns_start;
    shm::Status rt_status;
    job.last_line = f.active && f.line != 0              ? f.line
                    : shm.block().status.load(rt_status) ? rt_status.line
                                                         : 0;
    end.planned = &planned;
    end.running = running.get();
    end.fault = f;
    end.estopped = estopped;
    end.completed = kernel->last_job_completed();
    end.line = job.last_line;
    end.progress = job.progress;
    end.cycle_time_s = job.last_cycle_time_s;
    end.underruns = job.last_underruns;
    const JobOutcomeText out = job_outcome(end, machine);
    job.last_outcome = out.outcome;
    job.last_fault = out.fault;
    job.progress = out.progress;
    if (out.failed_check)
      for (const std::string& b : end.breaches) logger()->error("job check: {}", b);
    copy_text(job.message, out.message);
    logger()->info("{}", out.message);
    event(job.last_outcome == shm::JobOutcome::Done ? shm::Severity::Info
          : job.last_fault != 0                     ? shm::Severity::Error
                                                    : shm::Severity::Warning,
          job.last_fault, f.line, 0, out.message);
    // the offsets as the job left them: an MDI command's modes go on to
    // the next; a program's end starts the MDI afresh
    mdi_modes = job.mdi ? mdi_end_modes : std::string();
    ++params_gen;
    refresh_work();
  }
};

Result<std::unique_ptr<Daemon>> Daemon::create(const DaemonOptions& options) {
  RunOptions ro;
  ro.machine_file = options.machine_file;
  Result<MachineConfig> machine = load_machine(ro);
  if (!machine) return machine.error();
  if (!options.parameter_file.empty()) {
    machine->parameter_file = options.parameter_file;
  } else if (machine->parameter_file.empty()) {
    std::string warning;
    machine->parameter_file = default_parameter_file(warning);
    if (!warning.empty()) logger()->warn("lasercncd: {}", warning);
  }
  // read before the segment appears: an HMI never sees other offsets
  Result<ReaderModes> work = read_work(*machine, Pose::Zero(), "");
  if (!work) return work.error();
  // and writable: a G10 the daemon could not keep is refused, but one that
  // can never be kept is a configuration error, said at start
  if (Status s = parameter_file_writable(machine->parameter_file); !s) return s.error();
  Result<shm::ShmOwner> owner =
      shm::ShmOwner::create(options.shm_name.empty() ? shm::kDefaultName : options.shm_name);
  if (!owner) return owner.error();
  auto impl = std::make_unique<Impl>(std::move(machine).value(), std::move(owner).value());
  Impl& d = *impl;
  d.publish_work(*work);
  d.shm.block().job.store(d.job);
  d.realtime = options.realtime && !options.simulated_clock;
  d.clock = options.simulated_clock ? rt::RtClock::SimulatedPaced : rt::RtClock::Wall;
  for (const std::string& dir : options.program_dirs) {
    std::error_code ec;
    const std::filesystem::path canon = std::filesystem::canonical(dir, ec);
    if (ec || !std::filesystem::is_directory(canon))
      return make_error(ErrorCode::FileNotFound, "program folder '" + dir + "': not a directory" +
                                                     (ec ? " (" + ec.message() + ")" : std::string()));
    d.program_dirs.push_back(canon.string());
  }
  StepQuantizer q(d.machine, Pose::Zero());
  for (int i = 0; i < kAxisCount; ++i) d.start_steps[i] = q.commanded(i);
  if (options.hal) {
    // the kernel runs in the HAL component; this side plans, streams and
    // commands it through the HAL segment
    const std::string file = options.machine_file.empty() ? default_machine_file() : options.machine_file;
    std::error_code ec;
    const std::filesystem::path abs = std::filesystem::absolute(file, ec);
    Result<shm::HalSegment> seg = shm::HalSegment::create(d.shm.name(), abs.string(), d.start_steps);
    if (!seg) return seg.error();
    d.hal.emplace(std::move(seg).value());
    shm::HalBlock& hb = d.hal->block();
    d.buffer = &hb.buffer;
    d.rt_log = &hb.log;
    d.trace = &hb.trace;
    d.hal_kernel = std::make_unique<rt::KernelControl>(d.machine, hb.port);
    d.kernel = d.hal_kernel.get();
  } else {
    d.own = std::make_unique<Impl::OwnRings>();
    d.buffer = &d.own->buffer;
    d.rt_log = &d.own->log;
    d.trace = &d.own->trace;
    // the simulated machine wired as a real one: hard limits beyond the
    // soft ones, a home switch per axis (drivers/sim_machine.h)
    d.sim = std::make_unique<drivers::SimMachine>(d.start_steps, drivers::wired_switches(d.machine));
    d.rt_kernel = std::make_unique<rt::RtKernel>(d.machine, *d.buffer, *d.sim, d.trace, d.start_steps);
    d.rt_kernel->set_log(d.rt_log);
    d.rt_kernel->set_status(&d.shm.block().status);
    d.rt_kernel->set_estop_word(&d.shm.block().estop.requests);
    d.kernel = d.rt_kernel.get();
  }
  d.feed = std::make_unique<PlannerFeed>(d.machine, *d.buffer, *d.kernel);
  logger()->info("lasercncd: work offsets kept in {}", d.machine.parameter_file);
  d.shm.block().job.store(d.job);
  if (options.modbus) {
    Result<std::unique_ptr<CncModbusHost>> host = CncModbusHost::start(*options.modbus, logger());
    if (!host) return host.error();
    d.modbus = std::move(host).value();
    logger()->info("lasercncd: Modbus slave (device cnc, unit 1) on {}", d.modbus->endpoint().to_string());
  }
  return std::unique_ptr<Daemon>(new Daemon(std::move(impl)));
}

Daemon::Daemon(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Daemon::~Daemon() = default;

bool Daemon::recovered_stale() const noexcept { return impl_->shm.recovered_stale(); }

int Daemon::run(const std::atomic<bool>& quit) {
  Impl& d = *impl_;
  rt::RtOptions o;
  o.try_realtime = d.realtime;
  o.clock = d.clock;
  o.exit_at_end = false;
  o.start_running = false;
  if (d.rt_kernel) {
    d.rt_kernel->start(o);
    if (!d.rt_kernel->warning().empty()) logger()->warn("{}", d.rt_kernel->warning());
    logger()->info("lasercncd: machine '{}', period {} us, ready", d.machine.name,
                   d.machine.period_ns / 1000);
  } else {
    logger()->info(
        "lasercncd: machine '{}', period {} us; the kernel runs in LinuxCNC's HAL: "
        "loadrt lasercnc segment={}, then addf lasercnc.update to a thread of that period",
        d.machine.name, d.machine.period_ns / 1000, d.shm.name());
    if (d.machine.allow_unhomed)
      logger()->warn(
          "lasercncd: [machine] allow_unhomed = true: jobs run from wherever the axes stood at "
          "power-on, without homing; soft limits are only as good as that position");
  }
  shm::ShmBlock& block = d.shm.block();
  while (!quit.load()) {
    block.header.heartbeat.fetch_add(1, std::memory_order_relaxed);
    d.drain_commands();
    d.finish_load(false);
    if (d.modbus) d.serve_modbus();
    d.drain_trace();
    d.follow_job();
    d.drain_rt_log();
    d.follow_hal();
    block.job.store(d.job);
    std::this_thread::sleep_for(kTick);
  }
  // SIGTERM: motion ends along the path, then the threads end.
  logger()->info("lasercncd: shutting down");
  const shm::MachineState st = d.kernel->state();
  if (st != shm::MachineState::Idle && st != shm::MachineState::EStop) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    while (!d.push({rt::RtCommandType::Stop, 0, 0.0}) && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    while (d.kernel->state() != shm::MachineState::Idle && d.kernel->state() != shm::MachineState::EStop &&
           std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  d.cancel_load();
  d.finish_load(true);  // cancelled, the loader ends at its next line: joined
  d.feed->abort();
  if (d.rt_kernel) {
    d.rt_kernel->shutdown();
    d.rt_kernel->join();
  }
  d.drain_rt_log();
  return 0;
}

}  // namespace lcnc::app
