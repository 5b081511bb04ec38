#include "rt/hal_block.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>

namespace lcnc::shm {
namespace {

// Like the main segment's: the daemon's user and group. The HAL's
// rtapi_app must run as one of them.
constexpr mode_t kHalMode = 0660;

Diagnostic hal_error(const std::string& name, const std::string& what) {
  return make_error(ErrorCode::RtShmLink, "shared memory '" + name + "': " + what);
}

}  // namespace

Result<HalSegment> HalSegment::create(const std::string& main_name, const std::string& machine_path,
                                      const std::array<std::int64_t, kAxisCount>& start_steps) {
  const std::string name = hal_segment_name(main_name);
  if (machine_path.size() >= sizeof(HalHeader::machine_path))
    return hal_error(name, "machine path longer than " + std::to_string(sizeof(HalHeader::machine_path) - 1) +
                               " bytes: " + machine_path);
  shm_unlink(name.c_str());  // a dead daemon's
  const int fd = shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, kHalMode);
  if (fd < 0) return hal_error(name, std::string("cannot create: ") + std::strerror(errno));
  fchmod(fd, kHalMode);
  if (ftruncate(fd, sizeof(HalBlock)) != 0) {
    const int e = errno;
    close(fd);
    shm_unlink(name.c_str());
    return hal_error(name, std::string("cannot size: ") + std::strerror(e));
  }
  void* at = mmap(nullptr, sizeof(HalBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  if (at == MAP_FAILED) {
    shm_unlink(name.c_str());
    return hal_error(name, "cannot map");
  }
  HalBlock* b = new (at) HalBlock();
  b->header.version = kHalVersion;
  b->header.size = sizeof(HalBlock);
  b->header.owner_pid = getpid();
  std::snprintf(b->header.machine_path, sizeof b->header.machine_path, "%s", machine_path.c_str());
  b->header.start_steps = start_steps;
  // the magic last: a component that sees it sees the rest
  std::atomic_thread_fence(std::memory_order_release);
  b->header.magic = kHalMagic;
  return HalSegment(name, b);
}

HalSegment::HalSegment(HalSegment&& o) noexcept : name_(std::move(o.name_)), block_(o.block_) {
  o.block_ = nullptr;
}

HalSegment::~HalSegment() {
  if (block_ == nullptr) return;
  block_->~HalBlock();
  munmap(block_, sizeof(HalBlock));
  shm_unlink(name_.c_str());
}

pid_t HalSegment::attached() const noexcept {
  const pid_t pid = block_->header.attached.load(std::memory_order_acquire);
  return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM) ? pid : 0;
}

}  // namespace lcnc::shm
