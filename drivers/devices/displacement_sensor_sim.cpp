#include "drivers/devices/displacement_sensor_sim.h"

#include <algorithm>
#include <cmath>

namespace lcnc::drivers {

Result<std::unique_ptr<DisplacementSensorSim>> DisplacementSensorSim::create(
    DeviceMap map, SlaveConfig config, DisplacementSensorParams params) {
  if (Status s = require(map, "displacement_sensor",
                         {"in_range", "averaging", "distance_mm", "sample_counter", "intensity_pct"});
      !s)
    return s.error();
  return std::unique_ptr<DisplacementSensorSim>(
      new DisplacementSensorSim(std::move(map), std::move(config), params));
}

DisplacementSensorSim::DisplacementSensorSim(DeviceMap map, SlaveConfig config,
                                             DisplacementSensorParams params)
    : VirtualDevice(std::move(map), std::move(config)), p_(params), noise_(p_.seed) {
  // Start at the middle of the range above the surface.
  z_mm_ = p_.surface.z_at(x_mm_, y_mm_) + 0.5 * (p_.range_min_mm + p_.range_max_mm);
}

DisplacementSensorSim::~DisplacementSensorSim() { stop(); }

void DisplacementSensorSim::set_position(double x_mm, double y_mm, double z_mm) {
  std::lock_guard lock(pos_mutex_);
  x_mm_ = x_mm;
  y_mm_ = y_mm;
  z_mm_ = z_mm;
}

void DisplacementSensorSim::tick(double, RegisterBank& b) {
  double x, y, z;
  {
    std::lock_guard lock(pos_mutex_);
    x = x_mm_;
    y = y_mm_;
    z = z_mm_;
  }
  const double averaging = std::max(1.0, b.value(b.def("averaging")));
  const double d = z - p_.surface.z_at(x, y) + noise_(p_.noise_mm / std::sqrt(averaging));
  const bool in_range = d >= p_.range_min_mm && d <= p_.range_max_mm;
  const double mid = 0.5 * (p_.range_min_mm + p_.range_max_mm);
  const double half = 0.5 * (p_.range_max_mm - p_.range_min_mm);
  const double intensity = in_range ? 100.0 - 80.0 * std::abs(d - mid) / half : 0.0;
  b.set_clamped(b.def("distance_mm"), in_range ? d : 0.0);
  b.set_clamped(b.def("in_range"), in_range ? 1 : 0);
  b.set_clamped(b.def("intensity_pct"), intensity);
  b.set_clamped(b.def("sample_counter"), ++samples_);
}

}  // namespace lcnc::drivers
