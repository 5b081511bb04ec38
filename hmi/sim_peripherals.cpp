#include "hmi/sim_peripherals.h"

#include <chrono>

#include "drivers/modbus/register_map.h"
#include "hmi/machine_link.h"

namespace lcnc::hmi {

Result<std::unique_ptr<SimPeripherals>> SimPeripherals::start(const std::string& shm_name) {
  std::unique_ptr<SimPeripherals> p(new SimPeripherals());
  drivers::SurfaceModel surface;
  Result<drivers::DeviceMap> sensor_map = drivers::shipped_device("displacement_sensor");
  Result<drivers::DeviceMap> probe_map = drivers::shipped_device("probe_3d");
  if (!sensor_map) return sensor_map.error();
  if (!probe_map) return probe_map.error();
  drivers::DisplacementSensorParams sp;
  sp.surface = surface;
  auto sensor = drivers::DisplacementSensorSim::create(*sensor_map, {}, sp);
  if (!sensor) return sensor.error();
  p->sensor_ = std::move(sensor).value();
  drivers::Probe3dParams pp;
  pp.surface = surface;
  auto probe = drivers::Probe3dSim::create(*probe_map, {}, pp);
  if (!probe) return probe.error();
  p->probe_ = std::move(probe).value();
  if (Status s = p->sensor_->start(); !s) return s.error();
  if (Status s = p->probe_->start(); !s) return s.error();
  p->follower_ = std::thread([raw = p.get(), shm_name] { raw->follow(shm_name); });
  return p;
}

SimPeripherals::~SimPeripherals() {
  running_ = false;
  if (follower_.joinable()) follower_.join();
  if (probe_) probe_->stop();
  if (sensor_) sensor_->stop();
}

void SimPeripherals::follow(const std::string& shm_name) noexcept {
  MachineLink link(shm_name);
  std::array<double, 3> last{1e300, 1e300, 1e300};
  while (running_.load()) {
    if (link.poll()) {
      if (const std::optional<shm::Status> st = link.status()) {
        const std::array<double, 3> at{st->pos[0], st->pos[1], st->pos[2]};
        if (at != last) {
          sensor_->set_position(at[0], at[1], at[2]);
          probe_->set_position(at[0], at[1], at[2]);
          last = at;
          follows_.fetch_add(1);
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace lcnc::hmi
