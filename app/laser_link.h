// The job's link to the laser source and the power meter over Modbus
// (register map devices laser_source and power_meter),
// as `lasercnc run --devices` (in-process simulators, drivers/devices/) or
// `--laser ENDPOINT [--power-meter ENDPOINT]` (real devices, or
// lasercnc-devices) use it.
//
// Before motion: the source is enabled and must report ready — a latched
// alarm refuses the run before anything moves. While the job runs: the
// power setpoint follows the commanded power (the RT thread's per-period
// output, docs/design.md §2) whenever it changes by more than kSetpointDeadband,
// at most every kSetpointInterval, and the meter is read every
// kMeterInterval — all asynchronous (ModbusMaster's worker), so the job's
// drain loop never waits on the wire. The source's alarm and temperature
// are read every kHealthInterval: a latched alarm, any reading outside its
// register's range (a failed sensor), or kFailuresToFault requests in a row
// without an answer make fault() say so, and the job stops along the path
// with the beam off (app/run_job.cpp). After the job (or on any fault): the
// setpoint goes to 0 and emission is disabled.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "common/result.h"
#include "drivers/devices/laser_source_sim.h"
#include "drivers/devices/power_meter_sim.h"
#include "drivers/modbus/modbus_master.h"

namespace lcnc::app {

struct PeripheralReport {
  bool used = false;
  bool simulated = false;  // in-process simulators (--devices)
  std::string laser;       // "laser_source (unit 2, tcp 127.0.0.1:40123)"
  std::string meter;       // empty: none
  double rated_power_w = 0.0;
  std::uint64_t setpoint_writes = 0;
  std::uint64_t meter_samples = 0;
  double meter_peak_w = 0.0;
  double meter_mean_lasing_w = 0.0;      // mean of the readings taken while the job lased
  double commanded_mean_lasing_w = 0.0;  // the commanded power at those readings, W
  double peak_temperature_c = 0.0;
  std::uint64_t requests = 0, failed = 0;  // Modbus, both devices
  std::string alarm;                       // what the source reported at the end; empty: none
  std::string error;                       // the first failed request; empty: none
};

class LaserLink {
 public:
  static constexpr std::chrono::milliseconds kSetpointInterval{20};
  static constexpr std::chrono::milliseconds kMeterInterval{50};
  static constexpr double kSetpointDeadband = 0.5;  // % of rated power
  static constexpr std::chrono::milliseconds kHealthInterval{200};
  // Failed requests to the source in a row that make it lost: one lost
  // frame is retried by the next request; three (~0.6 s of the health
  // polls, or each waiting out its timeout) is a link that is gone.
  static constexpr int kFailuresToFault = 3;

  // Starts a simulated laser source and a power meter in its beam on free
  // loopback ports, and links to them.
  [[nodiscard]] static Result<std::unique_ptr<LaserLink>> simulated();
  // Links to devices at these endpoints (the meter optional).
  [[nodiscard]] static Result<std::unique_ptr<LaserLink>> connect(
      const drivers::Endpoint& laser, const std::optional<drivers::Endpoint>& meter);
  ~LaserLink();

  // Enables emission at setpoint 0 and checks the source is ready; bounded
  // by the masters' timeouts. A failure names the device and why.
  [[nodiscard]] Status enable();
  // From the job's drain loop, with the commanded power now (% of rated).
  // Never blocks.
  void follow(double commanded_pct);
  // Why the source can no longer be trusted during the job (lost, alarm,
  // an implausible reading); empty while it is well. From any thread.
  [[nodiscard]] std::string fault();
  // Setpoint 0, emission off, the last status read; the report. (Without
  // it, the destructor still switches emission off.)
  [[nodiscard]] PeripheralReport finish();

 private:
  LaserLink() = default;
  [[nodiscard]] Status open(const drivers::Endpoint& laser, const std::optional<drivers::Endpoint>& meter);
  // Every answer of the source (and every failure) passes here: failures in
  // a row count toward fault().
  void note_result(const Status& s);
  void set_fault(std::string why);  // the first one stays (mutex_ held)

  std::unique_ptr<drivers::LaserSourceSim> laser_sim_;
  std::unique_ptr<drivers::PowerMeterSim> meter_sim_;
  std::unique_ptr<drivers::ModbusMaster> laser_;
  std::unique_ptr<drivers::ModbusMaster> meter_;
  PeripheralReport report_;
  double sent_pct_ = 0.0;
  double commanded_pct_ = 0.0;
  std::chrono::steady_clock::time_point next_setpoint_{}, next_meter_{}, next_health_{};
  int failures_in_row_ = 0;  // guarded by mutex_
  std::string fault_;        // guarded by mutex_
  bool enabled_ = false;     // enable() wrote enable = 1
  bool finished_ = false;    // finish() has switched it off (guarded by mutex_)
  bool meter_busy_ = false;  // one read outstanding at a time (guarded by mutex_)
  std::mutex mutex_;         // the callbacks (master's worker) ↔ the drain loop
  double meter_sum_w_ = 0.0, commanded_sum_w_ = 0.0;
  std::uint64_t lasing_samples_ = 0;
};

}  // namespace lcnc::app
