#include "drivers/devices/laser_source_sim.h"

namespace lcnc::drivers {

Result<std::unique_ptr<LaserSourceSim>> LaserSourceSim::create(DeviceMap map, SlaveConfig config,
                                                               LaserSourceParams params) {
  if (Status s = require(map, "laser_source",
                         {"enable", "alarm_reset", "ready", "emission", "alarm", "power_setpoint_pct",
                          "status", "alarm_code", "output_power_w", "temperature_c", "rated_power_w"});
      !s)
    return s.error();
  return std::unique_ptr<LaserSourceSim>(new LaserSourceSim(std::move(map), std::move(config), params));
}

LaserSourceSim::LaserSourceSim(DeviceMap map, SlaveConfig config, LaserSourceParams params)
    : VirtualDevice(std::move(map), std::move(config)), p_(params), temp_c_(params.ambient_c) {
  slave().with_bank([&](RegisterBank& b) {
    b.set_clamped(b.def("rated_power_w"), p_.rated_power_w);
    b.set_clamped(b.def("temperature_c"), temp_c_);
    b.set_clamped(b.def("ready"), 1);
  });
}

LaserSourceSim::~LaserSourceSim() { stop(); }

ModbusException LaserSourceSim::on_write(std::span<const RegisterWrite> writes, RegisterBank&) {
  for (const RegisterWrite& w : writes)
    if (w.reg->name == "enable" && w.value != 0 && alarm_) return ModbusException::DeviceFailure;
  return ModbusException::None;
}

void LaserSourceSim::tick(double dt, RegisterBank& b) {
  // Commands first: alarm_reset clears a latched alarm once it is cool.
  if (b.value(b.def("alarm_reset")) != 0) {
    if (alarm_ && temp_c_ < p_.reset_below_c) alarm_ = false;
    b.set_clamped(b.def("alarm_reset"), 0);
  }
  const bool enabled = b.value(b.def("enable")) != 0;
  const double setpoint_pct = b.value(b.def("power_setpoint_pct"));
  const bool emitting = enabled && !alarm_ && setpoint_pct > 0;
  const double target_w = emitting ? setpoint_pct / 100.0 * p_.rated_power_w : 0.0;
  power_w_ += (target_w - power_w_) * lag_fraction(dt, p_.power_tau_s);
  if (!emitting && power_w_ < 1e-6) power_w_ = 0.0;
  const double target_c = p_.ambient_c + p_.rise_at_full_c * power_w_ / p_.rated_power_w;
  temp_c_ += (target_c - temp_c_) * lag_fraction(dt, p_.thermal_tau_s);
  if (temp_c_ >= p_.alarm_c && !alarm_) {
    alarm_ = true;
    b.set_clamped(b.def("enable"), 0);  // interlock: emission off until reset
  }
  output_w_.store(power_w_, std::memory_order_relaxed);

  const LaserStatus status = alarm_     ? LaserStatus::Alarm
                             : emitting ? LaserStatus::Emitting
                             : enabled  ? LaserStatus::Ready
                                        : LaserStatus::Standby;
  b.set_clamped(b.def("status"), static_cast<double>(status));
  b.set_clamped(b.def("alarm_code"), alarm_ ? kAlarmOverTemperature : 0);
  b.set_clamped(b.def("alarm"), alarm_ ? 1 : 0);
  b.set_clamped(b.def("ready"), alarm_ ? 0 : 1);
  b.set_clamped(b.def("emission"), emitting ? 1 : 0);
  b.set_clamped(b.def("output_power_w"), power_w_);
  b.set_clamped(b.def("temperature_c"), temp_c_);
}

}  // namespace lcnc::drivers
