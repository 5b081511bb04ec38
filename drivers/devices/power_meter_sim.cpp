#include "drivers/devices/power_meter_sim.h"

#include <algorithm>

namespace lcnc::drivers {

Result<std::unique_ptr<PowerMeterSim>> PowerMeterSim::create(DeviceMap map, SlaveConfig config,
                                                             PowerMeterParams params) {
  if (Status s =
          require(map, "power_meter",
                  {"zero", "over_range", "wavelength_nm", "power_w", "full_scale_w", "sample_counter"});
      !s)
    return s.error();
  return std::unique_ptr<PowerMeterSim>(
      new PowerMeterSim(std::move(map), std::move(config), std::move(params)));
}

PowerMeterSim::PowerMeterSim(DeviceMap map, SlaveConfig config, PowerMeterParams params)
    : VirtualDevice(std::move(map), std::move(config)), p_(std::move(params)), noise_(p_.seed) {
  slave().with_bank([&](RegisterBank& b) {
    b.set_clamped(b.def("full_scale_w"), p_.full_scale_w);
    b.set_clamped(b.def("wavelength_nm"), 1030);
  });
}

PowerMeterSim::~PowerMeterSim() { stop(); }

void PowerMeterSim::tick(double dt, RegisterBank& b) {
  const double true_w = p_.source ? std::max(0.0, p_.source()) : 0.0;
  filtered_w_ += (true_w + p_.dark_w - filtered_w_) * lag_fraction(dt, p_.tau_s);
  if (b.value(b.def("zero")) != 0) {
    zero_offset_w_ = filtered_w_;
    b.set_clamped(b.def("zero"), 0);
  }
  const double reading = std::max(0.0, filtered_w_ - zero_offset_w_ + noise_(p_.noise_w));
  b.set_clamped(b.def("power_w"), reading);
  b.set_clamped(b.def("over_range"), reading > p_.full_scale_w ? 1 : 0);
  b.set_clamped(b.def("sample_counter"), ++samples_);
}

}  // namespace lcnc::drivers
