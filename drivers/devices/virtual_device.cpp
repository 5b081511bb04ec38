#include "drivers/devices/virtual_device.h"

namespace lcnc::drivers {

VirtualDevice::VirtualDevice(DeviceMap map, SlaveConfig config) {
  if (config.tick_period.count() <= 0) config.tick_period = kDeviceTick;
  slave_ = std::make_unique<ModbusSlave>(std::move(map), std::move(config));
  // The hooks run on the slave's thread, which starts only in start(): by
  // then the derived object is complete.
  slave_->set_tick_hook([this](double dt, RegisterBank& b) { tick(dt, b); });
  slave_->set_write_hook(
      [this](std::span<const RegisterWrite> w, RegisterBank& b) { return on_write(w, b); });
}

VirtualDevice::~VirtualDevice() = default;

Status VirtualDevice::start() { return slave_->start(); }

void VirtualDevice::stop() noexcept { slave_->stop(); }

ModbusException VirtualDevice::on_write(std::span<const RegisterWrite>, RegisterBank&) {
  return ModbusException::None;
}

Status VirtualDevice::require(const DeviceMap& map, std::string_view device,
                              std::initializer_list<std::string_view> names) {
  if (map.name != device)
    return make_error(
        ErrorCode::RegisterMapInvalid,
        "the " + std::string(device) + " simulator was given the map of device '" + map.name + "'");
  for (std::string_view n : names)
    if (auto r = map.lookup(n); !r)
      return make_error(ErrorCode::RegisterMapInvalid, "the " + std::string(device) +
                                                           " simulator needs register '" + std::string(n) +
                                                           "': " + r.error().message);
  return {};
}

}  // namespace lcnc::drivers
