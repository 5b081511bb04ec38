#include "hmi/sim_peripherals.h"

#include <chrono>
#include <cmath>

#include "drivers/modbus/register_map.h"
#include "hmi/machine_link.h"

namespace lcnc::hmi {

drivers::WorkpieceBlock default_sim_block() {
  drivers::WorkpieceBlock b;
  b.size_mm = Vec3(200.0, 100.0, 40.0);
  b.work_to_machine = Eigen::Translation3d(400.0, 150.0, 60.0) *
                      Eigen::AngleAxisd(1.5 * M_PI / 180.0, Vec3::UnitZ()) *
                      Eigen::AngleAxisd(0.3 * M_PI / 180.0, Vec3::UnitX());
  return b;
}

Result<std::unique_ptr<SimPeripherals>> SimPeripherals::start(const std::string& shm_name,
                                                              const drivers::WorkpieceBlock& block) {
  std::unique_ptr<SimPeripherals> p(new SimPeripherals());
  p->block_ = block;
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
  pp.block = block;
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
  std::array<double, 5> last{1e300, 1e300, 1e300, 1e300, 1e300};
  while (running_.load()) {
    if (link.poll()) {
      if (const std::optional<shm::Status> st = link.status()) {
        const std::array<double, 5> at{st->pos[0], st->pos[1], st->pos[2], st->pos[3], st->pos[5]};
        if (at != last) {
          sensor_->set_position(at[0], at[1], at[2]);
          probe_->set_pose(at[0], at[1], at[2], at[3], at[4]);
          last = at;
          follows_.fetch_add(1);
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace lcnc::hmi
