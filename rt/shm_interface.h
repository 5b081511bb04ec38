// The kernel ↔ HMI interface in POSIX shared memory (docs/design.md §2): the one header of rt/ the HMI includes. Fixed size, no pointers
// (offsets only), versioned; mode 0660.
//
//   ShmHeader   magic, version, size, owner pid, heartbeat (stale detection)
//   status      Seqlock<Status>: written by the RT kernel every few periods,
//               read by any number of HMIs without blocking the kernel
//   estop       EStopWord: a counter any process bumps with one atomic add
//               (ShmClient::request_estop), no lock; the RT kernel polls it
//               every period — an e-stop waits behind nothing
//   job         Seqlock<JobStatus>: the daemon's jobs and its last answer
//   answers     Seqlock<Answer>[kAnswerSlots]: the answer to command seq s in
//               slot s % kAnswerSlots, where its own sender looks for it
//   commands    SpscRing<Command>: HMIs and `lasercnc send` → the daemon;
//               its senders take turns under a process-shared robust mutex
//               (ShmClient::send, a timed lock), which also hands out unique
//               sequence numbers — the daemon's control thread pops without it
//   events      SpscRing<Event>:   kernel → HMI (faults, state changes)
//
// Trust: the segment is the group's (mode 0660); a frame's sender uid/gid
// are what the sending process wrote, checked by the daemon like any other
// field, not proof of identity — they keep an honest client from loading a
// file its user cannot read, not a hostile member of the group.
#pragma once

#include <pthread.h>
#include <sys/types.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "common/result.h"
#include "rt/seqlock.h"
#include "rt/spsc_ring.h"

namespace lcnc::shm {

inline constexpr std::uint32_t kMagic = 0x434E434Cu;  // "LCNC" in memory
inline constexpr std::uint32_t kVersion = 8;
inline constexpr const char* kDefaultName = "/lasercnc";

enum class MachineState : std::uint8_t { Idle, Running, FeedHold, Stopping, EStop, Jog, Homing };

enum class CommandType : std::uint8_t {
  Load,   // text: program path
  Start,  // value: run from this line (0: from the start); axis: StartFlags bits
  Hold,
  Resume,
  Stop,
  EStop,
  Reset,     // leave e-stop
  Override,  // value: feed override K (1 = 100 %)
  Jog,       // axis, value: distance (mm or deg)
  Home,      // axis
  Mdi,       // text: one line of G-code, run now from where the machine stands
  Frame,     // traces the loaded program's X Y extents with the beam off, at the Z it stands
  Count,     // not a command: the number of them (a larger type byte is a bad frame)
};

// How a Start runs the program (Command::axis of a Start, bits).
inline constexpr std::uint8_t kStartSingleBlock = 1u;  // a pause after each block's moves
inline constexpr std::uint8_t kStartDryRun = 2u;       // every move with the beam off
inline constexpr std::uint8_t kStartFlags = kStartSingleBlock | kStartDryRun;

struct Command {
  CommandType type = CommandType::Stop;
  std::uint8_t axis = 0;
  std::uint32_t seq = 0;  // unique among senders (ShmClient::send), keys the answer slot
  double value = 0.0;
  // The sender's own id of this request (0: none). A sender that sends the
  // same request again (a retry after no answer) keeps the id: the daemon
  // executes it once and answers the repeat with the first answer.
  std::uint64_t request_id = 0;
  std::uint32_t sender_uid = 0;  // whose rights a load is read with (see Trust above)
  std::uint32_t sender_gid = 0;
  char text[240] = {};
};

// The answer to one command, in slot seq % kAnswerSlots.
struct Answer {
  std::uint32_t seq = 0;   // the command's seq; 0: the slot is empty
  std::uint16_t code = 0;  // 0: accepted; else the ErrorCode why not
  char message[256] = {};
};
inline constexpr std::size_t kAnswerSlots = 256;

enum class Severity : std::uint8_t { Info, Warning, Error };

struct Event {
  std::uint64_t period = 0;
  std::uint16_t code = 0;              // ErrorCode (share/errors.def), 0 for plain state changes
  Severity severity = Severity::Info;  // Error: a fault or a failed job; Warning: worth a look
  MachineState state = MachineState::Idle;
  std::uint32_t line = 0;  // program line, 0 if none
  std::uint32_t command_seq = 0;
  char text[112] = {};
};

struct Status {
  MachineState state = MachineState::Idle;
  std::uint16_t fault = 0;       // ErrorCode of the active fault, 0 if none
  std::int8_t fault_axis = -1;   // axis of the fault, −1 if none
  std::uint32_t line = 0;        // program line executing (or last executed)
  std::uint32_t homed_mask = 0;  // bit per axis whose position is known
  std::uint32_t axes_mask = 0;   // bit per axis the machine has
  std::uint64_t periods = 0;
  std::uint64_t underruns = 0;    // periods with the buffer empty while running
  std::uint64_t starvations = 0;  // decelerations for a low buffer while streaming
  std::array<std::int64_t, 6> pos_steps{};
  std::array<double, 6> pos{};        // mm / deg
  double feed_override = 1.0;         // K now
  double feed_override_target = 1.0;  // the operator's K
  double machine_time_s = 0.0;
  std::uint32_t buffer_fill = 0;
  float power_pct = 0.0f;
  // The outputs the job drives now: digital outputs P0 … P7 in bits 0 … 7,
  // the assist gas in kGasLowBit (M7) and kGasHighBit (M8).
  std::uint16_t outputs = 0;
  float latency_p50_us = 0.0f, latency_p99_us = 0.0f, latency_max_us = 0.0f;
  // The program paused itself (M0, M1, M60): FeedHold at rest until a
  // resume, which then goes on with the program.
  bool program_pause = false;
  // An M66 holds the job (FeedHold at rest) until this input does as asked
  // or its timeout; −1: none.
  std::int8_t input_wait = -1;
};

inline constexpr std::uint16_t kGasLowBit = 1u << 8;   // Status::outputs: M7 (mist)
inline constexpr std::uint16_t kGasHighBit = 1u << 9;  // M8 (flood)

// How the last job ended.
enum class JobOutcome : std::uint8_t {
  None,      // no job has ended yet
  Done,      // ran to its end
  Stopped,   // the operator's stop (or the planner's, short of a soft limit)
  EStopped,  // an e-stop: the command, the input or a limit
  Failed,    // the program could not be read or planned to its end
};

// What the daemon says of jobs and commands (written by its control thread,
// a second seqlock beside the kernel's Status): the answer to the last
// command — any number of `lasercnc send` and HMIs read it, none consumes it.
// A sender waits for its own answer in ShmBlock::answers instead: with
// several senders, this one is overwritten by the next answer.
struct JobStatus {
  std::uint32_t ack_seq = 0;   // seq of the last command taken
  std::uint16_t ack_code = 0;  // 0: accepted; else the ErrorCode why not
  char message[256] = {};      // what came of it (an error says file:line:col)
  char program[256] = {};      // the loaded program, "" if none
  std::uint32_t lines = 0;
  std::uint64_t segments = 0;
  bool job_active = false;  // planning/executing a job
  double progress = 0.0;    // 0 … 1 of the active (or last) job
  std::uint32_t jobs_ended = 0;
  double last_cycle_time_s = 0.0;
  std::uint64_t last_underruns = 0;
  std::uint16_t last_fault = 0;  // ErrorCode that ended the last job, 0 if it ran to the end
  JobOutcome last_outcome = JobOutcome::None;
  std::uint32_t last_line = 0;  // program line where the last job ended
  // The work coordinates: work = machine − work_offset (mm, deg), in work
  // system coord_system (0 = G54 … 8 = G59.3), as the last job or MDI
  // command left them (and the parameter file keeps them).
  std::array<double, 6> work_offset{};
  std::uint8_t coord_system = 0;
  bool inch = false;     // MDI commands are read in inches (G20)
  char modes[128] = {};  // the modes the next MDI command starts in
  // The active (or last) job: what it is and how it runs.
  bool mdi = false;  // an MDI command or framing, not the loaded program
  bool single_block = false;
  bool dry_run = false;
  std::uint32_t start_line = 0;  // run from this line; 0: from the start
  // X Y Z from where the machine is to the end of the programmed move it is
  // making (mm, machine axes); 0 with no job moving.
  std::array<double, 3> distance_to_go{};
};

// Blocks copied out of the segment, made safe to use: any process of the
// group can write there, so a reader (HMI, CLI) passes its copy through
// sanitize() — text fields end at their last byte at the latest, a bool is
// 0 or 1, an axis index names an axis or is −1.
void sanitize(Status& s) noexcept;
void sanitize(JobStatus& j) noexcept;
void sanitize(Event& e) noexcept;
void sanitize(Answer& a) noexcept;

struct ShmHeader {
  std::uint32_t magic = 0;
  std::uint32_t version = 0;
  std::uint64_t size = 0;  // sizeof(ShmBlock) of the writer
  pid_t owner_pid = 0;
  std::atomic<std::uint64_t> heartbeat{0};  // bumped by the kernel; stale when it stops
};

// The command ring's senders: any number of processes, one at a time.
struct CommandSenders {
  pthread_mutex_t lock;        // PTHREAD_PROCESS_SHARED, PTHREAD_MUTEX_ROBUST
  std::uint32_t next_seq = 0;  // guarded by lock
};

// The e-stop's own path: a request counter, bumped by any process with one
// atomic add and no lock (ShmClient::request_estop); the RT kernel compares
// it with the count it last saw every period (RtKernel::set_estop_word), so
// an e-stop acts within a period whatever the daemon's control thread or
// the senders' lock are doing. On a cache line of its own.
struct alignas(rt::kCacheLine) EStopWord {
  std::atomic<std::uint32_t> requests{0};
};
static_assert(std::atomic<std::uint32_t>::is_always_lock_free);

struct ShmBlock {
  ShmHeader header;
  EStopWord estop;
  rt::Seqlock<Status> status;
  rt::Seqlock<JobStatus> job;
  std::array<rt::Seqlock<Answer>, kAnswerSlots> answers;
  CommandSenders senders;
  rt::SpscRing<Command, 64> commands;
  rt::SpscRing<Event, 256> events;
};
static_assert(std::is_standard_layout_v<ShmHeader>);

// The owner (the daemon): creates the segment, or takes over a stale one
// whose owner process is gone; refuses when a live owner holds it.
class ShmOwner {
 public:
  [[nodiscard]] static Result<ShmOwner> create(const std::string& name = kDefaultName);
  ShmOwner(ShmOwner&&) noexcept;
  ShmOwner& operator=(ShmOwner&&) = delete;
  ~ShmOwner();  // unmaps and unlinks
  [[nodiscard]] ShmBlock& block() noexcept { return *block_; }
  [[nodiscard]] bool recovered_stale() const noexcept { return recovered_stale_; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }

 private:
  ShmOwner(std::string name, ShmBlock* block, bool stale)
      : name_(std::move(name)), block_(block), recovered_stale_(stale) {}
  std::string name_;
  ShmBlock* block_ = nullptr;
  bool recovered_stale_ = false;
};

// A client (the HMI, `lasercnc status`): maps an existing segment after
// checking magic, version and size.
class ShmClient {
 public:
  [[nodiscard]] static Result<ShmClient> open(const std::string& name = kDefaultName);
  ShmClient(ShmClient&&) noexcept;
  ShmClient& operator=(ShmClient&&) = delete;
  ~ShmClient();
  [[nodiscard]] ShmBlock& block() noexcept { return *block_; }
  // Puts `c` into the command ring with the next sequence number of the
  // segment (unique among all senders); the number, or 0 when the ring is
  // full or the senders' lock was not had within `lock_timeout`. Takes the
  // senders' lock: never from an RT thread. A sender that died holding it
  // does not block the others (robust mutex); a live one that holds it
  // delays them by `lock_timeout` at most. An e-stop is requested through
  // the e-stop word first (request_estop), lock or no lock.
  std::uint32_t send(Command c, std::chrono::nanoseconds lock_timeout = kDefaultLockTimeout);
  static constexpr std::chrono::nanoseconds kDefaultLockTimeout = std::chrono::seconds(1);
  // Asks the RT kernel for an e-stop: one atomic add, no lock, no wait.
  void request_estop() noexcept;
  // The answer to command `seq`, once the daemon has written it (and no
  // kAnswerSlots later commands have taken its slot since).
  [[nodiscard]] bool answer(std::uint32_t seq, Answer& out) const noexcept;
  // The owner process still exists.
  [[nodiscard]] bool owner_alive() const noexcept;

 private:
  explicit ShmClient(ShmBlock* block) : block_(block) {}
  ShmBlock* block_ = nullptr;
};

}  // namespace lcnc::shm
