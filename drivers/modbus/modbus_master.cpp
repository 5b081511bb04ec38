#include "drivers/modbus/modbus_master.h"

#include <modbus.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

namespace lcnc::drivers {

namespace {

using Clock = std::chrono::steady_clock;

// What an attempt's errno means for the next step.
enum class Fault : std::uint8_t { Timeout, Corrupted, Protocol, Exception, Link };

Fault classify(int err) noexcept {
  if (err == ETIMEDOUT) return Fault::Timeout;
  if (err == EMBBADCRC) return Fault::Corrupted;
  if (err >= EMBXILFUN && err <= EMBXGTAR) return Fault::Exception;
  if (err == EMBBADDATA || err == EMBMDATA || err == EMBBADSLAVE || err == EMBBADEXC || err == EMBUNKEXC)
    return Fault::Protocol;
  return Fault::Link;
}

void set_timeout(modbus_t* ctx, std::chrono::milliseconds t,
                 int (*setter)(modbus_t*, std::uint32_t, std::uint32_t)) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t).count();
  setter(ctx, static_cast<std::uint32_t>(us / 1'000'000), static_cast<std::uint32_t>(us % 1'000'000));
}

std::string function_text(const RawRequest& r) {
  return "FC" + std::to_string(static_cast<int>(r.function)) + " @" + std::to_string(r.address);
}

}  // namespace

struct ModbusMaster::Impl {
  DeviceMap map;
  MasterConfig cfg;
  int unit = 1;

  struct Job {
    RawRequest request;
    RawCallback done;
  };
  std::mutex mutex;  // guards queue, stopping, last_error
  std::condition_variable cv;
  std::deque<Job> queue;
  bool stopping = false;
  std::string last_error;
  std::thread worker;
  bool started = false;

  // Worker-thread state.
  modbus_t* ctx = nullptr;
  bool link_up = false;
  bool ever_connected = false;
  bool lost = false;                 // the link was up once and then lost
  Clock::time_point next_connect{};  // no connect attempt before this
  std::string why_down;              // why the link is down, for messages
  int consecutive_failures = 0;

  std::atomic<bool> connected{false};  // mirror of link_up for other threads
  struct AtomicCounters {
    std::atomic<std::uint64_t> requests{0}, ok{0}, failed{0}, retries{0}, timeouts{0}, crc_errors{0},
        protocol_errors{0}, exceptions{0}, link_errors{0}, reconnects{0}, refused{0};
  } n;

  Impl(DeviceMap m, MasterConfig c) : map(std::move(m)), cfg(std::move(c)) {
    unit = cfg.unit_id >= 0 ? cfg.unit_id : map.unit_id;
  }
  ~Impl() { close_link(); }

  std::string who() const {
    return map.name + " (unit " + std::to_string(unit) + ", " + cfg.endpoint.to_string() + ")";
  }

  Diagnostic fail(ErrorCode code, const RawRequest& r, const std::string& why) {
    std::string msg = who() + ": " + (r.what.empty() ? function_text(r) : r.what) + ": " + why;
    {
      std::lock_guard lock(mutex);
      last_error = msg;
    }
    return make_error(code, std::move(msg));
  }

  void close_link() noexcept {
    if (ctx != nullptr) {
      modbus_close(ctx);
      modbus_free(ctx);
      ctx = nullptr;
    }
    link_up = false;
    connected.store(false, std::memory_order_relaxed);
  }

  // Opens the link; false (with `why`) when the device is not there.
  bool open_link(std::string& why) {
    const Endpoint& ep = cfg.endpoint;
    ctx = ep.transport == Transport::Rtu
              ? modbus_new_rtu(ep.device.c_str(), ep.baud, ep.parity, 8, 1)
              : modbus_new_tcp_pi(ep.host.c_str(), std::to_string(ep.port).c_str());
    if (ctx == nullptr) {
      why = std::string("bad settings: ") + modbus_strerror(errno);
      return false;
    }
    modbus_set_slave(ctx, unit);
    modbus_set_error_recovery(ctx, MODBUS_ERROR_RECOVERY_PROTOCOL);
    set_timeout(ctx, cfg.response_timeout, modbus_set_response_timeout);
    set_timeout(ctx, cfg.byte_timeout, modbus_set_byte_timeout);
    if (modbus_connect(ctx) != 0) {
      why = modbus_strerror(errno);
      modbus_free(ctx);
      ctx = nullptr;
      return false;
    }
    link_up = true;
    connected.store(true, std::memory_order_relaxed);
    if (lost) n.reconnects.fetch_add(1, std::memory_order_relaxed);
    lost = false;
    ever_connected = true;
    return true;
  }

  void lose_link() noexcept {
    close_link();
    lost = ever_connected;
    next_connect = Clock::now();  // the next attempt may reconnect at once
  }

  // One attempt on the wire: ≥ 0 on success, −1 with errno.
  int call(const RawRequest& r, RawReply& out) {
    std::uint8_t bits[MODBUS_MAX_READ_BITS];
    switch (r.function) {
      case Function::ReadCoils:
      case Function::ReadDiscreteInputs: {
        const int rc = r.function == Function::ReadCoils
                           ? modbus_read_bits(ctx, r.address, r.count, bits)
                           : modbus_read_input_bits(ctx, r.address, r.count, bits);
        if (rc >= 0) out.assign(bits, bits + r.count);
        return rc;
      }
      case Function::ReadHoldingRegisters:
      case Function::ReadInputRegisters: {
        out.assign(r.count, 0);
        return r.function == Function::ReadHoldingRegisters
                   ? modbus_read_registers(ctx, r.address, r.count, out.data())
                   : modbus_read_input_registers(ctx, r.address, r.count, out.data());
      }
      case Function::WriteSingleCoil:
        return modbus_write_bit(ctx, r.address, r.data.at(0) != 0 ? TRUE : FALSE);
      case Function::WriteSingleRegister: return modbus_write_register(ctx, r.address, r.data.at(0));
      case Function::WriteMultipleCoils: {
        std::vector<std::uint8_t> b(r.data.begin(), r.data.end());
        return modbus_write_bits(ctx, r.address, static_cast<int>(b.size()), b.data());
      }
      case Function::WriteMultipleRegisters:
        return modbus_write_registers(ctx, r.address, static_cast<int>(r.data.size()), r.data.data());
    }
    errno = EINVAL;
    return -1;
  }

  Result<RawReply> execute(const RawRequest& r) {
    const int attempts = 1 + std::max(0, cfg.retries);
    ErrorCode code = ErrorCode::PeripheralTimeout;
    std::string why;
    for (int i = 0; i < attempts; ++i) {
      if (i > 0) n.retries.fetch_add(1, std::memory_order_relaxed);
      if (!link_up) {
        // Still inside the back-off after a failed connect: fail at once
        // rather than let requests queue up behind a device that is away.
        if (Clock::now() < next_connect)
          return fail(ErrorCode::PeripheralDisconnected, r,
                      "link down (" + why_down + "); reconnecting every " +
                          std::to_string(cfg.reconnect_interval.count()) + " ms");
        std::string reason;
        if (!open_link(reason)) {
          n.link_errors.fetch_add(1, std::memory_order_relaxed);
          next_connect = Clock::now() + cfg.reconnect_interval;
          why_down = reason;
          return fail(ErrorCode::PeripheralDisconnected, r,
                      "cannot connect: " + reason + "; will retry on the next request");
        }
      }
      RawReply reply;
      if (call(r, reply) >= 0) {
        consecutive_failures = 0;
        return reply;
      }
      const int err = errno;
      switch (classify(err)) {
        case Fault::Exception: {
          n.exceptions.fetch_add(1, std::memory_order_relaxed);
          const int ex = err - MODBUS_ENOBASE;
          consecutive_failures = 0;  // the device is there and answering
          return fail(ErrorCode::PeripheralException, r,
                      "exception " + std::string(ex < 10 ? "0" : "") + std::to_string(ex) + " (" +
                          std::string(exception_name(static_cast<std::uint8_t>(ex))) + ")");
        }
        case Fault::Timeout:
          n.timeouts.fetch_add(1, std::memory_order_relaxed);
          code = ErrorCode::PeripheralTimeout;
          why = "no answer within " + std::to_string(cfg.response_timeout.count()) + " ms";
          modbus_flush(ctx);
          break;
        case Fault::Corrupted:
          n.crc_errors.fetch_add(1, std::memory_order_relaxed);
          code = ErrorCode::PeripheralCorrupted;
          why = "answer with a bad CRC";
          modbus_flush(ctx);
          break;
        case Fault::Protocol:
          n.protocol_errors.fetch_add(1, std::memory_order_relaxed);
          code = ErrorCode::PeripheralProtocol;
          why = std::string("garbled answer: ") + modbus_strerror(err);
          modbus_flush(ctx);
          break;
        case Fault::Link:
          n.link_errors.fetch_add(1, std::memory_order_relaxed);
          code = ErrorCode::PeripheralDisconnected;
          why = std::string("link lost: ") + modbus_strerror(err);
          why_down = modbus_strerror(err);
          lose_link();
          break;
      }
    }
    if (++consecutive_failures >= cfg.rtu_reopen_after && cfg.endpoint.transport == Transport::Rtu &&
        link_up) {
      lose_link();  // reopen the port on the next request
      why_down = "port reopened after " + std::to_string(consecutive_failures) + " failed requests";
      consecutive_failures = 0;
    }
    return fail(code, r,
                why + " (" + std::to_string(attempts) + " attempt" + (attempts > 1 ? "s" : "") + ")");
  }
  void run() {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex);
        cv.wait(lock, [&] { return stopping || !queue.empty(); });
        if (stopping) break;
        job = std::move(queue.front());
        queue.pop_front();
      }
      Result<RawReply> result = execute(job.request);
      n.requests.fetch_add(1, std::memory_order_relaxed);
      (result.ok() ? n.ok : n.failed).fetch_add(1, std::memory_order_relaxed);
      job.done(std::move(result));
    }
    close_link();
  }

  void submit(RawRequest r, RawCallback done) {
    std::string refusal;
    {
      std::lock_guard lock(mutex);
      if (stopping || !started) {
        refusal = "master stopped";
      } else if (queue.size() >= cfg.queue_capacity) {
        refusal = "request queue full (" + std::to_string(cfg.queue_capacity) + ")";
      } else {
        queue.push_back({std::move(r), std::move(done)});
        cv.notify_one();
        return;
      }
    }
    n.refused.fetch_add(1, std::memory_order_relaxed);
    done(fail(ErrorCode::PeripheralStopped, r, refusal));
  }
};

ModbusMaster::ModbusMaster(DeviceMap map, MasterConfig config)
    : impl_(std::make_shared<Impl>(std::move(map), std::move(config))) {}

ModbusMaster::~ModbusMaster() { stop(); }

Status ModbusMaster::start() {
  std::lock_guard lock(impl_->mutex);
  if (impl_->started) return {};
  impl_->started = true;
  impl_->stopping = false;
  impl_->worker = std::thread([impl = impl_.get()] { impl->run(); });
  return {};
}

void ModbusMaster::stop() noexcept {
  std::deque<Impl::Job> orphans;
  {
    std::lock_guard lock(impl_->mutex);
    if (!impl_->started || impl_->stopping) return;
    impl_->stopping = true;
    orphans.swap(impl_->queue);
  }
  impl_->cv.notify_all();
  if (impl_->worker.joinable()) impl_->worker.join();
  for (Impl::Job& j : orphans) {
    impl_->n.refused.fetch_add(1, std::memory_order_relaxed);
    j.done(make_error(ErrorCode::PeripheralStopped,
                      who() + ": " + j.request.what + ": master stopped before it was sent"));
  }
  std::lock_guard lock(impl_->mutex);
  impl_->started = false;
}

void ModbusMaster::submit(RawRequest request, RawCallback done) {
  impl_->submit(std::move(request), std::move(done));
}

namespace {

// A call that answers through a callback, as a future: `start(done)` with
// done(T) fulfilling it.
template <typename T, typename Start>
std::future<T> as_future(Start&& start) {
  auto p = std::make_shared<std::promise<T>>();
  std::future<T> f = p->get_future();
  start([p](T v) { p->set_value(std::move(v)); });
  return f;
}

Function read_function(Table t) noexcept {
  switch (t) {
    case Table::Coil: return Function::ReadCoils;
    case Table::Discrete: return Function::ReadDiscreteInputs;
    case Table::Holding: return Function::ReadHoldingRegisters;
    case Table::Input: return Function::ReadInputRegisters;
  }
  return Function::ReadHoldingRegisters;
}

// A device value outside its register's range: the map and the device
// disagree, which the caller must hear about rather than use the value.
Result<double> checked(const DeviceMap& map, const RegisterDef& r, double v, const std::string& who) {
  if (r.in_range(v)) return v;
  return make_error(ErrorCode::PeripheralValueOutOfRange, who + ": read " + r.name + ": device reported " +
                                                              format_number(v) + " outside " +
                                                              r.describe(map.name));
}

}  // namespace

std::future<Result<RawReply>> ModbusMaster::request(RawRequest r) {
  return as_future<Result<RawReply>>([&](auto done) { submit(std::move(r), std::move(done)); });
}

void ModbusMaster::read_async(std::string_view name, std::function<void(Result<double>)> done) {
  auto reg = impl_->map.lookup(name);
  if (!reg) {
    impl_->n.refused.fetch_add(1, std::memory_order_relaxed);
    done(make_error(reg.error().code, who() + ": " + reg.error().message));
    return;
  }
  const RegisterDef* r = reg.value();
  RawRequest req{read_function(r->table), r->address, r->words(), {}, "read " + r->name};
  submit(std::move(req), [r, impl = impl_, done = std::move(done)](Result<RawReply> res) {
    if (!res) return done(res.error());
    done(checked(impl->map, *r, r->decode(res.value()), impl->who()));
  });
}

std::future<Result<double>> ModbusMaster::read(std::string_view name) {
  return as_future<Result<double>>([&](auto done) { read_async(name, std::move(done)); });
}

void ModbusMaster::write_async(std::string_view name, double value, std::function<void(Status)> done) {
  auto refuse = [&](const Diagnostic& d) {
    impl_->n.refused.fetch_add(1, std::memory_order_relaxed);
    done(make_error(d.code, who() + ": write " + std::string(name) + ": " + d.message));
  };
  auto reg = impl_->map.lookup(name);
  if (!reg) return refuse(reg.error());
  const RegisterDef* r = reg.value();
  if (!r->writable())
    return refuse(make_error(ErrorCode::PeripheralReadOnly, r->describe(impl_->map.name) + " is read-only"));
  std::uint16_t raw[2] = {0, 0};
  if (Status s = r->encode(value, std::span<std::uint16_t>(raw, r->words())); !s) return refuse(s.error());
  RawRequest req;
  req.address = r->address;
  req.data.assign(raw, raw + r->words());
  req.function = r->table == Table::Coil ? Function::WriteSingleCoil
                 : r->words() == 1       ? Function::WriteSingleRegister
                                         : Function::WriteMultipleRegisters;
  req.what = "write " + r->name + " = " + format_number(value);
  submit(std::move(req), [done = std::move(done)](const Result<RawReply>& res) {
    done(res ? Status{} : Status{res.error()});
  });
}

std::future<Status> ModbusMaster::write(std::string_view name, double value) {
  return as_future<Status>([&](auto done) { write_async(name, value, std::move(done)); });
}

std::future<Result<std::vector<double>>> ModbusMaster::read_block(const std::vector<std::string>& names) {
  return as_future<Result<std::vector<double>>>([&](auto done) { read_block_async(names, std::move(done)); });
}

void ModbusMaster::read_block_async(const std::vector<std::string>& names,
                                    std::function<void(Result<std::vector<double>>)> done) {
  auto refuse = [&](ErrorCode c, const std::string& why) {
    impl_->n.refused.fetch_add(1, std::memory_order_relaxed);
    done(make_error(c, who() + ": read block: " + why));
  };
  std::vector<const RegisterDef*> regs;
  for (const std::string& nm : names) {
    auto r = impl_->map.lookup(nm);
    if (!r) {
      refuse(r.error().code, r.error().message);
      return;
    }
    regs.push_back(r.value());
  }
  if (regs.empty()) {
    refuse(ErrorCode::PeripheralBadRequest, "no registers named");
    return;
  }
  std::uint32_t lo = 0xFFFF, hi = 0;
  for (const RegisterDef* r : regs) {
    if (r->table != regs[0]->table) {
      refuse(ErrorCode::PeripheralBadRequest,
             r->name + " is in table " + std::string(table_name(r->table)) + ", " + regs[0]->name + " in " +
                 std::string(table_name(regs[0]->table)) + "; one request reads one table");
      return;
    }
    lo = std::min<std::uint32_t>(lo, r->address);
    hi = std::max<std::uint32_t>(hi, r->address + r->words());
  }
  for (std::uint32_t a = lo; a < hi; ++a)
    if (impl_->map.at(regs[0]->table, static_cast<std::uint16_t>(a)) == nullptr) {
      refuse(ErrorCode::PeripheralBadRequest,
             std::string(table_name(regs[0]->table)) + " " + std::to_string(a) +
                 " inside the block holds no register; read in two requests");
      return;
    }
  RawRequest req{read_function(regs[0]->table),
                 static_cast<std::uint16_t>(lo),
                 static_cast<std::uint16_t>(hi - lo),
                 {},
                 "read block of " + std::to_string(regs.size())};
  submit(std::move(req), [done = std::move(done), regs, lo, impl = impl_](Result<RawReply> res) {
    if (!res) return done(res.error());
    std::vector<double> out;
    for (const RegisterDef* r : regs) {
      auto v = checked(
          impl->map, *r,
          r->decode(std::span<const std::uint16_t>(res.value().data() + (r->address - lo), r->words())),
          impl->who());
      if (!v) return done(v.error());
      out.push_back(v.value());
    }
    done(std::move(out));
  });
}

std::future<Status> ModbusMaster::write_block(const std::vector<std::pair<std::string, double>>& values) {
  return as_future<Status>([&](auto done) { write_block_async(values, std::move(done)); });
}

void ModbusMaster::write_block_async(const std::vector<std::pair<std::string, double>>& values,
                                     std::function<void(Status)> done) {
  auto refuse = [&](ErrorCode c, const std::string& why) {
    impl_->n.refused.fetch_add(1, std::memory_order_relaxed);
    done(make_error(c, who() + ": write block: " + why));
  };
  struct Item {
    const RegisterDef* reg;
    double value;
  };
  std::vector<Item> items;
  for (const auto& [nm, v] : values) {
    auto r = impl_->map.lookup(nm);
    if (!r) {
      refuse(r.error().code, r.error().message);
      return;
    }
    items.push_back({r.value(), v});
  }
  if (items.empty()) {
    refuse(ErrorCode::PeripheralBadRequest, "no registers named");
    return;
  }
  std::sort(items.begin(), items.end(),
            [](const Item& a, const Item& b) { return a.reg->address < b.reg->address; });
  const Table t = items[0].reg->table;
  if (t != Table::Holding && t != Table::Coil) {
    refuse(ErrorCode::PeripheralReadOnly, items[0].reg->describe(impl_->map.name) + " is read-only");
    return;
  }
  RawRequest req;
  req.function = t == Table::Holding ? Function::WriteMultipleRegisters : Function::WriteMultipleCoils;
  req.address = items[0].reg->address;
  std::uint32_t next = req.address;
  for (const Item& it : items) {
    const RegisterDef& r = *it.reg;
    if (r.table != t || !r.writable()) {
      refuse(ErrorCode::PeripheralReadOnly,
             r.describe(impl_->map.name) + (r.table != t ? " is in another table" : " is read-only"));
      return;
    }
    if (r.address != next) {
      refuse(ErrorCode::PeripheralBadRequest, "not contiguous: " + r.name + " at " +
                                                  std::to_string(r.address) + ", expected " +
                                                  std::to_string(next) + "; a block is written with one FC" +
                                                  std::to_string(static_cast<int>(req.function)));
      return;
    }
    std::uint16_t raw[2];
    if (Status s = r.encode(it.value, std::span<std::uint16_t>(raw, r.words())); !s) {
      refuse(s.error().code, s.error().message + "; nothing sent");
      return;
    }
    req.data.insert(req.data.end(), raw, raw + r.words());
    next += r.words();
  }
  req.what = "write block " + items.front().reg->name + " … " + items.back().reg->name;
  submit(std::move(req), [done = std::move(done)](const Result<RawReply>& res) {
    done(res ? Status{} : Status{res.error()});
  });
}

MasterCounters ModbusMaster::counters() const noexcept {
  const auto& n = impl_->n;
  return {n.requests.load(),    n.ok.load(),         n.failed.load(),          n.retries.load(),
          n.timeouts.load(),    n.crc_errors.load(), n.protocol_errors.load(), n.exceptions.load(),
          n.link_errors.load(), n.reconnects.load(), n.refused.load()};
}

bool ModbusMaster::connected() const noexcept { return impl_->connected.load(); }

std::string ModbusMaster::last_error() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->last_error;
}

const DeviceMap& ModbusMaster::map() const noexcept { return impl_->map; }
std::string ModbusMaster::who() const { return impl_->who(); }

}  // namespace lcnc::drivers
