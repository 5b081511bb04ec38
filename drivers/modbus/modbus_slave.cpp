// The slave's request check (check_request) is the part of seed 000 fig. 15
// that matters: every address of the request must hold a register of the
// map, writes must hit whole writable registers, and every value must be in
// range — all checked before libmodbus's modbus_reply() touches the tables,
// so a refused block leaves everything as it was.
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
constexpr std::uint16_t kMaxReadRegisters = 125;   // Modbus limits per request
constexpr std::uint16_t kMaxReadBits = 2000;
constexpr std::uint16_t kMaxWriteRegisters = 123;
constexpr std::uint16_t kMaxWriteBits = 1968;

std::uint16_t be16(const std::uint8_t* p) noexcept {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}

}  // namespace

struct ModbusSlave::Impl {
  SlaveConfig cfg;
  RegisterBank bank;
  mutable std::mutex mutex;  // guards bank (slave thread ↔ owner threads)
  WriteHook write_hook;
  TickHook tick_hook;

  modbus_t* ctx = nullptr;
  modbus_mapping_t mapping{};
  int listen_fd = -1;
  int wake_fd = -1;
  std::vector<int> clients;
  std::uint16_t bound_port = 0;
  std::thread thread;
  std::atomic<bool> running{false};

  std::atomic<std::uint64_t> requests{0}, exceptions{0}, refused{0}, crc_errors{0},
      connections{0};

  Impl(DeviceMap map, SlaveConfig c) : cfg(std::move(c)), bank(std::move(map)) {
    mapping.nb_bits = static_cast<int>(bank.bits(Table::Coil).size());
    mapping.tab_bits = bank.bits(Table::Coil).data();
    mapping.nb_input_bits = static_cast<int>(bank.bits(Table::Discrete).size());
    mapping.tab_input_bits = bank.bits(Table::Discrete).data();
    mapping.nb_registers = static_cast<int>(bank.words(Table::Holding).size());
    mapping.tab_registers = bank.words(Table::Holding).data();
    mapping.nb_input_registers = static_cast<int>(bank.words(Table::Input).size());
    mapping.tab_input_registers = bank.words(Table::Input).data();
  }

  std::string who() const { return bank.map().name + " slave (" + cfg.endpoint.to_string() + ")"; }

  Status open();
  void close_all() noexcept;
  void run() noexcept;
  void serve(int fd) noexcept;
  ModbusException check_request(const std::uint8_t* q, int len,
                                std::vector<RegisterWrite>& writes) const;
  void handle(const std::uint8_t* q, int len) noexcept;
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

// Checks a request against the map; fills `writes` for a valid write.
ModbusException ModbusSlave::Impl::check_request(const std::uint8_t* q, int len,
                                                 std::vector<RegisterWrite>& writes) const {
  const int o = modbus_get_header_length(ctx);
  if (len < o + 5) return ModbusException::IllegalDataValue;
  const std::uint8_t fc = q[o];
  const std::uint16_t addr = be16(q + o + 1);
  const std::uint16_t n = be16(q + o + 3);
  const DeviceMap& map = bank.map();

  // Every address in [addr, addr + count) must hold a register of table t.
  auto all_mapped = [&](Table t, std::uint32_t count) {
    for (std::uint32_t a = addr; a < addr + count; ++a)
      if (a > 0xFFFF || map.at(t, static_cast<std::uint16_t>(a)) == nullptr) return false;
    return true;
  };

  switch (fc) {
    case 1: case 2: case 3: case 4: {
      const Table t = fc == 1 ? Table::Coil
                      : fc == 2 ? Table::Discrete
                      : fc == 3 ? Table::Holding
                                : Table::Input;
      const std::uint16_t limit = is_bit_table(t) ? kMaxReadBits : kMaxReadRegisters;
      if (n < 1 || n > limit) return ModbusException::IllegalDataValue;
      return all_mapped(t, n) ? ModbusException::None : ModbusException::IllegalDataAddress;
    }
    case 5: {
      const RegisterDef* r = map.at(Table::Coil, addr);
      if (r == nullptr || !r->writable()) return ModbusException::IllegalDataAddress;
      if (n != 0xFF00 && n != 0x0000) return ModbusException::IllegalDataValue;
      writes.push_back({r, n == 0xFF00 ? 1.0 : 0.0});
      return ModbusException::None;
    }
    case 6: {
      const RegisterDef* r = map.at(Table::Holding, addr);
      if (r == nullptr || !r->writable() || r->words() != 1)
        return ModbusException::IllegalDataAddress;
      const double v = r->decode(std::span<const std::uint16_t>(&n, 1));
      if (!r->in_range(v)) return ModbusException::IllegalDataValue;
      writes.push_back({r, v});
      return ModbusException::None;
    }
    case 15: {
      if (len < o + 6) return ModbusException::IllegalDataValue;
      const std::uint8_t bytes = q[o + 5];
      if (n < 1 || n > kMaxWriteBits || bytes != (n + 7) / 8 || len < o + 6 + bytes)
        return ModbusException::IllegalDataValue;
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t a = addr + i;
        const RegisterDef* r = a > 0xFFFF ? nullptr : map.at(Table::Coil, static_cast<std::uint16_t>(a));
        if (r == nullptr || !r->writable()) return ModbusException::IllegalDataAddress;
        writes.push_back({r, ((q[o + 6 + i / 8] >> (i % 8)) & 1) ? 1.0 : 0.0});
      }
      return ModbusException::None;
    }
    case 16: {
      if (len < o + 6) return ModbusException::IllegalDataValue;
      const std::uint8_t bytes = q[o + 5];
      if (n < 1 || n > kMaxWriteRegisters || bytes != 2 * n || len < o + 6 + bytes)
        return ModbusException::IllegalDataValue;
      ModbusException verdict = ModbusException::None;
      for (std::uint32_t a = addr; a < addr + n;) {
        const RegisterDef* r = a > 0xFFFF ? nullptr : map.at(Table::Holding, static_cast<std::uint16_t>(a));
        // Whole registers only: a write must not start or end inside a u32/i32.
        if (r == nullptr || !r->writable() || r->address != a || a + r->words() > addr + n)
          return ModbusException::IllegalDataAddress;
        std::uint16_t raw[2];
        for (std::uint16_t k = 0; k < r->words(); ++k) raw[k] = be16(q + o + 6 + 2 * (a - addr + k));
        const double v = r->decode(std::span<const std::uint16_t>(raw, r->words()));
        // Addresses outrank values: keep scanning for a 02 after a bad value.
        if (!r->in_range(v)) verdict = ModbusException::IllegalDataValue;
        writes.push_back({r, v});
        a += r->words();
      }
      return verdict;
    }
    default:
      return ModbusException::IllegalFunction;
  }
}

void ModbusSlave::Impl::handle(const std::uint8_t* q, int len) noexcept {
  requests.fetch_add(1, std::memory_order_relaxed);
  std::vector<RegisterWrite> writes;
  std::lock_guard lock(mutex);
  ModbusException ex = check_request(q, len, writes);
  if (ex == ModbusException::None && !writes.empty() && write_hook)
    ex = write_hook(std::span<const RegisterWrite>(writes), bank);
  if (ex != ModbusException::None) {
    exceptions.fetch_add(1, std::memory_order_relaxed);
    const std::uint8_t fc = q[modbus_get_header_length(ctx)];
    if (fc == 5 || fc == 6 || fc == 15 || fc == 16) refused.fetch_add(1, std::memory_order_relaxed);
    modbus_reply_exception(ctx, q, static_cast<unsigned>(ex));
    return;
  }
  modbus_reply(ctx, q, len, &mapping);  // applies the (checked) write and answers
}

void ModbusSlave::Impl::serve(int fd) noexcept {
  std::uint8_t q[MODBUS_TCP_MAX_ADU_LENGTH];
  if (cfg.endpoint.transport == Transport::Tcp) modbus_set_socket(ctx, fd);
  const int rc = modbus_receive(ctx, q);
  if (rc > 0) {
    handle(q, rc);
    return;
  }
  if (rc == 0) return;  // RTU: a frame for another unit
  if (errno == EMBBADCRC) {
    crc_errors.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (cfg.endpoint.transport == Transport::Tcp) {  // peer closed or broke the framing
    ::close(fd);
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
  return {impl_->requests.load(), impl_->exceptions.load(), impl_->refused.load(),
          impl_->crc_errors.load(), impl_->connections.load()};
}

}  // namespace lcnc::drivers
