// Simulated ultrafast laser source (register map device "laser_source").
//
// Model, per tick dt:
//   emitting = enable ∧ ¬alarm ∧ setpoint > 0
//   P  += (P_target − P)·(1 − e^(−dt/τ_P)),  P_target = setpoint% · P_rated if emitting
//   T  += (T_amb + ΔT_full·P/P_rated − T)·(1 − e^(−dt/τ_T))     (pump diode)
//   T ≥ T_alarm → over-temperature alarm (latched): emission stops and
//   `enable` is cleared (an interlock); alarm_reset clears it once T < T_reset.
// With the defaults, full power settles at 25 + 30 = 55 °C and trips the
// 45 °C alarm after τ_T·ln 3 ≈ 22 s of sustained full power; 60 % settles
// at 43 °C and never trips. Writing enable = 1 while an alarm is latched is
// refused with exception 04 (server device failure).
#pragma once

#include <atomic>
#include <memory>

#include "drivers/devices/virtual_device.h"

namespace lcnc::drivers {

struct LaserSourceParams {
  double rated_power_w = 50.0;
  double power_tau_s = 0.005;  // output follows the setpoint
  double ambient_c = 25.0;
  double rise_at_full_c = 30.0;  // steady-state temperature rise at rated power
  double thermal_tau_s = 20.0;
  double alarm_c = 45.0;        // over-temperature trip
  double reset_below_c = 40.0;  // alarm_reset works below this
};

// Status register values (register map: laser_source.status).
enum class LaserStatus : std::uint8_t { Standby = 0, Ready = 1, Emitting = 2, Alarm = 3 };
inline constexpr std::uint16_t kAlarmOverTemperature = 1u << 0;

class LaserSourceSim final : public VirtualDevice {
 public:
  [[nodiscard]] static Result<std::unique_ptr<LaserSourceSim>> create(DeviceMap map, SlaveConfig config = {},
                                                                      LaserSourceParams params = {});
  ~LaserSourceSim() override;

  // The optical output now (W), for the power meter in its beam (any thread).
  [[nodiscard]] double output_power_w() const noexcept { return output_w_.load(std::memory_order_relaxed); }

 private:
  LaserSourceSim(DeviceMap map, SlaveConfig config, LaserSourceParams params);
  void tick(double dt_s, RegisterBank& bank) override;
  ModbusException on_write(std::span<const RegisterWrite> writes, RegisterBank& bank) override;

  LaserSourceParams p_;
  double power_w_ = 0.0;
  double temp_c_;
  bool alarm_ = false;
  std::atomic<double> output_w_{0.0};  // relaxed: a reading, nothing rides on it
};

}  // namespace lcnc::drivers
