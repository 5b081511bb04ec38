// Simulated 3D point probe (register map device "probe_3d"), reachable two
// ways, as such devices are:
//   * RS-232: the ASCII line protocol of drivers/serial/probe_protocol.h on
//     a pseudo-terminal; clients open serial_path() like a serial port;
//   * Modbus: write the `trigger` coil; busy = 1 while it measures, then
//     measurement_id += 1, x/y/z_mm, valid and status, trigger cleared.
// A measurement looks down −Z from the probe tip (set_position(), machine
// frame) and finds the surface model within `reach_mm`:
//   point = (x, y, surface.z(x, y) + N(0, σ))   after `latency`
// otherwise "no surface in range" ($ERR code 1 / status 1, valid = 0).
// A request with a bad checksum or syntax is answered $ERR,<id or 0>,3,….
// Fault injection: corrupt_next_answer() sends the next serial answer with
// a wrong checksum (the host must reject it and ask again).
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "drivers/devices/virtual_device.h"
#include "drivers/serial/probe_protocol.h"
#include "drivers/serial/serial_port.h"

namespace lcnc::drivers {

struct Probe3dParams {
  SurfaceModel surface;
  double reach_mm = 10.0;  // the tip finds the surface up to this far below it
  double noise_mm = 0.001;
  std::chrono::milliseconds latency{5};
  std::uint64_t seed = 3;
  std::string model = "LCNC-SIM-PROBE3D";
  std::string firmware = "1.0";
};

class Probe3dSim final : public VirtualDevice {
 public:
  [[nodiscard]] static Result<std::unique_ptr<Probe3dSim>> create(
      DeviceMap map, SlaveConfig config = {}, Probe3dParams params = {});
  ~Probe3dSim() override;

  // Starts the Modbus slave and the serial side (a new pty).
  [[nodiscard]] Status start() override;
  void stop() noexcept override;
  // The pty path a client opens as its serial port (after start()).
  [[nodiscard]] const std::string& serial_path() const noexcept { return pty_.path; }

  void set_position(double x_mm, double y_mm, double z_mm);
  void corrupt_next_answer() noexcept { corrupt_next_.store(true); }
  [[nodiscard]] const SurfaceModel& surface() const noexcept { return p_.surface; }
  [[nodiscard]] std::uint64_t serial_requests() const noexcept { return serial_requests_.load(); }

 private:
  Probe3dSim(DeviceMap map, SlaveConfig config, Probe3dParams params);
  void tick(double dt_s, RegisterBank& bank) override;
  // One measurement at the current position: the point, or empty.
  std::optional<probe::PointReply> measure(std::uint16_t id);
  void serial_loop() noexcept;
  std::string answer(const std::string& line);

  Probe3dParams p_;
  std::mutex mutex_;  // guards position and noise (serial thread ↔ Modbus thread ↔ owner)
  Noise noise_;
  double x_mm_ = 100.0, y_mm_ = 100.0, z_mm_ = 0.0;

  double busy_s_ = -1.0;  // Modbus side: time left of a measurement; < 0 idle
  std::uint16_t measurement_id_ = 0;

  Pty pty_;
  int wake_fd_ = -1;
  std::thread serial_thread_;
  std::atomic<bool> serial_running_{false};
  std::atomic<bool> corrupt_next_{false};
  std::atomic<std::uint64_t> serial_requests_{0};
};

}  // namespace lcnc::drivers
