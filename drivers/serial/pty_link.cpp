#include "drivers/serial/pty_link.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace lcnc::drivers {

PtyLink::~PtyLink() { stop(); }

Status PtyLink::start() {
  if (running_.load()) return {};
  auto a = open_pty();
  if (!a) return a.error();
  auto b = open_pty();
  if (!b) {
    close_pty(a.value());
    return b.error();
  }
  a_ = a.value();
  b_ = b.value();
  wake_fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (wake_fd_ < 0) {
    close_pty(a_);
    close_pty(b_);
    return make_error(ErrorCode::PeripheralSetup, std::string("eventfd: ") + std::strerror(errno));
  }
  running_.store(true);
  thread_ = std::thread([this] { run(); });
  return {};
}

void PtyLink::stop() noexcept {
  if (!running_.exchange(false)) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
  if (thread_.joinable()) thread_.join();
  ::close(wake_fd_);
  wake_fd_ = -1;
  close_pty(a_);
  close_pty(b_);
}

void PtyLink::corrupt_next(LinkDirection dir, std::size_t byte_offset) {
  std::lock_guard lock(fault_mutex_);
  armed_[static_cast<int>(dir)] = static_cast<long long>(byte_offset);
}

void PtyLink::set_connected(bool connected) noexcept {
  connected_.store(connected, std::memory_order_relaxed);
}

std::uint64_t PtyLink::bytes_relayed(LinkDirection dir) const noexcept {
  return relayed_[static_cast<int>(dir)].load();
}

void PtyLink::relay(int from, int to, LinkDirection dir) noexcept {
  unsigned char buf[512];
  const ssize_t n = ::read(from, buf, sizeof buf);
  if (n <= 0) return;  // EAGAIN, or EIO while a side has no reader: nothing to move
  if (!connected_.load(std::memory_order_relaxed)) return;  // the cable is pulled
  {
    std::lock_guard lock(fault_mutex_);
    long long& armed = armed_[static_cast<int>(dir)];
    if (armed >= 0) {
      if (armed < n) {
        buf[armed] ^= 0x01;
        armed = -1;
        corruptions_.fetch_add(1);
      } else {
        armed -= n;
      }
    }
  }
  relayed_[static_cast<int>(dir)].fetch_add(static_cast<std::uint64_t>(n));
  // A full far side (no reader) drops the rest, like a line with no listener.
  ssize_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(to, buf + done, static_cast<std::size_t>(n - done));
    if (w <= 0) break;
    done += w;
  }
}

void PtyLink::run() noexcept {
  while (running_.load()) {
    pollfd fds[3] = {{a_.master_fd, POLLIN, 0}, {b_.master_fd, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
    const int rc = ::poll(fds, 3, 100);
    if (rc < 0 && errno != EINTR) break;
    if (fds[2].revents & POLLIN) break;
    if (fds[0].revents & POLLIN) relay(a_.master_fd, b_.master_fd, LinkDirection::AtoB);
    if (fds[1].revents & POLLIN) relay(b_.master_fd, a_.master_fd, LinkDirection::BtoA);
  }
}

}  // namespace lcnc::drivers
