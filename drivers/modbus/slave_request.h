// One Modbus request as the slave takes it: received and framed by libmodbus
// (RTU CRC, TCP MBAP), checked against the register map (seed 000 fig. 15:
// every address must hold a register of the map, writes must hit whole
// writable registers, every value must be in range), offered to the owner's
// write hook, then answered by libmodbus — all before anything changes, so
// a refused block leaves every register as it was.
//
// ModbusSlave serves its connections with this; RawFrameLoop feeds it raw
// bytes through a socket pair (the fuzz target of the slave's request
// handling, and tests of malformed frames).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "common/result.h"
#include "drivers/modbus/modbus_types.h"
#include "drivers/modbus/register_bank.h"
#include "drivers/modbus/register_map.h"

typedef struct _modbus modbus_t;  // libmodbus's context (modbus.h)

namespace lcnc::drivers {

// One register of a write request, decoded and range-checked.
struct RegisterWrite {
  const RegisterDef* reg;
  double value;
};

// Called before a valid write is applied; return None to accept it.
using WriteHook = std::function<ModbusException(std::span<const RegisterWrite>, RegisterBank&)>;

// Checks a request (`q`, `len`: the ADU, with a header of `header_length`
// bytes before the function code) against `map`; fills `writes` for a valid
// write. Reads nothing outside q[0, len).
[[nodiscard]] ModbusException check_slave_request(const DeviceMap& map, int header_length,
                                                  const std::uint8_t* q, int len,
                                                  std::vector<RegisterWrite>& writes);

// What came of one receive on a connection.
struct Received {
  enum class Kind : std::uint8_t {
    Answered,   // a request, answered (`exception` None) or refused
    OtherUnit,  // RTU: a frame for another unit, ignored
    NotARequest,  // a function code ≥ 0x80 (an exception response's): not
                  // answered — libmodbus would echo it as fc + 0x80 mod 256,
                  // which reads as a normal answer of another function
    BadCrc,     // RTU: dropped
    Broken,     // the peer closed or broke the framing (TCP: close it)
  };
  Kind kind = Kind::Broken;
  ModbusException exception = ModbusException::None;
  bool write = false;  // the request was a write (function 5, 6, 15 or 16)
};

// The slave's register bank and its answers. Not movable: libmodbus's
// mapping points into the bank.
class SlaveRequestHandler {
 public:
  explicit SlaveRequestHandler(DeviceMap map);
  ~SlaveRequestHandler();
  SlaveRequestHandler(const SlaveRequestHandler&) = delete;
  SlaveRequestHandler& operator=(const SlaveRequestHandler&) = delete;

  // What was received (any thread).
  struct Counts {
    std::uint64_t requests = 0;    // well-framed requests, answered or not (fc ≥ 0x80)
    std::uint64_t exceptions = 0;  // answered with an exception, or not a request
    std::uint64_t refused = 0;     // writes refused (exceptions 02/03/hook)
    std::uint64_t crc_errors = 0;  // RTU frames dropped for a bad CRC
  };
  [[nodiscard]] Counts counts() const noexcept;

  [[nodiscard]] RegisterBank& bank() noexcept;
  [[nodiscard]] const RegisterBank& bank() const noexcept;

  // Receives one request on `ctx` (its socket already set) and answers it;
  // `bank_lock`, when given, is held from the check to the reply (not while
  // waiting for the frame's bytes). The counts move before the answer goes
  // out: a peer that has its answer sees them counted.
  Received receive_and_answer(modbus_t* ctx, const WriteHook& hook,
                              std::mutex* bank_lock = nullptr) noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Raw bytes to the slave's request handling, in-process: the bytes are
// written into one end of a fresh socket pair and that end shut for
// writing (a peer that sends and hangs up), the handler receives from the
// other through libmodbus exactly as from a connection, and its answer is
// read back.
class RawFrameLoop {
 public:
  [[nodiscard]] static Result<std::unique_ptr<RawFrameLoop>> open(Transport framing, int unit_id);
  ~RawFrameLoop();
  RawFrameLoop(const RawFrameLoop&) = delete;
  RawFrameLoop& operator=(const RawFrameLoop&) = delete;

  struct Exchange {
    Received received;
    std::vector<std::uint8_t> reply;  // empty: no answer
  };
  // Delivers `frame`, lets `handler` take one request of it, returns its
  // answer; whatever of the bytes the handler did not take is discarded.
  Exchange deliver(SlaveRequestHandler& handler, std::span<const std::uint8_t> frame,
                   const WriteHook& hook = {});

  // The RTU frame of `unit` and `pdu` with its CRC appended.
  [[nodiscard]] static std::vector<std::uint8_t> rtu_frame(std::uint8_t unit,
                                                           std::span<const std::uint8_t> pdu);

 private:
  RawFrameLoop() = default;
  modbus_t* ctx_ = nullptr;
};

}  // namespace lcnc::drivers
