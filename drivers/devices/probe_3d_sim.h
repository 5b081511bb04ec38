// Simulated 3D point probe (register map device "probe_3d"), reachable two
// ways, as such devices are:
//   * RS-232: the ASCII line protocol of drivers/serial/probe_protocol.h on
//     a pseudo-terminal; clients open serial_path() like a serial port;
//   * Modbus: write the `trigger` coil; busy = 1 while it measures, then
//     measurement_id += 1, x/y/z_mm, valid and status, trigger cleared.
// The probe rides on the head: it measures from the machine point X Y Z
// along −k(A, C), the tool axis pointing down the beam (set_pose(); at A = 0
// straight down −Z). With a workpiece block (Probe3dParams::block) it finds
// the block's nearest face along that ray within `reach_mm` — so the side
// faces of a 3-2-1 set-up are probed with the head tilted to A = ±90°;
// without one, the surface model below the tip:
//   point = (x, y, surface.z(x, y)) + N(0, σ) along the ray   after `latency`
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

#include <Eigen/Geometry>

#include "drivers/devices/virtual_device.h"
#include "drivers/serial/probe_protocol.h"
#include "drivers/serial/serial_port.h"
#include "geom/pose.h"

namespace lcnc::drivers {

// A rectangular block on the table: x ∈ [0, size.x], y ∈ [0, size.y],
// z ∈ [−size.z, 0] in its own frame (the top face z = 0, the front y = 0, the
// left x = 0: the 3-2-1 datum faces), placed by `work_to_machine`.
struct WorkpieceBlock {
  Vec3 size_mm = Vec3(200.0, 100.0, 40.0);
  Eigen::Isometry3d work_to_machine = Eigen::Isometry3d::Identity();
};

struct Probe3dParams {
  SurfaceModel surface;
  std::optional<WorkpieceBlock> block;  // probed instead of the surface when given
  double reach_mm = 10.0;               // the tip finds the surface up to this far below it
  double noise_mm = 0.001;
  std::chrono::milliseconds latency{5};
  std::uint64_t seed = 3;
  std::string model = "LCNC-SIM-PROBE3D";
  std::string firmware = "1.0";
};

class Probe3dSim final : public VirtualDevice {
 public:
  [[nodiscard]] static Result<std::unique_ptr<Probe3dSim>> create(DeviceMap map, SlaveConfig config = {},
                                                                  Probe3dParams params = {});
  ~Probe3dSim() override;

  // Starts the Modbus slave and the serial side (a new pty).
  [[nodiscard]] Status start() override;
  void stop() noexcept override;
  // The pty path a client opens as its serial port (after start()).
  [[nodiscard]] const std::string& serial_path() const noexcept { return pty_.path; }

  void set_position(double x_mm, double y_mm, double z_mm);  // A = C = 0
  void set_pose(double x_mm, double y_mm, double z_mm, double a_deg, double c_deg);
  void corrupt_next_answer() noexcept { corrupt_next_.store(true); }
  [[nodiscard]] const SurfaceModel& surface() const noexcept { return p_.surface; }
  [[nodiscard]] std::uint64_t serial_requests() const noexcept { return serial_requests_.load(); }

 private:
  Probe3dSim(DeviceMap map, SlaveConfig config, Probe3dParams params);
  void tick(double dt_s, RegisterBank& bank) override;
  // One measurement at the current position: the point, or empty.
  std::optional<probe::PointReply> measure(std::uint16_t id);
  void serial_loop();
  std::string answer(const std::string& line);

  Probe3dParams p_;
  std::mutex mutex_;  // guards position and noise (serial thread ↔ Modbus thread ↔ owner)
  Noise noise_;
  double x_mm_ = 100.0, y_mm_ = 100.0, z_mm_ = 0.0, a_deg_ = 0.0, c_deg_ = 0.0;

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
