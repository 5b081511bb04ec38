// The RS-232 line protocol of the 3D point probe (Shao 2022 §4: the 3D
// measuring device talks to the industrial PC over RS-232). ASCII sentences
// in the style of NMEA 0183, one per line, each with a checksum:
//
//   sentence  = '$' body '*' HH CR LF            at most 82 bytes in all
//   body      = type { ',' field }               printable ASCII, no '$' '*'
//   HH        = XOR of every byte of body (between '$' and '*'), two hex
//               digits, upper case when sent, either case accepted
//
// host → probe
//   $MEAS,<id>                 measure the point under the probe; id 1–65535
//   $PING                      are you there?
// probe → host
//   $POS,<id>,<x>,<y>,<z>      the point in mm, machine frame, 4 decimals
//   $ERR,<id>,<code>,<text>    1 no surface in range, 2 busy, 3 bad request
//                              (bad checksum or syntax: id 0 when unreadable)
//   $PONG,<model>,<firmware>
//
// Example: "$MEAS,7*01\r\n" → "$POS,7,512.2500,100.5000,20.0131*51\r\n".
// The parser rejects, with the column and what was expected: a missing '$',
// a missing or malformed "*HH", a checksum that does not match, bytes
// outside printable ASCII, a missing CR LF, over-long lines, unknown types,
// wrong field counts and malformed numbers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/result.h"

namespace lcnc::drivers::probe {

inline constexpr std::size_t kMaxSentence = 82;  // bytes, with "\r\n" (NMEA 0183)

[[nodiscard]] std::uint8_t checksum(std::string_view body) noexcept;
// "$" body "*" HH "\r\n"
[[nodiscard]] std::string frame(std::string_view body);

struct Sentence {
  std::string type;                 // "POS"
  std::vector<std::string> fields;  // after the type
};
// `source` (a port path) is put in the Diagnostic's file; col is 1-based.
[[nodiscard]] Result<Sentence> parse_sentence(std::string_view line, std::string_view source = {});

enum class ProbeError : std::uint8_t { NoSurface = 1, Busy = 2, BadRequest = 3 };
[[nodiscard]] std::string_view probe_error_text(ProbeError e) noexcept;

struct MeasureRequest {
  std::uint16_t id = 1;
};
struct PingRequest {};
struct PointReply {
  std::uint16_t id = 0;
  double x_mm = 0, y_mm = 0, z_mm = 0;
};
struct ErrorReply {
  std::uint16_t id = 0;
  ProbeError code = ProbeError::BadRequest;
  std::string text;
};
struct PongReply {
  std::string model, firmware;
};
using Message = std::variant<MeasureRequest, PingRequest, PointReply, ErrorReply, PongReply>;

[[nodiscard]] std::string encode(const Message& m);
[[nodiscard]] Result<Message> decode(std::string_view line, std::string_view source = {});

}  // namespace lcnc::drivers::probe
