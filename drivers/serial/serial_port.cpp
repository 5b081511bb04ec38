#include "drivers/serial/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace lcnc::drivers {

namespace {

speed_t speed_of(int baud) noexcept {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return B0;
  }
}

std::string errno_text() { return std::strerror(errno); }

}  // namespace

Status make_raw(int fd, int baud, const std::string& what) {
  const speed_t speed = speed_of(baud);
  if (speed == B0)
    return make_error(ErrorCode::PeripheralSetup,
                      what + ": baud rate " + std::to_string(baud) +
                          " unsupported; expected 9600 … 921600 (a standard rate)");
  termios tio{};
  if (tcgetattr(fd, &tio) != 0)
    return make_error(ErrorCode::PeripheralSetup, what + ": not a terminal: " + errno_text());
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB | PARENB);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  if (tcsetattr(fd, TCSANOW, &tio) != 0)
    return make_error(ErrorCode::PeripheralSetup, what + ": cannot set raw mode: " + errno_text());
  return {};
}

Result<Pty> open_pty() {
  Pty p;
  char name[128] = {};
  if (openpty(&p.master_fd, &p.slave_fd, name, nullptr, nullptr) != 0)
    return make_error(ErrorCode::PeripheralSetup, "openpty failed: " + errno_text());
  p.path = name;
  // Raw before anyone opens the path: an echoing pty would reflect every
  // request back to its sender.
  if (Status s = make_raw(p.slave_fd, 115200, p.path); !s) {
    close_pty(p);
    return s.error();
  }
  ::fcntl(p.master_fd, F_SETFL, ::fcntl(p.master_fd, F_GETFL) | O_NONBLOCK);
  ::fcntl(p.master_fd, F_SETFD, FD_CLOEXEC);
  ::fcntl(p.slave_fd, F_SETFD, FD_CLOEXEC);
  return p;
}

void close_pty(Pty& p) noexcept {
  if (p.master_fd >= 0) ::close(p.master_fd);
  if (p.slave_fd >= 0) ::close(p.slave_fd);
  p.master_fd = p.slave_fd = -1;
}

SerialPort::~SerialPort() { close(); }

Status SerialPort::open(const std::string& path, int baud) {
  close();
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    return make_error(ErrorCode::PeripheralSetup, "cannot open serial port " + path + ": " + errno_text());
  if (Status s = make_raw(fd, baud, path); !s) {
    ::close(fd);
    return s;
  }
  fd_ = fd;
  path_ = path;
  pending_.clear();
  return {};
}

void SerialPort::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  pending_.clear();
}

void SerialPort::flush_input() noexcept {
  pending_.clear();
  if (fd_ >= 0) tcflush(fd_, TCIFLUSH);
}

Status SerialPort::write_all(std::string_view bytes) {
  if (fd_ < 0) return make_error(ErrorCode::PeripheralDisconnected, "serial port not open");
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EAGAIN) {
      pollfd p{fd_, POLLOUT, 0};
      if (::poll(&p, 1, 100) <= 0) return make_error(ErrorCode::PeripheralTimeout, path_ + ": write blocked");
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    return make_error(ErrorCode::PeripheralDisconnected, path_ + ": write failed: " + errno_text());
  }
  return {};
}

Result<std::string> SerialPort::read_line(std::chrono::milliseconds timeout, std::size_t max_len) {
  if (fd_ < 0) return make_error(ErrorCode::PeripheralDisconnected, "serial port not open");
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (const std::size_t nl = pending_.find('\n'); nl != std::string::npos) {
      std::string line = pending_.substr(0, nl + 1);
      pending_.erase(0, nl + 1);
      if (line.size() > max_len)
        return make_error(ErrorCode::SerialSyntax, path_ + ": line of " + std::to_string(line.size()) +
                                                       " bytes; at most " + std::to_string(max_len));
      return line;
    }
    if (pending_.size() > max_len) {
      pending_.clear();
      return make_error(ErrorCode::SerialSyntax,
                        path_ + ": no line end within " + std::to_string(max_len) + " bytes");
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0)
      return make_error(ErrorCode::PeripheralTimeout,
                        path_ + ": no answer within " + std::to_string(timeout.count()) + " ms");
    pollfd p{fd_, POLLIN, 0};
    const int rc = ::poll(&p, 1, static_cast<int>(left.count()));
    if (rc < 0 && errno != EINTR)
      return make_error(ErrorCode::PeripheralDisconnected, path_ + ": " + errno_text());
    if (rc <= 0) continue;
    char buf[256];
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n > 0) {
      pending_.append(buf, static_cast<std::size_t>(n));
    } else if (n < 0 && errno != EAGAIN && errno != EINTR) {
      return make_error(ErrorCode::PeripheralDisconnected, path_ + ": read failed: " + errno_text());
    } else if (n == 0 || (p.revents & (POLLHUP | POLLERR))) {
      // The other side hung up: wait out the timeout rather than spin.
      const auto rest =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (rest.count() > 0) ::poll(nullptr, 0, static_cast<int>(std::min<long>(rest.count(), 10)));
    }
  }
}

}  // namespace lcnc::drivers
