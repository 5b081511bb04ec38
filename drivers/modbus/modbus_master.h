// Modbus master (client) for one device of the register map, over libmodbus
// RTU or TCP. Asynchronous: every call queues a request for the master's own
// worker thread and returns at once — a future, or a callback run on the
// worker thread — so a GUI thread never waits on the wire (docs/design.md §8).
//
// Per request, in order:
//   1. connect if the link is down (at most once per reconnect_interval;
//      while the device stays away requests fail at once with
//      PeripheralDisconnected instead of queueing up behind timeouts);
//   2. send, wait up to response_timeout for the answer;
//   3. on a timeout, a corrupted answer (bad CRC, garbled frame) or a lost
//      link (reconnect first): try again, up to `retries` more times;
//      an exception answer is final (the device has spoken);
//   4. complete the request with the data or one clear Diagnostic:
//      "laser_source (unit 2, tcp 127.0.0.1:40123): write power_setpoint_pct
//       = 120: …". Counters record each kind of fault.
// On RTU, `rtu_reopen_after` consecutive failed requests close and reopen
// the port (a USB adapter that was re-plugged); on TCP a broken connection
// is reopened at the next attempt. Typed accessors go by register name,
// scale to engineering units and check the map's range both ways: a value
// out of range is never sent, and a device reporting one is an error.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/result.h"
#include "drivers/modbus/modbus_types.h"
#include "drivers/modbus/register_map.h"

namespace lcnc::drivers {

struct MasterConfig {
  Endpoint endpoint;  // TCP host:port, or RTU device/baud/parity
  int unit_id = -1;   // −1: the map's unit_id
  std::chrono::milliseconds response_timeout{200};
  std::chrono::milliseconds byte_timeout{50};  // between bytes of one answer
  int retries = 2;                             // further attempts after a timeout, corruption or lost link
  std::chrono::milliseconds reconnect_interval{200};
  int rtu_reopen_after = 3;          // consecutive failed requests before reopening the port
  std::size_t queue_capacity = 256;  // requests beyond it are refused at once
};

struct MasterCounters {
  std::uint64_t requests = 0;  // completed, either way
  std::uint64_t ok = 0;
  std::uint64_t failed = 0;
  std::uint64_t retries = 0;          // extra attempts made
  std::uint64_t timeouts = 0;         // attempts without an answer in time
  std::uint64_t crc_errors = 0;       // answers with a bad CRC
  std::uint64_t protocol_errors = 0;  // garbled answers (bad length, unit, function)
  std::uint64_t exceptions = 0;       // exception answers
  std::uint64_t link_errors = 0;      // connection lost, refused, port gone
  std::uint64_t reconnects = 0;       // links re-established after a loss
  std::uint64_t refused = 0;          // refused before the wire (queue full, stopped, range)
};

// One request in protocol terms. Bits travel as 0/1 words.
struct RawRequest {
  Function function = Function::ReadHoldingRegisters;
  std::uint16_t address = 0;
  std::uint16_t count = 1;          // reads; writes take data.size()
  std::vector<std::uint16_t> data;  // writes
  std::string what;                 // for messages: "read power_w"
};
using RawReply = std::vector<std::uint16_t>;  // read data; empty for writes
using RawCallback = std::function<void(Result<RawReply>)>;

class ModbusMaster {
 public:
  ModbusMaster(DeviceMap map, MasterConfig config);
  ~ModbusMaster();  // stop()
  ModbusMaster(const ModbusMaster&) = delete;
  ModbusMaster& operator=(const ModbusMaster&) = delete;

  // Starts the worker (the link is opened by the first request).
  [[nodiscard]] Status start();
  // Fails every queued request with PeripheralStopped and joins the worker
  // (after the request on the wire, if any: at most its timeouts). Not from
  // a callback (that runs on the worker it would join).
  void stop() noexcept;

  // Raw requests by function code. Never blocks; `done` runs on the worker
  // thread (or at once on this thread when the request is refused) and must
  // be quick: a GUI posts the result to its own thread from there.
  void submit(RawRequest request, RawCallback done);
  [[nodiscard]] std::future<Result<RawReply>> request(RawRequest request);

  // Typed, by register name (FC1/2/3/4 for reads by table; FC5 coil, FC6 a
  // one-word holding register, FC16 a two-word one).
  [[nodiscard]] std::future<Result<double>> read(std::string_view name);
  [[nodiscard]] std::future<Status> write(std::string_view name, double value);
  void read_async(std::string_view name, std::function<void(Result<double>)> done);
  void write_async(std::string_view name, double value, std::function<void(Status)> done);
  // Several registers of one table in one request (FC1/2/3/4 over the span
  // from the lowest to the highest address; every address of it mapped).
  [[nodiscard]] std::future<Result<std::vector<double>>> read_block(const std::vector<std::string>& names);
  void read_block_async(const std::vector<std::string>& names,
                        std::function<void(Result<std::vector<double>>)> done);
  // A parameter block: registers of one writable table that are contiguous
  // once sorted by address, written with one FC16 (holding) or FC15 (coils).
  // All values are range-checked first; one bad value sends nothing.
  [[nodiscard]] std::future<Status> write_block(const std::vector<std::pair<std::string, double>>& values);
  void write_block_async(const std::vector<std::pair<std::string, double>>& values,
                         std::function<void(Status)> done);

  [[nodiscard]] MasterCounters counters() const noexcept;
  [[nodiscard]] bool connected() const noexcept;
  [[nodiscard]] std::string last_error() const;  // empty until something fails
  [[nodiscard]] const DeviceMap& map() const noexcept;
  [[nodiscard]] std::string who() const;  // "laser_source (unit 2, tcp 127.0.0.1:40123)"

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace lcnc::drivers
