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
  const auto map = [](const char* name) { return drivers::shipped_device(name); };
  for (const char* name : {"laser_source", "power_meter", "scan_head", "displacement_sensor", "probe_3d"})
    if (Result<drivers::DeviceMap> m = map(name); !m) return m.error();
  auto laser = drivers::LaserSourceSim::create(*map("laser_source"), {});
  if (!laser) return laser.error();
  p->laser_ = std::move(laser).value();
  drivers::PowerMeterParams mp;
  mp.source = [l = p->laser_.get()] { return l->output_power_w(); };
  auto meter = drivers::PowerMeterSim::create(*map("power_meter"), {}, mp);
  if (!meter) return meter.error();
  p->meter_ = std::move(meter).value();
  auto head = drivers::ScanHeadSim::create(*map("scan_head"), {});
  if (!head) return head.error();
  p->head_ = std::move(head).value();
  drivers::DisplacementSensorParams sp;
  sp.surface = surface;
  auto sensor = drivers::DisplacementSensorSim::create(*map("displacement_sensor"), {}, sp);
  if (!sensor) return sensor.error();
  p->sensor_ = std::move(sensor).value();
  drivers::Probe3dParams pp;
  pp.surface = surface;
  pp.block = block;
  auto probe = drivers::Probe3dSim::create(*map("probe_3d"), {}, pp);
  if (!probe) return probe.error();
  p->probe_ = std::move(probe).value();
  for (drivers::VirtualDevice* d : std::initializer_list<drivers::VirtualDevice*>{
           p->laser_.get(), p->meter_.get(), p->head_.get(), p->sensor_.get(), p->probe_.get()})
    if (Status s = d->start(); !s) return s.error();
  p->follower_ = std::thread([raw = p.get(), shm_name] { raw->follow(shm_name); });
  return p;
}

SimPeripherals::~SimPeripherals() {
  running_ = false;
  if (follower_.joinable()) follower_.join();
  for (drivers::VirtualDevice* d : std::initializer_list<drivers::VirtualDevice*>{
           probe_.get(), sensor_.get(), head_.get(), meter_.get(), laser_.get()})
    if (d != nullptr) d->stop();
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
