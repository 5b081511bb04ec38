// The slave's thread: its sockets, clients and ticks. Each request is taken
// by SlaveRequestHandler (slave_request.h: the check before anything changes).
//
// TCP: every socket is non-blocking and the thread never waits on one
// client. Each poll round reads once from each readable connection (at
// most one frame's worth, kMaxTcpAdu) into its buffer, answers the whole
// frames there and keeps the rest; then closes connections whose deadline
// passed. An answer that cannot be sent at once (a client that never reads
// its answers has filled its socket) closes that connection instead of
// waiting for it.
#include "drivers/modbus/modbus_slave.h"

#include <arpa/inet.h>
#include <modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

namespace lcnc::drivers {

namespace {

constexpr int kIdlePollMs = 200;  // the longest poll wait (nothing due sooner)
using Clock = std::chrono::steady_clock;

// One TCP client: its socket and the bytes of a frame not yet whole.
struct Connection {
  int fd = -1;  // −1: closed this round, erased at its end
  std::array<std::uint8_t, kMaxTcpAdu> buf{};
  std::size_t len = 0;
  Clock::time_point last_byte;    // or the accept: idle and byte timeouts count from here
  Clock::time_point frame_start;  // when buf's first byte came (len > 0)
};
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
  std::vector<Connection> clients;
  std::uint8_t unit = 1;  // TCP: answered besides 0 and 255
  std::uint16_t bound_port = 0;
  std::thread thread;
  std::atomic<bool> running{false};

  std::atomic<std::uint64_t> connections{0}, idle_closed{0}, frame_timeouts{0}, evicted{0};

  Impl(DeviceMap map, SlaveConfig c) : cfg(std::move(c)), handler(std::move(map)), bank(handler.bank()) {}

  std::string who() const { return bank.map().name + " slave (" + cfg.endpoint.to_string() + ")"; }

  Status open();
  void close_all() noexcept;
  void run() noexcept;
  void serve_rtu() noexcept;
  void admit(int fd) noexcept;
  void read_from(Connection& c) noexcept;
  void expire(Clock::time_point now) noexcept;
  [[nodiscard]] Clock::time_point deadline(const Connection& c) const noexcept;
  static void close(Connection& c) noexcept;
};

Status ModbusSlave::Impl::open() {
  const Endpoint& ep = cfg.endpoint;
  const int unit = cfg.unit_id >= 0 ? cfg.unit_id : bank.map().unit_id;
  this->unit = static_cast<std::uint8_t>(unit);
  cfg.max_clients = std::max(cfg.max_clients, 1);
  if (ep.transport == Transport::Rtu) {
    ctx = modbus_new_rtu(ep.device.c_str(), ep.baud, ep.parity, 8, 1);
    if (ctx == nullptr)
      return make_error(ErrorCode::PeripheralSetup, who() + ": bad RTU settings: " + modbus_strerror(errno));
    modbus_set_slave(ctx, unit);
    if (modbus_connect(ctx) != 0) {
      const std::string why = modbus_strerror(errno);
      modbus_free(ctx);
      ctx = nullptr;
      return make_error(ErrorCode::PeripheralSetup, who() + ": cannot open " + ep.device + ": " + why);
    }
  } else {
    ctx = modbus_new_tcp(ep.host.c_str(), ep.port);  // framing only: we own the sockets
    if (ctx == nullptr) return make_error(ErrorCode::PeripheralSetup, who() + ": " + modbus_strerror(errno));
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(ep.port);
    if (inet_pton(AF_INET, ep.host.c_str(), &addr.sin_addr) != 1) {
      close_all();
      return make_error(ErrorCode::PeripheralSetup,
                        who() + ": host '" + ep.host + "' is not an IPv4 address");
    }
    listen_fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
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
  modbus_set_byte_timeout(
      ctx, 0, static_cast<std::uint32_t>(std::chrono::microseconds(kTcpByteTimeout).count()));  // RTU
  wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  return {};
}

void ModbusSlave::Impl::close_all() noexcept {
  for (Connection& c : clients) close(c);
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

void ModbusSlave::Impl::close(Connection& c) noexcept {
  if (c.fd >= 0) ::close(c.fd);
  c.fd = -1;
}

void ModbusSlave::Impl::serve_rtu() noexcept {
  (void)handler.receive_and_answer(ctx, write_hook, &mutex);  // counts itself
}

// At the limit the newcomer replaces the connection silent the longest: a
// client that just connected is about to ask, an idle one may never.
void ModbusSlave::Impl::admit(int fd) noexcept {
  const auto open = [](const Connection& c) { return c.fd >= 0; };
  if (std::count_if(clients.begin(), clients.end(), open) >= cfg.max_clients) {
    Connection* quietest = nullptr;
    for (Connection& c : clients)
      if (open(c) && (quietest == nullptr || c.last_byte < quietest->last_byte)) quietest = &c;
    close(*quietest);
    evicted.fetch_add(1, std::memory_order_relaxed);
  }
  Connection c;
  c.fd = fd;
  c.last_byte = Clock::now();
  clients.push_back(c);
  connections.fetch_add(1, std::memory_order_relaxed);
}

void ModbusSlave::Impl::read_from(Connection& c) noexcept {
  const ssize_t n = ::recv(c.fd, c.buf.data() + c.len, c.buf.size() - c.len, 0);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
  if (n <= 0) {  // the peer closed, or the connection broke
    close(c);
    return;
  }
  const auto now = Clock::now();
  if (c.len == 0) c.frame_start = now;
  c.len += static_cast<std::size_t>(n);
  c.last_byte = now;
  for (;;) {
    const TcpFrameCut cut = cut_tcp_frame(std::span<const std::uint8_t>(c.buf.data(), c.len));
    if (cut.kind == TcpFrameCut::Kind::NeedMore) return;
    if (cut.kind == TcpFrameCut::Kind::Unframeable) {
      handler.count_malformed();
      close(c);
      return;
    }
    if (cut.kind == TcpFrameCut::Kind::Foreign) {
      handler.count_malformed();
    } else {
      modbus_set_socket(ctx, c.fd);
      const Received r = handler.answer_tcp_frame(ctx, std::span<const std::uint8_t>(c.buf.data(), cut.size),
                                                  unit, write_hook, &mutex);
      modbus_set_socket(ctx, -1);
      if (r.kind == Received::Kind::Broken) {  // the answer could not go out
        close(c);
        return;
      }
    }
    std::memmove(c.buf.data(), c.buf.data() + cut.size, c.len - cut.size);
    c.len -= cut.size;
    c.frame_start = now;  // what is left came with this read
  }
}

Clock::time_point ModbusSlave::Impl::deadline(const Connection& c) const noexcept {
  if (c.len == 0) return c.last_byte + cfg.idle_timeout;
  return std::min(c.last_byte + cfg.byte_timeout, c.frame_start + cfg.frame_timeout);
}

void ModbusSlave::Impl::expire(Clock::time_point now) noexcept {
  for (Connection& c : clients) {
    if (c.fd < 0 || now < deadline(c)) continue;
    (c.len == 0 ? idle_closed : frame_timeouts).fetch_add(1, std::memory_order_relaxed);
    close(c);
  }
}

void ModbusSlave::Impl::run() noexcept {
  auto last_tick = Clock::now();
  const bool ticking = tick_hook && cfg.tick_period.count() > 0;
  const bool tcp = cfg.endpoint.transport == Transport::Tcp;
  std::vector<pollfd> fds;
  while (running.load(std::memory_order_acquire)) {
    fds.clear();
    fds.push_back({wake_fd, POLLIN, 0});
    auto wake_at = Clock::now() + std::chrono::milliseconds(kIdlePollMs);
    if (ticking) wake_at = std::min(wake_at, last_tick + cfg.tick_period);
    if (!tcp) {
      fds.push_back({modbus_get_socket(ctx), POLLIN, 0});
    } else {
      fds.push_back({listen_fd, POLLIN, 0});
      for (const Connection& c : clients) {
        fds.push_back({c.fd, POLLIN, 0});
        wake_at = std::min(wake_at, deadline(c));
      }
    }
    // Rounded up: waking a millisecond early would only poll again.
    const auto wait = std::chrono::ceil<std::chrono::milliseconds>(wake_at - Clock::now());
    const int rc = ::poll(fds.data(), fds.size(), static_cast<int>(std::max<long long>(0, wait.count())));
    if (rc < 0 && errno != EINTR) break;
    if (fds[0].revents & POLLIN) break;  // stop()
    if (!tcp) {
      if (fds[1].revents & POLLIN) {
        serve_rtu();
      } else if (fds[1].revents & (POLLHUP | POLLERR)) {
        // The far end of the line is gone (a pty whose other side closed):
        // poll would report it at once forever, so wait (stop() still wakes).
        pollfd w{wake_fd, POLLIN, 0};
        ::poll(&w, 1, kIdlePollMs);
      }
    } else {
      // fds[2 + i] is clients[i]: nothing is added or erased until the end.
      for (std::size_t i = 0; i < clients.size(); ++i)
        if (clients[i].fd >= 0 && (fds[2 + i].revents & (POLLIN | POLLHUP | POLLERR))) read_from(clients[i]);
      expire(Clock::now());
      if (fds[1].revents & POLLIN) {
        for (;;) {  // every client waiting, so none waits a round per peer
          const int c = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
          if (c < 0) break;
          admit(c);
        }
      }
      std::erase_if(clients, [](const Connection& c) { return c.fd < 0; });
    }
    if (ticking) {
      const auto now = Clock::now();
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
  return {c.requests,
          c.exceptions,
          c.refused,
          c.crc_errors,
          impl_->connections.load(),
          c.malformed,
          impl_->idle_closed.load(),
          impl_->frame_timeouts.load(),
          impl_->evicted.load()};
}

}  // namespace lcnc::drivers
