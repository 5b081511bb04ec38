#include "app/laser_link.h"

#include <algorithm>
#include <cmath>

#include "drivers/modbus/register_map.h"

namespace lcnc::app {
namespace {

std::string alarm_text(double code) {
  return (static_cast<int>(code) & drivers::kAlarmOverTemperature) != 0
             ? "over-temperature"
             : "alarm code " + std::to_string(static_cast<int>(code));
}

}  // namespace

Result<std::unique_ptr<LaserLink>> LaserLink::simulated() {
  Result<drivers::DeviceMap> laser_map = drivers::shipped_device("laser_source");
  if (!laser_map) return laser_map.error();
  Result<drivers::DeviceMap> meter_map = drivers::shipped_device("power_meter");
  if (!meter_map) return meter_map.error();
  std::unique_ptr<LaserLink> link(new LaserLink());
  auto laser = drivers::LaserSourceSim::create(*laser_map);
  if (!laser) return laser.error();
  link->laser_sim_ = std::move(laser).value();
  drivers::PowerMeterParams mp;
  mp.source = [l = link->laser_sim_.get()] { return l->output_power_w(); };
  auto meter = drivers::PowerMeterSim::create(*meter_map, {}, mp);
  if (!meter) return meter.error();
  link->meter_sim_ = std::move(meter).value();
  if (Status s = link->laser_sim_->start(); !s.ok()) return s.error();
  if (Status s = link->meter_sim_->start(); !s.ok()) return s.error();
  link->report_.simulated = true;
  if (Status s = link->open(link->laser_sim_->endpoint(), link->meter_sim_->endpoint()); !s.ok())
    return s.error();
  return link;
}

Result<std::unique_ptr<LaserLink>> LaserLink::connect(const drivers::Endpoint& laser,
                                                      const std::optional<drivers::Endpoint>& meter) {
  std::unique_ptr<LaserLink> link(new LaserLink());
  if (Status s = link->open(laser, meter); !s.ok()) return s.error();
  return link;
}

Status LaserLink::open(const drivers::Endpoint& laser, const std::optional<drivers::Endpoint>& meter) {
  Result<drivers::DeviceMap> laser_map = drivers::shipped_device("laser_source");
  if (!laser_map) return laser_map.error();
  drivers::MasterConfig lc;
  lc.endpoint = laser;
  laser_ = std::make_unique<drivers::ModbusMaster>(*laser_map, lc);
  if (Status s = laser_->start(); !s.ok()) return s;
  report_.used = true;
  report_.laser = laser_->who();
  if (meter) {
    Result<drivers::DeviceMap> meter_map = drivers::shipped_device("power_meter");
    if (!meter_map) return meter_map.error();
    drivers::MasterConfig mc;
    mc.endpoint = *meter;
    meter_ = std::make_unique<drivers::ModbusMaster>(*meter_map, mc);
    if (Status s = meter_->start(); !s.ok()) return s;
    report_.meter = meter_->who();
  }
  return {};
}

LaserLink::~LaserLink() {
  // Not finished (an error path): emission off all the same, bounded by the
  // master's timeouts — a link is never left with the laser enabled.
  if (laser_ && enabled_ && !finished_) {
    (void)laser_->write("power_setpoint_pct", 0).get();
    (void)laser_->write("enable", 0).get();
  }
  // the masters first: their callbacks refer to this object
  if (laser_) laser_->stop();
  if (meter_) meter_->stop();
  if (meter_sim_) meter_sim_->stop();
  if (laser_sim_) laser_sim_->stop();
}

void LaserLink::note_result(const Status& s) {
  std::lock_guard lock(mutex_);
  if (s.ok()) {
    failures_in_row_ = 0;
    return;
  }
  if (report_.error.empty()) report_.error = s.error().message;
  if (finished_) return;
  // a reading its register cannot hold (a sensor open or shorted reads as
  // the word's end, 3276.7 °C): the device and its map disagree, and no
  // value of it can be trusted
  if (s.error().code == ErrorCode::PeripheralValueOutOfRange)
    set_fault(s.error().message + ": taken as a failed sensor");
  if (++failures_in_row_ >= kFailuresToFault)
    set_fault(laser_->who() + " lost: " + std::to_string(failures_in_row_) + " requests in a row failed (" +
              s.error().message + ")");
}

void LaserLink::set_fault(std::string why) {
  if (fault_.empty()) fault_ = std::move(why);
}

std::string LaserLink::fault() {
  std::lock_guard lock(mutex_);
  return fault_;
}

Status LaserLink::enable() {
  if (Status s = laser_->write("power_setpoint_pct", 0).get(); !s.ok()) return s;
  if (Status s = laser_->write("enable", 1).get(); !s.ok()) return s;
  enabled_ = true;
  Result<double> ready = laser_->read("ready").get();
  if (!ready) return ready.error();
  if (*ready != 1.0)
    return make_error(ErrorCode::PeripheralException, laser_->who() + ": enabled but not ready");
  Result<double> rated = laser_->read("rated_power_w").get();
  if (!rated) return rated.error();
  report_.rated_power_w = *rated;
  const auto now = std::chrono::steady_clock::now();
  next_setpoint_ = next_meter_ = next_health_ = now;
  return {};
}

void LaserLink::follow(double commanded_pct) {
  const auto now = std::chrono::steady_clock::now();
  commanded_pct_ = std::clamp(commanded_pct, 0.0, 100.0);
  if (now >= next_setpoint_ && std::abs(commanded_pct_ - sent_pct_) > kSetpointDeadband) {
    next_setpoint_ = now + kSetpointInterval;
    sent_pct_ = commanded_pct_;
    ++report_.setpoint_writes;
    laser_->write_async("power_setpoint_pct", sent_pct_, [this](const Status& s) { note_result(s); });
  }
  if (now >= next_health_) {
    next_health_ = now + kHealthInterval;
    laser_->read_async("temperature_c", [this](Result<double> t) {
      if (!t) return note_result(t.error());
      note_result({});
      std::lock_guard lock(mutex_);
      report_.peak_temperature_c = std::max(report_.peak_temperature_c, *t);
    });
    laser_->read_async("alarm_code", [this](Result<double> a) {
      if (!a) return note_result(a.error());
      note_result({});
      if (*a == 0.0) return;
      std::lock_guard lock(mutex_);
      set_fault(laser_->who() + " alarm: " + alarm_text(*a));
    });
  }
  if (meter_ && now >= next_meter_) {
    std::lock_guard lock(mutex_);
    if (meter_busy_) return;
    meter_busy_ = true;
    next_meter_ = now + kMeterInterval;
    const double commanded_w = commanded_pct_ / 100.0 * report_.rated_power_w;
    meter_->read_async("power_w", [this, commanded_w](Result<double> w) {
      std::lock_guard lock(mutex_);
      meter_busy_ = false;
      if (!w) {
        if (report_.error.empty()) report_.error = w.error().message;
        return;
      }
      ++report_.meter_samples;
      report_.meter_peak_w = std::max(report_.meter_peak_w, *w);
      if (commanded_w > 0.0) {
        meter_sum_w_ += *w;
        commanded_sum_w_ += commanded_w;
        ++lasing_samples_;
      }
    });
  }
}

PeripheralReport LaserLink::finish() {
  {
    std::lock_guard lock(mutex_);
    finished_ = true;  // failures from here on are the link's end, not a fault
  }
  note_result(laser_->write("power_setpoint_pct", 0).get());
  note_result(laser_->write("enable", 0).get());
  if (Result<double> alarm = laser_->read("alarm_code").get(); !alarm) {
    note_result(alarm.error());
  } else if (*alarm != 0.0) {
    std::lock_guard lock(mutex_);
    report_.alarm = alarm_text(*alarm);
  }
  // the masters are done: every callback has run
  laser_->stop();
  if (meter_) meter_->stop();
  std::lock_guard lock(mutex_);
  if (lasing_samples_ > 0) {
    report_.meter_mean_lasing_w = meter_sum_w_ / static_cast<double>(lasing_samples_);
    report_.commanded_mean_lasing_w = commanded_sum_w_ / static_cast<double>(lasing_samples_);
  }
  const drivers::MasterCounters lc = laser_->counters();
  report_.requests = lc.requests;
  report_.failed = lc.failed;
  if (meter_) {
    const drivers::MasterCounters mc = meter_->counters();
    report_.requests += mc.requests;
    report_.failed += mc.failed;
  }
  return report_;
}

}  // namespace lcnc::app
