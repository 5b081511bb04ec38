// Simulated point-laser displacement sensor (register map device
// "displacement_sensor"): a triangulation sensor on the Z carriage, beam
// pointing down −Z, measuring range 30–70 mm.
//   d = z_sensor − surface.z(x_sensor, y_sensor) + N(0, σ/√averaging)
// Inside the range: distance_mm = d, in_range = 1, intensity highest at the
// middle of the range; outside: distance_mm = 0, in_range = 0. Where the
// sensor is comes from the machine (set_position(), any thread) — in the
// demo it stays where it was put.
#pragma once

#include <memory>
#include <mutex>

#include "drivers/devices/virtual_device.h"

namespace lcnc::drivers {

struct DisplacementSensorParams {
  SurfaceModel surface;
  double range_min_mm = 30.0;
  double range_max_mm = 70.0;
  double noise_mm = 0.002;  // σ of one sample
  std::uint64_t seed = 2;
};

class DisplacementSensorSim final : public VirtualDevice {
 public:
  [[nodiscard]] static Result<std::unique_ptr<DisplacementSensorSim>> create(
      DeviceMap map, SlaveConfig config = {}, DisplacementSensorParams params = {});
  ~DisplacementSensorSim() override;

  // Where the sensor's beam leaves it (mm, machine frame).
  void set_position(double x_mm, double y_mm, double z_mm);
  [[nodiscard]] const SurfaceModel& surface() const noexcept { return p_.surface; }

 private:
  DisplacementSensorSim(DeviceMap map, SlaveConfig config, DisplacementSensorParams params);
  void tick(double dt_s, RegisterBank& bank) override;

  DisplacementSensorParams p_;
  Noise noise_;
  std::mutex pos_mutex_;  // position: machine thread ↔ sensor thread
  double x_mm_ = 500.0, y_mm_ = 225.0, z_mm_ = 0.0;
  std::uint16_t samples_ = 0;
};

}  // namespace lcnc::drivers
