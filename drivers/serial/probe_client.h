// The host side of the 3D point probe's RS-232 protocol (probe_protocol.h):
// sends $MEAS,<id>, waits for the $POS or $ERR with the same id, and checks
// the point against the probe_3d ranges of the register map. A corrupted or
// malformed answer is counted, and the request sent again (up to `retries`
// times); an answer with another id (a late one) is skipped; no answer in
// `timeout` is PeripheralTimeout. Every wait is bounded.
//
// measure() blocks for at most (1 + retries) · timeout: call it from a
// worker thread, or use measure_async(), which runs it on one.
#pragma once

#include <chrono>
#include <cstdint>
#include <future>
#include <mutex>
#include <string>

#include "common/result.h"
#include "drivers/modbus/register_map.h"
#include "drivers/serial/probe_protocol.h"
#include "drivers/serial/serial_port.h"

namespace lcnc::drivers {

struct ProbeClientConfig {
  std::string device;  // /dev/ttyS0, /dev/pts/N
  int baud = 115200;
  std::chrono::milliseconds timeout{300};
  int retries = 2;
};

struct ProbeCounters {
  std::uint64_t requests = 0;
  std::uint64_t points = 0;
  std::uint64_t checksum_errors = 0;  // answers with a bad checksum
  std::uint64_t syntax_errors = 0;    // malformed answers
  std::uint64_t timeouts = 0;
  std::uint64_t device_errors = 0;  // $ERR answers
  std::uint64_t stale = 0;          // answers to an earlier request, skipped
};

class ProbeClient {
 public:
  // `map` is the probe_3d device of the register map (for the ranges).
  ProbeClient(DeviceMap map, ProbeClientConfig config);

  [[nodiscard]] Status open();
  void close() noexcept;

  [[nodiscard]] Result<probe::PointReply> measure();
  [[nodiscard]] std::future<Result<probe::PointReply>> measure_async();
  [[nodiscard]] Result<probe::PongReply> ping();

  [[nodiscard]] ProbeCounters counters() const;

 private:
  // Sends `request` and returns the first good answer to it.
  Result<probe::Message> transact(const probe::Message& request, std::uint16_t id);

  DeviceMap map_;
  ProbeClientConfig cfg_;
  mutable std::mutex mutex_;  // one transaction at a time; guards port_, counters_
  SerialPort port_;
  std::uint16_t next_id_ = 1;
  ProbeCounters counters_;
};

}  // namespace lcnc::drivers
