// The HMI's peripherals when no real ones are given (the default): the
// register map's five virtual devices (drivers/devices/, simulators named as
// such) started in-process as real Modbus TCP slaves on loopback, the HMI
// talking to them over the wire as to the hardware. The displacement sensor
// and the 3D probe ride on the Z carriage, so their position is the
// machine's: a thread follows the daemon's DRO over the shared memory (its
// own MachineLink) and moves them with it, as the carriage would.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "common/result.h"
#include "drivers/devices/displacement_sensor_sim.h"
#include "drivers/devices/laser_source_sim.h"
#include "drivers/devices/power_meter_sim.h"
#include "drivers/devices/probe_3d_sim.h"
#include "drivers/devices/scan_head_sim.h"

namespace lcnc::hmi {

// The simulated workpiece the probe finds: a 200 × 100 × 40 mm block
// clamped with its datum corner near X 400 Y 150 Z 60, turned 1.5° about Z
// and 0.3° about X — what the 3D measurement is to find out.
[[nodiscard]] drivers::WorkpieceBlock default_sim_block();

class SimPeripherals {
 public:
  // Starts the five devices; the sensor and the probe follow the machine on
  // `shm_name`; the power meter sits in the laser's beam.
  [[nodiscard]] static Result<std::unique_ptr<SimPeripherals>> start(
      const std::string& shm_name, const drivers::WorkpieceBlock& block = default_sim_block());
  ~SimPeripherals();
  SimPeripherals(const SimPeripherals&) = delete;
  SimPeripherals& operator=(const SimPeripherals&) = delete;

  [[nodiscard]] drivers::Endpoint sensor_endpoint() const { return sensor_->endpoint(); }
  [[nodiscard]] drivers::Endpoint laser_endpoint() const { return laser_->endpoint(); }
  [[nodiscard]] drivers::Endpoint meter_endpoint() const { return meter_->endpoint(); }
  [[nodiscard]] drivers::Endpoint head_endpoint() const { return head_->endpoint(); }
  [[nodiscard]] drivers::Endpoint probe_endpoint() const { return probe_->endpoint(); }
  [[nodiscard]] const std::string& probe_serial_path() const { return probe_->serial_path(); }
  [[nodiscard]] const drivers::SurfaceModel& surface() const noexcept { return sensor_->surface(); }
  [[nodiscard]] const drivers::WorkpieceBlock& block() const noexcept { return block_; }
  // Times the carriage-mounted devices were moved to a new DRO reading.
  [[nodiscard]] std::uint64_t follows() const noexcept { return follows_.load(); }

 private:
  SimPeripherals() = default;
  void follow(const std::string& shm_name) noexcept;

  std::unique_ptr<drivers::LaserSourceSim> laser_;
  std::unique_ptr<drivers::PowerMeterSim> meter_;
  std::unique_ptr<drivers::ScanHeadSim> head_;
  std::unique_ptr<drivers::DisplacementSensorSim> sensor_;
  std::unique_ptr<drivers::Probe3dSim> probe_;
  drivers::WorkpieceBlock block_;
  std::atomic<bool> running_{true};
  std::atomic<std::uint64_t> follows_{0};
  std::thread follower_;
};

}  // namespace lcnc::hmi
