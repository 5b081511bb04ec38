#include "rt/shm_interface.h"

#include "path/segment.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <new>

static_assert(lcnc::shm::kGasLowBit == lcnc::kOutputMist && lcnc::shm::kGasHighBit == lcnc::kOutputFlood,
              "the status's gas bits are the segments' output bits");

namespace lcnc::shm {
namespace {

constexpr mode_t kMode = 0660;

bool process_alive(pid_t pid) { return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM); }

Diagnostic shm_error(const std::string& name, const std::string& what) {
  return make_error(ErrorCode::RtShmLink, "shared memory '" + name + "': " + what);
}

ShmBlock* map(int fd) {
  void* p = mmap(nullptr, sizeof(ShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  return p == MAP_FAILED ? nullptr : static_cast<ShmBlock*>(p);
}

}  // namespace

Result<ShmOwner> ShmOwner::create(const std::string& name) {
  bool stale = false;
  int fd = shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, kMode);
  if (fd < 0 && errno == EEXIST) {
    // Someone's segment: live owner → refuse; dead owner → take it over.
    const int old = shm_open(name.c_str(), O_RDWR, 0);
    if (old >= 0) {
      struct stat st {};
      const bool sized = fstat(old, &st) == 0 && static_cast<std::size_t>(st.st_size) >= sizeof(ShmHeader);
      pid_t pid = 0;
      if (sized) {
        void* p = mmap(nullptr, sizeof(ShmHeader), PROT_READ, MAP_SHARED, old, 0);
        if (p != MAP_FAILED) {
          pid = static_cast<const ShmHeader*>(p)->owner_pid;
          munmap(p, sizeof(ShmHeader));
        }
      }
      close(old);
      if (process_alive(pid) && pid != getpid())
        return shm_error(
            name, "already owned by running process " + std::to_string(pid) + "; stop that daemon first");
    }
    shm_unlink(name.c_str());
    stale = true;
    fd = shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, kMode);
  }
  if (fd < 0) return shm_error(name, std::string("cannot create: ") + std::strerror(errno));
  fchmod(fd, kMode);  // whatever the umask
  if (ftruncate(fd, sizeof(ShmBlock)) != 0) {
    const int e = errno;
    close(fd);
    shm_unlink(name.c_str());
    return shm_error(name, std::string("cannot size: ") + std::strerror(e));
  }
  ShmBlock* block = map(fd);
  close(fd);
  if (block == nullptr) {
    shm_unlink(name.c_str());
    return shm_error(name, "cannot map");
  }
  new (block) ShmBlock();  // a fresh segment is zero-filled; construct in place
  pthread_mutexattr_t attr;
  pthread_mutexattr_init(&attr);
  pthread_mutexattr_setpshared(&attr, PTHREAD_PROCESS_SHARED);
  pthread_mutexattr_setrobust(&attr, PTHREAD_MUTEX_ROBUST);
  const int init = pthread_mutex_init(&block->senders.lock, &attr);
  pthread_mutexattr_destroy(&attr);
  if (init != 0) {
    munmap(block, sizeof(ShmBlock));
    shm_unlink(name.c_str());
    return shm_error(name, std::string("cannot make the senders' lock: ") + std::strerror(init));
  }
  block->header.version = kVersion;
  block->header.size = sizeof(ShmBlock);
  block->header.owner_pid = getpid();
  // release: a client that sees the magic sees the rest initialised.
  std::atomic_ref<std::uint32_t>(block->header.magic).store(kMagic, std::memory_order_release);
  return ShmOwner(name, block, stale);
}

ShmOwner::ShmOwner(ShmOwner&& o) noexcept
    : name_(std::move(o.name_)), block_(o.block_), recovered_stale_(o.recovered_stale_) {
  o.block_ = nullptr;
}

ShmOwner::~ShmOwner() {
  if (block_ == nullptr) return;
  munmap(block_, sizeof(ShmBlock));
  shm_unlink(name_.c_str());
}

Result<ShmClient> ShmClient::open(const std::string& name) {
  const int fd = shm_open(name.c_str(), O_RDWR, 0);
  if (fd < 0)
    return shm_error(name, std::string("cannot open (is lasercncd running?): ") + std::strerror(errno));
  struct stat st {};
  if (fstat(fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < sizeof(ShmBlock)) {
    close(fd);
    return shm_error(name, "segment too small: not a LaserCNC segment of this version");
  }
  ShmBlock* block = map(fd);
  close(fd);
  if (block == nullptr) return shm_error(name, "cannot map");
  // acquire: pairs with the owner's release store of the magic.
  const std::uint32_t magic =
      std::atomic_ref<std::uint32_t>(block->header.magic).load(std::memory_order_acquire);
  if (magic != kMagic || block->header.version != kVersion || block->header.size != sizeof(ShmBlock)) {
    munmap(block, sizeof(ShmBlock));
    return shm_error(name, "not a LaserCNC segment of interface version " + std::to_string(kVersion) +
                               " (magic, version or size differ)");
  }
  return ShmClient(block);
}

ShmClient::ShmClient(ShmClient&& o) noexcept : block_(o.block_) { o.block_ = nullptr; }

ShmClient::~ShmClient() {
  if (block_ != nullptr) munmap(block_, sizeof(ShmBlock));
}

std::uint32_t ShmClient::send(Command c, std::chrono::nanoseconds lock_timeout) {
  if (c.type == CommandType::EStop) request_estop();  // acts even if the lock is never had
  CommandSenders& s = block_->senders;
  // The robust mutex times out against CLOCK_REALTIME (glibc has no
  // monotonic timedlock for robust mutexes): a clock step during the wait
  // only lengthens or shortens this one wait.
  timespec until{};
  clock_gettime(CLOCK_REALTIME, &until);
  const std::int64_t ns = std::max<std::int64_t>(0, lock_timeout.count());
  until.tv_sec += static_cast<time_t>(ns / 1'000'000'000);
  until.tv_nsec += static_cast<long>(ns % 1'000'000'000);
  if (until.tv_nsec >= 1'000'000'000) {
    until.tv_nsec -= 1'000'000'000;
    ++until.tv_sec;
  }
  const int r = pthread_mutex_timedlock(&s.lock, &until);
  if (r == EOWNERDEAD)
    pthread_mutex_consistent(&s.lock);  // its push was whole or not begun
  else if (r != 0)
    return 0;
  c.seq = ++s.next_seq == 0 ? ++s.next_seq : s.next_seq;
  const bool pushed = block_->commands.try_push(c);
  pthread_mutex_unlock(&s.lock);
  return pushed ? c.seq : 0;
}

void ShmClient::request_estop() noexcept {
  // release pairs with the RT kernel's acquire load of the word: nothing
  // else is published with it, the order only keeps the add from moving
  // after what the sender does next.
  block_->estop.requests.fetch_add(1, std::memory_order_release);
}

bool ShmClient::answer(std::uint32_t seq, Answer& out) const noexcept {
  if (seq == 0) return false;
  Answer a;
  if (!block_->answers[seq % kAnswerSlots].load(a)) return false;
  if (a.seq != seq) return false;
  sanitize(a);
  out = a;
  return true;
}

bool ShmClient::owner_alive() const noexcept { return process_alive(block_->header.owner_pid); }

void sanitize(Status& s) noexcept {
  if (s.fault_axis < -1 || s.fault_axis >= static_cast<int>(s.pos.size())) s.fault_axis = -1;
  std::uint8_t pause = 0;  // the byte as written: a bool of any other value is undefined
  std::memcpy(&pause, &s.program_pause, 1);
  s.program_pause = pause != 0;
  if (s.input_wait < -1 || s.input_wait >= lcnc::kDigitalInputs) s.input_wait = -1;
}

void sanitize(JobStatus& j) noexcept {
  j.message[sizeof j.message - 1] = '\0';
  j.program[sizeof j.program - 1] = '\0';
  j.modes[sizeof j.modes - 1] = '\0';
  // the bytes as written: a bool of any other value is undefined
  for (bool* b : {&j.job_active, &j.inch, &j.mdi, &j.single_block, &j.dry_run}) {
    std::uint8_t byte = 0;
    std::memcpy(&byte, b, 1);
    *b = byte != 0;
  }
  if (j.coord_system >= 9) j.coord_system = 0;
  for (double& w : j.work_offset)
    if (!std::isfinite(w)) w = 0.0;
  for (double& d : j.distance_to_go)
    if (!std::isfinite(d)) d = 0.0;
  std::uint8_t outcome = 0;  // likewise an enum byte out of its range
  std::memcpy(&outcome, &j.last_outcome, 1);
  if (outcome > static_cast<std::uint8_t>(JobOutcome::Failed)) j.last_outcome = JobOutcome::None;
}

void sanitize(Event& e) noexcept {
  e.text[sizeof e.text - 1] = '\0';
  std::uint8_t severity = 0;  // an enum byte out of its range
  std::memcpy(&severity, &e.severity, 1);
  if (severity > static_cast<std::uint8_t>(Severity::Error)) e.severity = Severity::Error;
}

void sanitize(Answer& a) noexcept { a.message[sizeof a.message - 1] = '\0'; }

}  // namespace lcnc::shm
