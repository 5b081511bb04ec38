// Live read-back of one peripheral for the adjustment and monitoring screen:
// its registers read over Modbus every `period` on a thread of its own
// (drivers/modbus/modbus_master.h, one request per table block), the latest
// values and a history of chosen ones kept for the screen to show; writes
// queued to the device without waiting, the last one's outcome kept. The
// screen's timer only copies a snapshot: a slow or lost device never blocks
// it. Qt-free.
#pragma once

#include <atomic>
#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/result.h"
#include "drivers/modbus/modbus_master.h"

namespace lcnc::hmi {

struct PollSnapshot {
  std::map<std::string, double> values;  // the last good reading of each
  bool linked = false;                   // the last poll got through
  std::string error;                     // why not, when not
  std::string last_write;                // "" ok / pending; else why it failed
  drivers::MasterCounters counters;
  std::uint64_t polls = 0;
};

struct HistorySample {
  double t_s = 0;              // since the poller started
  std::vector<double> values;  // of history_names, in order
};

class DevicePoller {
 public:
  // `device`: a device of the shipped register map. `history`: the registers
  // whose values are also kept over time (up to `history_s`).
  static Result<std::unique_ptr<DevicePoller>> start(
      const std::string& device, const drivers::Endpoint& at, std::vector<std::string> history = {},
      std::chrono::milliseconds period = std::chrono::milliseconds(100), double history_s = 60.0);
  ~DevicePoller();
  DevicePoller(const DevicePoller&) = delete;
  DevicePoller& operator=(const DevicePoller&) = delete;

  [[nodiscard]] PollSnapshot snapshot() const;
  [[nodiscard]] std::vector<HistorySample> history() const;
  [[nodiscard]] const std::vector<std::string>& history_names() const noexcept { return history_names_; }

  // Queued, not waited for; the outcome shows in snapshot().last_write.
  void write(const std::string& name, double value);
  void write_block(const std::vector<std::pair<std::string, double>>& values);

 private:
  DevicePoller(std::unique_ptr<drivers::ModbusMaster> m, std::vector<std::string> history,
               std::chrono::milliseconds period, double history_s);
  void run() noexcept;

  std::unique_ptr<drivers::ModbusMaster> master_;
  std::vector<std::vector<std::string>> blocks_;  // the map's registers, one read per table
  std::vector<std::string> history_names_;
  std::chrono::milliseconds period_;
  double history_s_;
  mutable std::mutex mutex_;
  PollSnapshot snap_;
  std::deque<HistorySample> history_;
  std::atomic<bool> running_{true};
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  std::thread thread_;
};

}  // namespace lcnc::hmi
