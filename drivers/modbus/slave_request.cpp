#include "drivers/modbus/slave_request.h"

#include <modbus.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

namespace lcnc::drivers {
namespace {

constexpr std::uint16_t kMaxReadRegisters = 125;  // Modbus limits per request
constexpr std::uint16_t kMaxReadBits = 2000;
constexpr std::uint16_t kMaxWriteRegisters = 123;
constexpr std::uint16_t kMaxWriteBits = 1968;

std::uint16_t be16(const std::uint8_t* p) noexcept { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

bool is_write(std::uint8_t fc) noexcept { return fc == 5 || fc == 6 || fc == 15 || fc == 16; }

}  // namespace

TcpFrameCut cut_tcp_frame(std::span<const std::uint8_t> bytes) noexcept {
  constexpr std::size_t kLengthEnd = 6;  // transaction id, protocol id, length
  if (bytes.size() < kLengthEnd) return {};
  const std::size_t length = be16(bytes.data() + 4);
  if (length > kMaxMbapLength) return {TcpFrameCut::Kind::Unframeable, 0};
  const std::size_t size = kLengthEnd + length;
  if (bytes.size() < size) return {};
  const bool modbus = be16(bytes.data() + 2) == 0 && length >= 2;  // unit id and a function code
  return {modbus ? TcpFrameCut::Kind::Frame : TcpFrameCut::Kind::Foreign, size};
}

std::size_t request_pdu_length(std::span<const std::uint8_t> pdu) noexcept {
  if (pdu.empty()) return 1;
  switch (pdu[0]) {
    case 1:
    case 2:
    case 3:
    case 4:
    case 5:
    case 6: return 5;  // fc, address, count or value
    case 15:
    case 16: return pdu.size() < 6 ? 6 : 6 + std::size_t{pdu[5]};  // fc, address, count, byte count, data
    default: return 0;
  }
}

ModbusException check_slave_request(const DeviceMap& map, int header_length, const std::uint8_t* q, int len,
                                    std::vector<RegisterWrite>& writes) {
  const int o = header_length;
  if (len < o + 1) return ModbusException::IllegalDataValue;
  // The function first (an unknown one is 01 however short), then its fields.
  const std::uint8_t fc = q[o];
  if (!(fc >= 1 && fc <= 6) && fc != 15 && fc != 16) return ModbusException::IllegalFunction;
  if (len < o + 5) return ModbusException::IllegalDataValue;
  const std::uint16_t addr = be16(q + o + 1);
  const std::uint16_t n = be16(q + o + 3);

  // Every address in [addr, addr + count) must hold a register of table t.
  auto all_mapped = [&](Table t, std::uint32_t count) {
    for (std::uint32_t a = addr; a < addr + count; ++a)
      if (a > 0xFFFF || map.at(t, static_cast<std::uint16_t>(a)) == nullptr) return false;
    return true;
  };

  switch (fc) {
    case 1:
    case 2:
    case 3:
    case 4: {
      const Table t = fc == 1   ? Table::Coil
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
      if (r == nullptr || !r->writable() || r->words() != 1) return ModbusException::IllegalDataAddress;
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
    default: return ModbusException::IllegalFunction;
  }
}

struct SlaveRequestHandler::Impl {
  RegisterBank bank;
  modbus_mapping_t mapping{};
  std::atomic<std::uint64_t> requests{0}, exceptions{0}, refused{0}, crc_errors{0}, malformed{0};

  explicit Impl(DeviceMap map) : bank(std::move(map)) {
    mapping.nb_bits = static_cast<int>(bank.bits(Table::Coil).size());
    mapping.tab_bits = bank.bits(Table::Coil).data();
    mapping.nb_input_bits = static_cast<int>(bank.bits(Table::Discrete).size());
    mapping.tab_input_bits = bank.bits(Table::Discrete).data();
    mapping.nb_registers = static_cast<int>(bank.words(Table::Holding).size());
    mapping.tab_registers = bank.words(Table::Holding).data();
    mapping.nb_input_registers = static_cast<int>(bank.words(Table::Input).size());
    mapping.tab_input_registers = bank.words(Table::Input).data();
  }
};

SlaveRequestHandler::SlaveRequestHandler(DeviceMap map) : impl_(std::make_unique<Impl>(std::move(map))) {}
SlaveRequestHandler::~SlaveRequestHandler() = default;
RegisterBank& SlaveRequestHandler::bank() noexcept { return impl_->bank; }

SlaveRequestHandler::Counts SlaveRequestHandler::counts() const noexcept {
  return {impl_->requests.load(), impl_->exceptions.load(), impl_->refused.load(), impl_->crc_errors.load(),
          impl_->malformed.load()};
}
const RegisterBank& SlaveRequestHandler::bank() const noexcept { return impl_->bank; }

Received SlaveRequestHandler::receive_and_answer(modbus_t* ctx, const WriteHook& hook,
                                                 std::mutex* bank_lock) noexcept {
  std::uint8_t q[MODBUS_TCP_MAX_ADU_LENGTH];  // ≥ MODBUS_RTU_MAX_ADU_LENGTH
  const int rc = modbus_receive(ctx, q);
  Received out;
  if (rc == 0) {
    out.kind = Received::Kind::OtherUnit;
    return out;
  }
  if (rc < 0) {
    out.kind = errno == EMBBADCRC ? Received::Kind::BadCrc : Received::Kind::Broken;
    if (out.kind == Received::Kind::BadCrc) impl_->crc_errors.fetch_add(1, std::memory_order_relaxed);
    return out;
  }
  return take(ctx, q, rc, hook, bank_lock);
}

void SlaveRequestHandler::count_malformed() noexcept {
  impl_->malformed.fetch_add(1, std::memory_order_relaxed);
}

Received SlaveRequestHandler::answer_tcp_frame(modbus_t* ctx, std::span<const std::uint8_t> adu,
                                               std::uint8_t unit, const WriteHook& hook,
                                               std::mutex* bank_lock) noexcept {
  constexpr std::size_t kHeader = 7;  // MBAP: transaction id, protocol id, length, unit id
  Received out;
  if (adu.size() <= kHeader || adu.size() > kMaxTcpAdu) {  // not a cut_tcp_frame Frame
    count_malformed();
    out.kind = Received::Kind::Malformed;
    return out;
  }
  const std::uint8_t to = adu[kHeader - 1];
  if (to != unit && to != 0 && to != 0xFF) {
    out.kind = Received::Kind::OtherUnit;
    return out;
  }
  const std::span<const std::uint8_t> pdu = adu.subspan(kHeader);
  const std::size_t need = request_pdu_length(pdu);
  if ((pdu[0] & 0x80u) == 0 && need != 0 && need != pdu.size()) {
    // The length and the function disagree: whatever the frame holds
    // beyond (or short of) the function's fields is no part of a request.
    impl_->requests.fetch_add(1, std::memory_order_relaxed);
    impl_->exceptions.fetch_add(1, std::memory_order_relaxed);
    impl_->malformed.fetch_add(1, std::memory_order_relaxed);
    out.kind = Received::Kind::Answered;
    out.exception = ModbusException::IllegalDataValue;
    out.write = is_write(pdu[0]);
    if (out.write) impl_->refused.fetch_add(1, std::memory_order_relaxed);
    if (modbus_reply_exception(ctx, adu.data(), static_cast<unsigned>(out.exception)) < 0)
      out.kind = Received::Kind::Broken;
    return out;
  }
  return take(ctx, adu.data(), static_cast<int>(adu.size()), hook, bank_lock);
}

Received SlaveRequestHandler::take(modbus_t* ctx, const std::uint8_t* q, int rc, const WriteHook& hook,
                                   std::mutex* bank_lock) noexcept {
  Received out;
  impl_->requests.fetch_add(1, std::memory_order_relaxed);
  const int hl = modbus_get_header_length(ctx);
  if (rc <= hl || (q[hl] & 0x80u) != 0) {
    out.kind = Received::Kind::NotARequest;
    impl_->exceptions.fetch_add(1, std::memory_order_relaxed);
    return out;
  }
  out.kind = Received::Kind::Answered;
  out.write = is_write(q[hl]);
  std::unique_lock<std::mutex> lock;
  if (bank_lock != nullptr) lock = std::unique_lock<std::mutex>(*bank_lock);
  std::vector<RegisterWrite> writes;
  ModbusException ex = check_slave_request(impl_->bank.map(), hl, q, rc, writes);
  if (ex == ModbusException::None && !writes.empty() && hook)
    ex = hook(std::span<const RegisterWrite>(writes), impl_->bank);
  out.exception = ex;
  if (ex != ModbusException::None) {
    impl_->exceptions.fetch_add(1, std::memory_order_relaxed);
    if (out.write) impl_->refused.fetch_add(1, std::memory_order_relaxed);
    if (modbus_reply_exception(ctx, q, static_cast<unsigned>(ex)) < 0) out.kind = Received::Kind::Broken;
  } else if (modbus_reply(ctx, q, rc, &impl_->mapping) < 0) {  // applies the (checked) write and answers
    out.kind = Received::Kind::Broken;
  }
  return out;
}

Result<std::unique_ptr<RawFrameLoop>> RawFrameLoop::open(Transport framing, int unit_id) {
  std::unique_ptr<RawFrameLoop> loop(new RawFrameLoop());
  // The device name is never opened: a socket pair stands for the line.
  loop->ctx_ = framing == Transport::Tcp ? modbus_new_tcp("127.0.0.1", 502)
                                         : modbus_new_rtu("/dev/null", 115200, 'N', 8, 1);
  if (loop->ctx_ == nullptr)
    return make_error(ErrorCode::PeripheralSetup, std::string("libmodbus: ") + modbus_strerror(errno));
  modbus_set_slave(loop->ctx_, unit_id);
  loop->framing_ = framing;
  loop->unit_ = static_cast<std::uint8_t>(unit_id);
  modbus_set_error_recovery(loop->ctx_, MODBUS_ERROR_RECOVERY_PROTOCOL);  // as the slave
  return loop;
}

RawFrameLoop::~RawFrameLoop() {
  if (ctx_ != nullptr) modbus_free(ctx_);  // not modbus_close: the sockets are ours
}

RawFrameLoop::Exchange RawFrameLoop::deliver(SlaveRequestHandler& handler,
                                             std::span<const std::uint8_t> frame, const WriteHook& hook) {
  Exchange x;
  int fds[2];  // [0] the handler's end, [1] the sender's
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) return x;
  std::size_t sent = 0;
  while (sent < frame.size()) {
    const ssize_t n = ::send(fds[1], frame.data() + sent, frame.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  // The sender is done: a frame cut short ends at the end of the stream at
  // once, not at libmodbus's byte timeout.
  ::shutdown(fds[1], SHUT_WR);
  modbus_set_socket(ctx_, fds[0]);
  if (framing_ == Transport::Rtu) {
    x.received = handler.receive_and_answer(ctx_, hook);
  } else {  // as ModbusSlave takes a connection's bytes
    const TcpFrameCut cut = cut_tcp_frame(frame);
    switch (cut.kind) {
      case TcpFrameCut::Kind::NeedMore:  // and the stream has ended
        x.received.kind = Received::Kind::Broken;
        break;
      case TcpFrameCut::Kind::Foreign:
      case TcpFrameCut::Kind::Unframeable:
        handler.count_malformed();
        x.received.kind = Received::Kind::Malformed;
        break;
      case TcpFrameCut::Kind::Frame:
        x.received = handler.answer_tcp_frame(ctx_, frame.first(cut.size), unit_, hook);
        break;
    }
  }
  std::uint8_t buf[512];
  for (;;) {  // the answer
    const ssize_t n = ::recv(fds[1], buf, sizeof buf, MSG_DONTWAIT);
    if (n <= 0) break;
    x.reply.insert(x.reply.end(), buf, buf + n);
  }
  modbus_set_socket(ctx_, -1);
  ::close(fds[0]);
  ::close(fds[1]);
  return x;
}

std::vector<std::uint8_t> RawFrameLoop::rtu_frame(std::uint8_t unit, std::span<const std::uint8_t> pdu) {
  std::vector<std::uint8_t> f;
  f.reserve(pdu.size() + 3);
  f.push_back(unit);
  f.insert(f.end(), pdu.begin(), pdu.end());
  std::uint16_t crc = 0xFFFF;  // Modbus CRC-16 (polynomial 0xA001 reflected)
  for (std::uint8_t b : f) {
    crc ^= b;
    for (int i = 0; i < 8; ++i)
      crc = (crc & 1u) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001u) : crc >> 1;
  }
  f.push_back(static_cast<std::uint8_t>(crc & 0xFF));  // low byte first
  f.push_back(static_cast<std::uint8_t>(crc >> 8));
  return f;
}

}  // namespace lcnc::drivers
