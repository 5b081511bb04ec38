// Virtual devices: simulators of the machine's peripherals (laser source,
// power meter, four-beam scanning head, displacement sensor, 3D probe), each
// a real Modbus slave (and the probe also a real serial device) serving the
// register map's device, so the HMI, the demo and the tests talk to them
// exactly as to the hardware. They are simulators and are named as such
// (…Sim); their physics is plausible, not calibrated.
//
// A VirtualDevice runs its model on the slave's thread every tick (10 ms by
// default), under the register bank's lock: the model reads its parameter
// registers and writes its status registers in one step, so a master never
// sees half an update. Commands arrive as coils written 1; the model clears
// them when taken. Noise comes from a seeded generator (deterministic given
// the sequence of ticks).
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <random>
#include <span>
#include <string_view>

#include "common/result.h"
#include "drivers/modbus/modbus_slave.h"

namespace lcnc::drivers {

inline constexpr std::chrono::milliseconds kDeviceTick{10};

// The measured surface of the workpiece, z(x, y) in mm (machine frame): a
// tilted plane with a gentle waviness — enough shape for the six-point and
// focal-length workflows to have something to find.
struct SurfaceModel {
  double z0_mm = 20.0;         // z at x = y = 0
  double slope_x = 0.002;      // dz/dx
  double slope_y = -0.001;     // dz/dy
  double wave_amp_mm = 0.05;   // amplitude of the waviness
  double wave_len_mm = 200.0;  // its wavelength in x and y

  [[nodiscard]] double z_at(double x_mm, double y_mm) const noexcept {
    constexpr double kTwoPi = 6.283185307179586;
    return z0_mm + slope_x * x_mm + slope_y * y_mm +
           wave_amp_mm * std::sin(kTwoPi * x_mm / wave_len_mm) * std::sin(kTwoPi * y_mm / wave_len_mm);
  }
};

// Gaussian noise from a seeded generator.
class Noise {
 public:
  explicit Noise(std::uint64_t seed) : rng_(seed) {}
  [[nodiscard]] double operator()(double sigma) { return sigma > 0 ? sigma * dist_(rng_) : 0.0; }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> dist_{0.0, 1.0};
};

// First-order lag: the fraction of the way to the target covered in dt.
[[nodiscard]] inline double lag_fraction(double dt_s, double tau_s) noexcept {
  return tau_s > 0 ? 1.0 - std::exp(-dt_s / tau_s) : 1.0;
}

class VirtualDevice {
 public:
  virtual ~VirtualDevice();
  VirtualDevice(const VirtualDevice&) = delete;
  VirtualDevice& operator=(const VirtualDevice&) = delete;

  [[nodiscard]] virtual Status start();
  virtual void stop() noexcept;
  [[nodiscard]] ModbusSlave& slave() noexcept { return *slave_; }
  [[nodiscard]] Endpoint endpoint() const { return slave_->endpoint(); }
  [[nodiscard]] const std::string& name() const noexcept { return slave_->map().name; }

 protected:
  // `config.tick_period` 0 means kDeviceTick.
  VirtualDevice(DeviceMap map, SlaveConfig config);
  // Every register the model uses must be in the map: checked once, by
  // name, when the device is made, so a mismatched map is an error there.
  [[nodiscard]] static Status require(const DeviceMap& map, std::string_view device,
                                      std::initializer_list<std::string_view> names);

  virtual void tick(double dt_s, RegisterBank& bank) = 0;
  virtual ModbusException on_write(std::span<const RegisterWrite> writes, RegisterBank& bank);

 private:
  std::unique_ptr<ModbusSlave> slave_;
};

}  // namespace lcnc::drivers
