// The slave's thread: its sockets, clients and ticks. Each request is taken
// by SlaveRequestHandler (slave_request.h: the check before anything changes).
#include "drivers/modbus/modbus_slave.h"

#include <arpa/inet.h>
#include <modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

namespace lcnc::drivers {

namespace {

constexpr int kByteTimeoutUs = 100'000;  // a started frame must complete within this
constexpr int kIdlePollMs = 200;         // poll period when no tick is due
}  // namespace

struct ModbusSlave::Impl {
  SlaveConfig cfg;
  SlaveRequestHandler handler;
  RegisterBank& bank;
  mutable std::mutex mutex;  // guards bank (slave thread ↔ owner threads)
  WriteHook write_hook;
  TickHook tick_hook;

  modbus_t* ctx = nullptr;
  int listen_fd = -1;
  int wake_fd = -1;
  std::vector<int> clients;
  std::uint16_t bound_port = 0;
  std::thread thread;
  std::atomic<bool> running{false};

  std::atomic<std::uint64_t> connections{0};

  Impl(DeviceMap map, SlaveConfig c) : cfg(std::move(c)), handler(std::move(map)), bank(handler.bank()) {}

  std::string who() const { return bank.map().name + " slave (" + cfg.endpoint.to_string() + ")"; }

  Status open();
  void close_all() noexcept;
  void run() noexcept;
  void serve(int fd) noexcept;
};

Status ModbusSlave::Impl::open() {
  const Endpoint& ep = cfg.endpoint;
  const int unit = cfg.unit_id >= 0 ? cfg.unit_id : bank.map().unit_id;
  if (ep.transport == Transport::Rtu) {
    ctx = modbus_new_rtu(ep.device.c_str(), ep.baud, ep.parity, 8, 1);
    if (ctx == nullptr)
      return make_error(ErrorCode::PeripheralSetup,
                        who() + ": bad RTU settings: " + modbus_strerror(errno));
    modbus_set_slave(ctx, unit);
    if (modbus_connect(ctx) != 0) {
      const std::string why = modbus_strerror(errno);
      modbus_free(ctx);
      ctx = nullptr;
      return make_error(ErrorCode::PeripheralSetup, who() + ": cannot open " + ep.device + ": " + why);
    }
  } else {
    ctx = modbus_new_tcp(ep.host.c_str(), ep.port);  // framing only: we own the sockets
    if (ctx == nullptr)
      return make_error(ErrorCode::PeripheralSetup, who() + ": " + modbus_strerror(errno));
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(ep.port);
    if (inet_pton(AF_INET, ep.host.c_str(), &addr.sin_addr) != 1) {
      close_all();
      return make_error(ErrorCode::PeripheralSetup,
                        who() + ": host '" + ep.host + "' is not an IPv4 address");
    }
    listen_fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const int one = 1;
    ::setsockopt(listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (listen_fd < 0 || ::bind(listen_fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
        ::listen(listen_fd, cfg.max_clients) != 0) {
      const std::string why = std::strerror(errno);
      close_all();
      return make_error(ErrorCode::PeripheralSetup, who() + ": cannot listen: " + why);
    }
    socklen_t len = sizeof addr;
    ::getsockname(listen_fd, reinterpret_cast<sockaddr*>(&addr), &len);
    bound_port = ntohs(addr.sin_port);
    cfg.endpoint.port = bound_port;
  }
  modbus_set_error_recovery(ctx, MODBUS_ERROR_RECOVERY_PROTOCOL);  // flush after a bad frame
  modbus_set_byte_timeout(ctx, 0, kByteTimeoutUs);
  wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  return {};
}

void ModbusSlave::Impl::close_all() noexcept {
  for (int fd : clients) ::close(fd);
  clients.clear();
  if (listen_fd >= 0) ::close(listen_fd);
  listen_fd = -1;
  if (ctx != nullptr) {
    if (cfg.endpoint.transport == Transport::Rtu) modbus_close(ctx);
    modbus_free(ctx);
    ctx = nullptr;
  }
  if (wake_fd >= 0) ::close(wake_fd);
  wake_fd = -1;
}

void ModbusSlave::Impl::serve(int fd) noexcept {
  if (cfg.endpoint.transport == Transport::Tcp) modbus_set_socket(ctx, fd);
  const Received r = handler.receive_and_answer(ctx, write_hook, &mutex);  // counts itself
  if (r.kind == Received::Kind::Broken && cfg.endpoint.transport == Transport::Tcp) {
    ::close(fd);  // the peer closed or broke the framing
    std::erase(clients, fd);
  }
}

void ModbusSlave::Impl::run() noexcept {
  using clock = std::chrono::steady_clock;
  auto last_tick = clock::now();
  const bool ticking = tick_hook && cfg.tick_period.count() > 0;
  std::vector<pollfd> fds;
  while (running.load(std::memory_order_acquire)) {
    fds.clear();
    fds.push_back({wake_fd, POLLIN, 0});
    if (cfg.endpoint.transport == Transport::Rtu) {
      fds.push_back({modbus_get_socket(ctx), POLLIN, 0});
    } else {
      fds.push_back({listen_fd, POLLIN, 0});
      for (int c : clients) fds.push_back({c, POLLIN, 0});
    }
    int timeout_ms = kIdlePollMs;
    if (ticking) {
      const auto due = last_tick + cfg.tick_period - clock::now();
      timeout_ms = static_cast<int>(std::max<long long>(
          0, std::chrono::duration_cast<std::chrono::milliseconds>(due).count()));
    }
    const int rc = ::poll(fds.data(), fds.size(), timeout_ms);
    if (rc < 0 && errno != EINTR) break;
    if (fds[0].revents & POLLIN) break;  // stop()
    if (cfg.endpoint.transport == Transport::Rtu) {
      if (fds[1].revents & POLLIN) {
        serve(fds[1].fd);
      } else if (fds[1].revents & (POLLHUP | POLLERR)) {
        // The far end of the line is gone (a pty whose other side closed):
        // poll would report it at once forever, so wait (stop() still wakes).
        pollfd w{wake_fd, POLLIN, 0};
        ::poll(&w, 1, kIdlePollMs);
      }
    } else {
      if (fds[1].revents & POLLIN) {
        const int c = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
        if (c >= 0) {
          if (static_cast<int>(clients.size()) >= cfg.max_clients) {
            ::close(c);  // full: the master sees the link drop and retries later
          } else {
            clients.push_back(c);
            connections.fetch_add(1, std::memory_order_relaxed);
          }
        }
      }
      for (std::size_t i = 2; i < fds.size(); ++i)
        if (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) serve(fds[i].fd);
    }
    if (ticking) {
      const auto now = clock::now();
      if (now - last_tick >= cfg.tick_period) {
        const double dt = std::chrono::duration<double>(now - last_tick).count();
        last_tick = now;
        std::lock_guard lock(mutex);
        tick_hook(dt, bank);
      }
    }
  }
}

ModbusSlave::ModbusSlave(DeviceMap map, SlaveConfig config)
    : impl_(std::make_unique<Impl>(std::move(map), std::move(config))) {}

ModbusSlave::~ModbusSlave() { stop(); }

void ModbusSlave::set_write_hook(WriteHook hook) { impl_->write_hook = std::move(hook); }
void ModbusSlave::set_tick_hook(TickHook hook) { impl_->tick_hook = std::move(hook); }

Status ModbusSlave::start() {
  if (impl_->running.load()) return {};
  if (Status s = impl_->open(); !s) return s;
  impl_->running.store(true, std::memory_order_release);
  impl_->thread = std::thread([this] { impl_->run(); });
  return {};
}

void ModbusSlave::stop() noexcept {
  if (!impl_->running.exchange(false, std::memory_order_acq_rel)) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(impl_->wake_fd, &one, sizeof one);
  if (impl_->thread.joinable()) impl_->thread.join();
  impl_->close_all();
}

bool ModbusSlave::running() const noexcept { return impl_->running.load(); }
Endpoint ModbusSlave::endpoint() const { return impl_->cfg.endpoint; }
std::uint16_t ModbusSlave::port() const noexcept { return impl_->bound_port; }
const DeviceMap& ModbusSlave::map() const noexcept { return impl_->bank.map(); }

Result<double> ModbusSlave::get(std::string_view name) const {
  std::lock_guard lock(impl_->mutex);
  return impl_->bank.get(name);
}

Status ModbusSlave::set(std::string_view name, double value) {
  std::lock_guard lock(impl_->mutex);
  return impl_->bank.set(name, value);
}

void ModbusSlave::with_bank(const std::function<void(RegisterBank&)>& fn) {
  std::lock_guard lock(impl_->mutex);
  fn(impl_->bank);
}

bool ModbusSlave::try_with_bank(const std::function<void(RegisterBank&)>& fn) {
  std::unique_lock lock(impl_->mutex, std::try_to_lock);
  if (!lock.owns_lock()) return false;
  fn(impl_->bank);
  return true;
}

SlaveCounters ModbusSlave::counters() const noexcept {
  const SlaveRequestHandler::Counts c = impl_->handler.counts();
  return {c.requests, c.exceptions, c.refused, c.crc_errors, impl_->connections.load()};
}

}  // namespace lcnc::drivers
