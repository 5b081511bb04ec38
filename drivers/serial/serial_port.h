// A raw serial port (termios, 8N1, no flow control, no echo, no line
// editing) for the line-protocol devices, and the pseudo-terminal helpers
// the tests and the virtual devices use in place of real RS-232 ports.
//
// A pty has no baud-rate timing: bytes move as fast as the kernel copies
// them. The baud rate is still set, so a real port opened the same way
// behaves the same; the benchmarks say so where it matters.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/result.h"

namespace lcnc::drivers {

// Puts an open tty fd into raw 8N1 mode at `baud` (one of the standard rates).
[[nodiscard]] Status make_raw(int fd, int baud, const std::string& what);

// One end of a pseudo-terminal pair: `master_fd` is the device side, `path`
// (/dev/pts/N) the side a client opens as its serial port. `slave_fd` is kept
// open so the master side never sees EIO while no client has the port open.
struct Pty {
  int master_fd = -1;
  int slave_fd = -1;
  std::string path;
};
[[nodiscard]] Result<Pty> open_pty();
void close_pty(Pty& pty) noexcept;

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  [[nodiscard]] Status open(const std::string& path, int baud);
  void close() noexcept;
  [[nodiscard]] bool is_open() const noexcept { return fd_ >= 0; }
  // Discards whatever is waiting to be read (stale answers).
  void flush_input() noexcept;
  [[nodiscard]] Status write_all(std::string_view bytes);
  // Reads one line ending in '\n' (returned with its "\r\n"), or fails with
  // PeripheralTimeout when none completes within `timeout`, or SerialSyntax
  // when a line grows beyond `max_len` bytes (it is then discarded).
  [[nodiscard]] Result<std::string> read_line(std::chrono::milliseconds timeout, std::size_t max_len = 256);
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  int fd_ = -1;
  std::string path_;
  std::string pending_;  // bytes read past the last line
};

}  // namespace lcnc::drivers
