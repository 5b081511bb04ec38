#include "drivers/devices/probe_3d_sim.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <variant>

namespace lcnc::drivers {

Result<std::unique_ptr<Probe3dSim>> Probe3dSim::create(DeviceMap map, SlaveConfig config,
                                                       Probe3dParams params) {
  if (Status s = require(map, "probe_3d",
                         {"trigger", "busy", "valid", "measurement_id", "x_mm", "y_mm", "z_mm",
                          "status"});
      !s)
    return s.error();
  return std::unique_ptr<Probe3dSim>(new Probe3dSim(std::move(map), std::move(config), std::move(params)));
}

Probe3dSim::Probe3dSim(DeviceMap map, SlaveConfig config, Probe3dParams params)
    : VirtualDevice(std::move(map), std::move(config)), p_(std::move(params)), noise_(p_.seed) {
  z_mm_ = p_.surface.z_at(x_mm_, y_mm_) + 0.5 * p_.reach_mm;  // just above the surface
}

Probe3dSim::~Probe3dSim() { stop(); }

void Probe3dSim::set_position(double x_mm, double y_mm, double z_mm) {
  std::lock_guard lock(mutex_);
  x_mm_ = x_mm;
  y_mm_ = y_mm;
  z_mm_ = z_mm;
}

std::optional<probe::PointReply> Probe3dSim::measure(std::uint16_t id) {
  std::lock_guard lock(mutex_);
  const double surface_z = p_.surface.z_at(x_mm_, y_mm_);
  const double below = z_mm_ - surface_z;
  if (below < 0.0 || below > p_.reach_mm) return std::nullopt;
  return probe::PointReply{id, x_mm_, y_mm_, surface_z + noise_(p_.noise_mm)};
}

void Probe3dSim::tick(double dt, RegisterBank& b) {
  if (busy_s_ < 0.0 && b.value(b.def("trigger")) != 0) {
    busy_s_ = std::chrono::duration<double>(p_.latency).count();
    b.set_clamped(b.def("busy"), 1);
    b.set_clamped(b.def("status"), 2);
    return;
  }
  if (busy_s_ < 0.0) return;
  busy_s_ -= dt;
  if (busy_s_ > 0.0) return;
  busy_s_ = -1.0;
  ++measurement_id_;
  const auto point = measure(measurement_id_);
  if (point) {
    b.set_clamped(b.def("x_mm"), point->x_mm);
    b.set_clamped(b.def("y_mm"), point->y_mm);
    b.set_clamped(b.def("z_mm"), point->z_mm);
  }
  b.set_clamped(b.def("valid"), point ? 1 : 0);
  b.set_clamped(b.def("status"), point ? 0 : 1);
  b.set_clamped(b.def("measurement_id"), measurement_id_);
  b.set_clamped(b.def("busy"), 0);
  b.set_clamped(b.def("trigger"), 0);
}

std::string Probe3dSim::answer(const std::string& line) {
  auto msg = probe::decode(line, pty_.path);
  if (!msg) {
    // Tell the host at once rather than let it time out; keep the text short
    // enough for one sentence.
    const bool checksum = msg.error().code == ErrorCode::SerialChecksum;
    return probe::encode(probe::ErrorReply{0, probe::ProbeError::BadRequest,
                                           checksum ? "bad checksum" : "malformed request"});
  }
  if (const auto* m = std::get_if<probe::MeasureRequest>(&msg.value())) {
    std::this_thread::sleep_for(p_.latency);  // the probe's own measuring time
    if (auto point = measure(m->id)) return probe::encode(*point);
    return probe::encode(probe::ErrorReply{m->id, probe::ProbeError::NoSurface, "no surface in range"});
  }
  if (std::holds_alternative<probe::PingRequest>(msg.value()))
    return probe::encode(probe::PongReply{p_.model, p_.firmware});
  return probe::encode(probe::ErrorReply{0, probe::ProbeError::BadRequest, "not a request"});
}

void Probe3dSim::serial_loop() noexcept {
  std::string pending;
  while (serial_running_.load()) {
    pollfd fds[2] = {{pty_.master_fd, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
    if (::poll(fds, 2, 200) < 0 && errno != EINTR) break;
    if (fds[1].revents & POLLIN) break;
    if (!(fds[0].revents & POLLIN)) continue;
    char buf[256];
    const ssize_t n = ::read(pty_.master_fd, buf, sizeof buf);
    if (n <= 0) continue;
    pending.append(buf, static_cast<std::size_t>(n));
    std::size_t nl;
    while ((nl = pending.find('\n')) != std::string::npos) {
      const std::string line = pending.substr(0, nl + 1);
      pending.erase(0, nl + 1);
      serial_requests_.fetch_add(1);
      std::string out = answer(line);
      if (corrupt_next_.exchange(false)) out[out.size() - 3] ^= 0x01;  // a checksum digit
      [[maybe_unused]] const ssize_t w = ::write(pty_.master_fd, out.data(), out.size());
    }
    if (pending.size() > 4 * probe::kMaxSentence) pending.clear();  // noise without line ends
  }
}

Status Probe3dSim::start() {
  if (serial_running_.load()) return {};
  auto pty = open_pty();
  if (!pty) return pty.error();
  pty_ = pty.value();
  wake_fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (Status s = VirtualDevice::start(); !s) {
    close_pty(pty_);
    ::close(wake_fd_);
    wake_fd_ = -1;
    return s;
  }
  serial_running_.store(true);
  serial_thread_ = std::thread([this] { serial_loop(); });
  return {};
}

void Probe3dSim::stop() noexcept {
  VirtualDevice::stop();
  if (!serial_running_.exchange(false)) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
  if (serial_thread_.joinable()) serial_thread_.join();
  ::close(wake_fd_);
  wake_fd_ = -1;
  close_pty(pty_);
}

}  // namespace lcnc::drivers
