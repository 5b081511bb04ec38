#include "drivers/devices/scan_head_sim.h"

#include <algorithm>

namespace lcnc::drivers {

Result<std::unique_ptr<ScanHeadSim>> ScanHeadSim::create(DeviceMap map, SlaveConfig config,
                                                         ScanHeadParams params) {
  if (Status s = require(map, "scan_head",
                         {"run", "running", "fault", "start_radius_mm", "end_radius_mm", "radius_turns",
                          "scan_speed_mm_s", "wedge_speed_rpm", "beam_offset_mm", "process_id", "status",
                          "actual_wedge_rpm", "current_radius_mm", "turns_done"});
      !s)
    return s.error();
  return std::unique_ptr<ScanHeadSim>(new ScanHeadSim(std::move(map), std::move(config), params));
}

ScanHeadSim::ScanHeadSim(DeviceMap map, SlaveConfig config, ScanHeadParams params)
    : VirtualDevice(std::move(map), std::move(config)), p_(params) {}

ScanHeadSim::~ScanHeadSim() { stop(); }

ModbusException ScanHeadSim::on_write(std::span<const RegisterWrite> writes, RegisterBank& b) {
  for (const RegisterWrite& w : writes) {
    if (w.reg->table == Table::Holding && running_) return ModbusException::DeviceBusy;
    if (w.reg->name == "run" && w.value != 0 && b.value(b.def("wedge_speed_rpm")) <= 0)
      return ModbusException::IllegalDataValue;
  }
  return ModbusException::None;
}

void ScanHeadSim::tick(double dt, RegisterBank& b) {
  const bool run = b.value(b.def("run")) != 0;
  if (run && !running_) turns_ = 0.0;  // a new pattern
  running_ = run;
  const double target_rpm = running_ ? b.value(b.def("wedge_speed_rpm")) : 0.0;
  const double step = p_.accel_rpm_s * dt;
  rpm_ = std::clamp(target_rpm, rpm_ - step, rpm_ + step);
  const bool at_speed = running_ && rpm_ >= target_rpm;
  const double turns_total = b.value(b.def("radius_turns"));
  if (at_speed) turns_ += rpm_ / 60.0 * dt;
  if (running_ && turns_ >= turns_total) {  // pattern done: stop by itself
    turns_ = turns_total;
    running_ = false;
    b.set_clamped(b.def("run"), 0);
  }
  const double r0 = b.value(b.def("start_radius_mm"));
  const double r1 = b.value(b.def("end_radius_mm"));
  const bool circle = b.value(b.def("process_id")) == 1;
  const double radius = circle ? r0 : r0 + (r1 - r0) * std::min(1.0, turns_ / turns_total);
  const ScanHeadStatus status = !running_  ? ScanHeadStatus::Idle
                                : at_speed ? ScanHeadStatus::Scanning
                                           : ScanHeadStatus::SpinningUp;
  b.set_clamped(b.def("status"), static_cast<double>(status));
  b.set_clamped(b.def("running"), running_ ? 1 : 0);
  b.set_clamped(b.def("actual_wedge_rpm"), rpm_);
  b.set_clamped(b.def("current_radius_mm"), radius);
  b.set_clamped(b.def("turns_done"), std::floor(turns_));
}

}  // namespace lcnc::drivers
