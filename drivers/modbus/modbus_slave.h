// Modbus slave (server) for one device of the register map, over RTU (a
// serial line) or TCP (bound to 127.0.0.1 unless configured otherwise), on
// its own thread. It is what lasercncd exposes to a PLC or an MES, and what
// every virtual device is built on. (docs/design.md §8, Shao (2022) §4 and fig. 15: the
// slave checks the address, parses function code and offset, then answers
// or reports an exception.)
//
// Function codes 1, 2, 3, 4 (read), 5, 6, 15, 16 (write); anything else gets
// exception 01. Each request is checked against the register map before
// anything changes:
//   * an address with no register, a write to a read-only register, or a
//     write that covers only one word of a 32-bit register → exception 02;
//   * a value outside its register's range (or a malformed count) → 03;
//   * the owner's write hook may refuse a valid write (e.g. 04 or 06).
// A refused request changes nothing: a block with one bad value leaves every
// register of the block as it was. Libmodbus frames RTU (requests with a
// bad CRC are dropped and counted) and builds every answer; TCP frames are
// cut by their MBAP header and checked (slave_request.h).
//
// The owner publishes status with set()/with_bank() (input registers,
// discrete inputs) and receives parameter writes and commands through the
// write hook; a tick hook runs the owner's model periodically on the slave's
// thread. Both hooks run under the bank's lock, so a hook sees the registers
// consistent and must be quick (no blocking I/O). stop() is prompt: the
// thread polls an eventfd next to its sockets.
//
// TCP clients are served fairly: one poll loop reads whatever bytes each
// connection has into that connection's buffer and answers only whole
// frames, so a client trickling its request byte by byte, or sending half
// a frame and going quiet, delays nobody else. A connection is closed when
// its frame stalls (kTcpByteTimeout between bytes, kTcpFrameTimeout from
// the first byte) or when it stays silent for the idle timeout; at the
// connection limit a new client replaces the connection silent the
// longest, so idle connections cannot lock the slave.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "common/result.h"
#include "drivers/modbus/modbus_types.h"
#include "drivers/modbus/register_bank.h"
#include "drivers/modbus/register_map.h"
#include "drivers/modbus/slave_request.h"

namespace lcnc::drivers {

// A master writes each request (at most 260 bytes) in one go, so its bytes
// arrive together; a pause this long inside a frame means the sender
// stalled or is not speaking Modbus. The same bound as libmodbus's byte
// timeout on the RTU line.
inline constexpr std::chrono::milliseconds kTcpByteTimeout{100};
// A frame must be whole this long after its first byte: bounds how long a
// client sending a byte just inside kTcpByteTimeout holds its connection.
inline constexpr std::chrono::milliseconds kTcpFrameTimeout{1000};
// A PLC, MES or ModbusMaster polls far more often than this; a connection
// silent for a minute is abandoned. Closing it costs a live master only a
// reconnect on its next request (ModbusMaster retries after a lost link).
inline constexpr std::chrono::milliseconds kTcpIdleTimeout{60'000};
// Connections served at once: a PLC, an MES, an HMI and some spare.
inline constexpr int kTcpMaxClients = 8;

struct SlaveConfig {
  Endpoint endpoint;                 // TCP 127.0.0.1:0 (any free port) by default
  int unit_id = -1;                  // −1: the map's unit_id (RTU answers only it; TCP it, 0 and 255)
  int max_clients = kTcpMaxClients;  // TCP connections served at once (≥ 1)
  std::chrono::milliseconds idle_timeout = kTcpIdleTimeout;  // TCP: a silent connection is closed
  // TCP: a frame's bytes may be this far apart, and it must be whole this
  // long after its first byte; otherwise its connection is closed.
  std::chrono::milliseconds byte_timeout = kTcpByteTimeout;
  std::chrono::milliseconds frame_timeout = kTcpFrameTimeout;
  std::chrono::milliseconds tick_period{0};  // 0: no tick hook calls
};

struct SlaveCounters {
  std::uint64_t requests = 0;        // well-framed requests received
  std::uint64_t exceptions = 0;      // answered with an exception, or not a request (fc ≥ 0x80)
  std::uint64_t refused_writes = 0;  // writes refused (exceptions 02/03/hook)
  std::uint64_t crc_errors = 0;      // RTU frames dropped for a bad CRC
  std::uint64_t connections = 0;     // TCP connections accepted
  std::uint64_t malformed = 0;       // TCP frames refused for their MBAP header (slave_request.h)
  std::uint64_t idle_closed = 0;     // TCP connections closed after the idle timeout
  std::uint64_t frame_timeouts = 0;  // TCP connections closed for a frame left unfinished
  std::uint64_t evicted = 0;         // TCP connections dropped for a new client at the limit
};

// Called every tick_period with the seconds since the last call.
using TickHook = std::function<void(double dt_s, RegisterBank&)>;

class ModbusSlave {
 public:
  ModbusSlave(DeviceMap map, SlaveConfig config);
  ~ModbusSlave();
  ModbusSlave(const ModbusSlave&) = delete;
  ModbusSlave& operator=(const ModbusSlave&) = delete;

  // Hooks are set before start().
  void set_write_hook(WriteHook hook);
  void set_tick_hook(TickHook hook);

  // Opens the serial port or binds the TCP port, then starts the thread.
  [[nodiscard]] Status start();
  void stop() noexcept;
  [[nodiscard]] bool running() const noexcept;

  // The endpoint as bound (TCP: the real port when 0 was asked for).
  [[nodiscard]] Endpoint endpoint() const;
  [[nodiscard]] std::uint16_t port() const noexcept;
  [[nodiscard]] const DeviceMap& map() const noexcept;

  // The owner's side (any thread): by name, range-checked.
  [[nodiscard]] Result<double> get(std::string_view name) const;
  [[nodiscard]] Status set(std::string_view name, double value);
  // Several reads/writes under one lock (a consistent status snapshot).
  void with_bank(const std::function<void(RegisterBank&)>& fn);
  // The same when no request is being served now; false (fn not called)
  // otherwise. For an owner that the write hook may be waiting for: it must
  // not wait for the bank in turn.
  bool try_with_bank(const std::function<void(RegisterBank&)>& fn);

  [[nodiscard]] SlaveCounters counters() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcnc::drivers
