// Simulated thermal power meter (register map device "power_meter") in the
// beam of a laser source. A thermopile head reads with a lag and noise:
//   F += (P_true + P_dark − F)·(1 − e^(−dt/τ))          (head response)
//   reading = max(0, F − zero_offset + N(0, σ))
// `zero` (a command coil) takes the current F as the zero offset, as a
// meter's zero button does with the beam blocked. over_range when the
// reading exceeds the head's full scale; sample_counter counts readings.
#pragma once

#include <functional>
#include <memory>

#include "drivers/devices/virtual_device.h"

namespace lcnc::drivers {

struct PowerMeterParams {
  double tau_s = 0.3;     // thermopile response time constant
  double noise_w = 0.02;  // σ of the reading noise
  double dark_w = 0.05;   // thermal offset before zeroing
  double full_scale_w = 100.0;
  std::uint64_t seed = 1;
  // The true optical power on the head (W), e.g. a LaserSourceSim's output;
  // called on the meter's thread. Empty: no beam.
  std::function<double()> source;
};

class PowerMeterSim final : public VirtualDevice {
 public:
  [[nodiscard]] static Result<std::unique_ptr<PowerMeterSim>> create(DeviceMap map, SlaveConfig config = {},
                                                                     PowerMeterParams params = {});
  ~PowerMeterSim() override;

 private:
  PowerMeterSim(DeviceMap map, SlaveConfig config, PowerMeterParams params);
  void tick(double dt_s, RegisterBank& bank) override;

  PowerMeterParams p_;
  Noise noise_;
  double filtered_w_ = 0.0;
  double zero_offset_w_ = 0.0;
  std::uint16_t samples_ = 0;
};

}  // namespace lcnc::drivers
