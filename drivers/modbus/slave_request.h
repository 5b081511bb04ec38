// One Modbus request as the slave takes it: received and framed by libmodbus
// (RTU CRC, TCP MBAP), checked against the register map (Shao 2022 fig. 15:
// every address must hold a register of the map, writes must hit whole
// writable registers, every value must be in range), offered to the owner's
// write hook, then answered by libmodbus — all before anything changes, so
// a refused block leaves every register as it was.
//
// Over TCP the slave cuts frames itself (cut_tcp_frame: the MBAP header's
// length delimits each frame) and hands whole ones to answer_tcp_frame,
// which checks the header before anything is taken: protocol id 0, the
// unit, and a PDU exactly as long as its function needs — no more bytes
// hidden behind it (Modbus Application Protocol 1.1b3 §7: exception 03 "the
// implied length is incorrect"). Over RTU libmodbus receives and frames
// (CRC, silence between frames).
//
// ModbusSlave serves its connections with this; RawFrameLoop feeds it raw
// bytes through a socket pair (the fuzz target of the slave's request
// handling, and tests of malformed frames).
#pragma once

#include <cstddef>
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

// The largest Modbus TCP frame: a 7-byte MBAP header and a 253-byte PDU, so
// an MBAP length (unit id + PDU) of at most 254.
inline constexpr std::size_t kMaxTcpAdu = 260;
inline constexpr std::size_t kMaxMbapLength = 254;

// Where the next Modbus TCP frame ends in the bytes a connection has
// received: 6 + the MBAP length.
struct TcpFrameCut {
  enum class Kind : std::uint8_t {
    NeedMore,     // the frame is not all in yet
    Frame,        // `size` bytes: a Modbus frame (protocol id 0, a function code)
    Foreign,      // `size` bytes that are no Modbus request (protocol id ≠ 0, or
                  // no function code): dropped, the next frame follows them
    Unframeable,  // a length beyond the largest frame: the stream holds no
                  // boundary to find the next frame by (close the connection)
  };
  Kind kind = Kind::NeedMore;
  std::size_t size = 0;
};
[[nodiscard]] TcpFrameCut cut_tcp_frame(std::span<const std::uint8_t> bytes) noexcept;

// The length a request's PDU must have by its function (function code and
// fields, plus the byte count's data for 15 and 16; a PDU too short to hold
// the byte count needs at least 6), or 0 for a function the slave does not
// implement (its answer, 01, needs no length).
[[nodiscard]] std::size_t request_pdu_length(std::span<const std::uint8_t> pdu) noexcept;

// What came of one receive on a connection.
struct Received {
  enum class Kind : std::uint8_t {
    Answered,     // a request, answered (`exception` None) or refused
    OtherUnit,    // a frame for another unit, ignored
    Malformed,    // TCP: dropped for its MBAP header (no answer), counted
    NotARequest,  // a function code ≥ 0x80 (an exception response's): not
                  // answered — libmodbus would echo it as fc + 0x80 mod 256,
                  // which reads as a normal answer of another function
    BadCrc,       // RTU: dropped
    Broken,       // the peer closed or broke the framing, or the answer could
                  // not be sent (TCP: close it)
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
    std::uint64_t malformed = 0;   // TCP frames refused for their header: protocol id ≠ 0,
                                   // no function code or a length beyond the largest frame
                                   // (dropped), a PDU not the function's length (answered 03)
  };
  [[nodiscard]] Counts counts() const noexcept;

  [[nodiscard]] RegisterBank& bank() noexcept;
  [[nodiscard]] const RegisterBank& bank() const noexcept;

  // Receives one request on `ctx` (its socket already set) and answers it;
  // `bank_lock`, when given, is held from the check to the reply (not while
  // waiting for the frame's bytes). The counts move before the answer goes
  // out: a peer that has its answer sees them counted.
  Received receive_and_answer(modbus_t* ctx, const WriteHook& hook, std::mutex* bank_lock = nullptr) noexcept;

  // Answers one whole TCP frame (cut_tcp_frame's Frame) on `ctx`'s socket
  // (a TCP context; the socket set). Units other than `unit`, 0 and 255
  // (Modbus TCP's "this server") are ignored, as on a serial line; a PDU
  // not exactly its function's length is exception 03 and nothing of it
  // is taken; the rest as receive_and_answer.
  Received answer_tcp_frame(modbus_t* ctx, std::span<const std::uint8_t> adu, std::uint8_t unit,
                            const WriteHook& hook, std::mutex* bank_lock = nullptr) noexcept;

  // Counts a TCP frame dropped for its header (Foreign, Unframeable).
  void count_malformed() noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Received take(modbus_t* ctx, const std::uint8_t* q, int len, const WriteHook& hook,
                std::mutex* bank_lock) noexcept;
};

// Raw bytes to the slave's request handling, in-process: the bytes are
// written into one end of a fresh socket pair and that end shut for
// writing (a peer that sends and hangs up), the handler takes the first
// frame exactly as from a connection (TCP: cut by cut_tcp_frame; RTU:
// received through libmodbus), and its answer is read back.
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
  Transport framing_ = Transport::Tcp;
  std::uint8_t unit_ = 1;
};

}  // namespace lcnc::drivers
