#include "drivers/devices/probe_3d_sim.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <variant>

#include "kinematics/five_axis.h"

namespace lcnc::drivers {

Result<std::unique_ptr<Probe3dSim>> Probe3dSim::create(DeviceMap map, SlaveConfig config,
                                                       Probe3dParams params) {
  if (Status s = require(map, "probe_3d",
                         {"trigger", "busy", "valid", "measurement_id", "x_mm", "y_mm", "z_mm", "status"});
      !s)
    return s.error();
  return std::unique_ptr<Probe3dSim>(new Probe3dSim(std::move(map), std::move(config), std::move(params)));
}

Probe3dSim::Probe3dSim(DeviceMap map, SlaveConfig config, Probe3dParams params)
    : VirtualDevice(std::move(map), std::move(config)), p_(std::move(params)), noise_(p_.seed) {
  z_mm_ = p_.surface.z_at(x_mm_, y_mm_) + 0.5 * p_.reach_mm;  // just above the surface
}

Probe3dSim::~Probe3dSim() { stop(); }

void Probe3dSim::set_position(double x_mm, double y_mm, double z_mm) { set_pose(x_mm, y_mm, z_mm, 0.0, 0.0); }

void Probe3dSim::set_pose(double x_mm, double y_mm, double z_mm, double a_deg, double c_deg) {
  std::lock_guard lock(mutex_);
  x_mm_ = x_mm;
  y_mm_ = y_mm;
  z_mm_ = z_mm;
  a_deg_ = a_deg;
  c_deg_ = c_deg;
}

namespace {

// Where the ray o + t·d (t ≥ 0) enters the box [0, s.x]×[0, s.y]×[−s.z, 0]
// (slabs); empty when it misses or starts inside.
std::optional<double> enter_box(const Vec3& o, const Vec3& d, const Vec3& s) {
  double t0 = 0.0, t1 = 1e300;
  const Vec3 lo(0.0, 0.0, -s.z()), hi(s.x(), s.y(), 0.0);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (o[i] < lo[i] || o[i] > hi[i]) return std::nullopt;
      continue;
    }
    double a = (lo[i] - o[i]) / d[i], b = (hi[i] - o[i]) / d[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return std::nullopt;
  }
  if (t0 <= 0.0) return std::nullopt;  // the tip is inside the block
  return t0;
}

}  // namespace

std::optional<probe::PointReply> Probe3dSim::measure(std::uint16_t id) {
  std::lock_guard lock(mutex_);
  const Vec3 tip(x_mm_, y_mm_, z_mm_);
  const Vec3 ray = -tool_axis(a_deg_, c_deg_);
  if (p_.block) {
    const Eigen::Isometry3d to_work = p_.block->work_to_machine.inverse();
    const std::optional<double> t = enter_box(to_work * tip, to_work.linear() * ray, p_.block->size_mm);
    if (!t || *t > p_.reach_mm) return std::nullopt;
    const Vec3 hit = tip + ray * (*t + noise_(p_.noise_mm));
    return probe::PointReply{id, hit.x(), hit.y(), hit.z()};
  }
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
    return probe::encode(
        probe::ErrorReply{0, probe::ProbeError::BadRequest, checksum ? "bad checksum" : "malformed request"});
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

void Probe3dSim::serial_loop() {
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
