// Simulated four-beam wedge scanning head (register map device "scan_head";
// its holding registers are process fields 12–18 of docs/design.md §6).
//
// Two counter-rotating wedge pairs turn at the wedge speed; one wedge turn
// is one turn of the beam circle. Writing run = 1 spins the wedges up to
// wedge_speed_rpm at `accel_rpm_s` (status 1), then scans (status 2): over
// radius_turns turns the circle's radius goes from start_radius_mm to
// end_radius_mm (helix, free shape) or stays at start_radius_mm (circle),
//   r(n) = r_start + (r_end − r_start) · n / radius_turns,  n = turns done;
// then the head stops by itself (run cleared, status 0). Writing run = 0
// stops it at once. While it runs, pattern parameters are refused with
// exception 06 (server device busy); run = 1 with wedge_speed_rpm = 0 is
// refused with exception 03.
#pragma once

#include <memory>

#include "drivers/devices/virtual_device.h"

namespace lcnc::drivers {

struct ScanHeadParams {
  double accel_rpm_s = 60000.0;  // wedge spin-up / spin-down
};

enum class ScanHeadStatus : std::uint8_t { Idle = 0, SpinningUp = 1, Scanning = 2 };

class ScanHeadSim final : public VirtualDevice {
 public:
  [[nodiscard]] static Result<std::unique_ptr<ScanHeadSim>> create(DeviceMap map, SlaveConfig config = {},
                                                                   ScanHeadParams params = {});
  ~ScanHeadSim() override;

 private:
  ScanHeadSim(DeviceMap map, SlaveConfig config, ScanHeadParams params);
  void tick(double dt_s, RegisterBank& bank) override;
  ModbusException on_write(std::span<const RegisterWrite> writes, RegisterBank& bank) override;

  ScanHeadParams p_;
  double rpm_ = 0.0;
  double turns_ = 0.0;
  bool running_ = false;
};

}  // namespace lcnc::drivers
