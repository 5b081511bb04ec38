#include "drivers/serial/probe_protocol.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace lcnc::drivers::probe {

namespace {

constexpr char kHex[] = "0123456789ABCDEF";

int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

Diagnostic syntax(std::string_view source, std::size_t col, std::string msg) {
  return make_error(ErrorCode::SerialSyntax, std::move(msg), std::string(source), 0,
                    static_cast<std::uint32_t>(col));
}

std::string shown(std::string_view line) {
  std::string s;
  for (char c : line) {
    if (c == '\r')
      s += "\\r";
    else if (c == '\n')
      s += "\\n";
    else if (c < 0x20 || c > 0x7E) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02X", static_cast<unsigned char>(c));
      s += b;
    } else {
      s += c;
    }
  }
  return s;
}

bool parse_id(const std::string& f, std::uint16_t& out, bool zero_ok) {
  unsigned v = 0;
  const auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  if (ec != std::errc() || p != f.data() + f.size() || v > 65535 || (v == 0 && !zero_ok)) return false;
  out = static_cast<std::uint16_t>(v);
  return true;
}

bool parse_mm(const std::string& f, double& out) {
  if (f.empty()) return false;
  const auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), out);
  return ec == std::errc() && p == f.data() + f.size() && std::isfinite(out);
}

std::string mm(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}

}  // namespace

std::uint8_t checksum(std::string_view body) noexcept {
  std::uint8_t x = 0;
  for (char c : body) x ^= static_cast<std::uint8_t>(c);
  return x;
}

std::string frame(std::string_view body) {
  const std::uint8_t cs = checksum(body);
  std::string s;
  s.reserve(body.size() + 6);
  s += '$';
  s += body;
  s += '*';
  s += kHex[cs >> 4];
  s += kHex[cs & 0xF];
  s += "\r\n";
  return s;
}

Result<Sentence> parse_sentence(std::string_view line, std::string_view source) {
  if (line.size() > kMaxSentence)
    return syntax(source, kMaxSentence + 1,
                  "line of " + std::to_string(line.size()) + " bytes; at most " +
                      std::to_string(kMaxSentence) + " with CR LF");
  if (line.size() < 2 || line.substr(line.size() - 2) != "\r\n")
    return syntax(source, line.size() + 1, "'" + shown(line) + "' does not end in CR LF");
  line.remove_suffix(2);
  if (line.empty() || line[0] != '$')
    return syntax(source, 1, "'" + shown(line) + "' does not start with '$'");
  const std::size_t star = line.rfind('*');
  if (star == std::string_view::npos || star + 3 != line.size())
    return syntax(source, star == std::string_view::npos ? line.size() + 1 : star + 1,
                  "'" + shown(line) + "' does not end in '*HH' (two hex digits of checksum)");
  const int hi = hex_value(line[star + 1]), lo = hex_value(line[star + 2]);
  if (hi < 0 || lo < 0)
    return syntax(source, star + 2, "checksum '" + shown(line.substr(star + 1)) + "' is not two hex digits");
  const std::string_view body = line.substr(1, star - 1);
  for (std::size_t i = 0; i < body.size(); ++i) {
    const char c = body[i];
    if (c < 0x20 || c > 0x7E || c == '$' || c == '*')
      return syntax(source, i + 2, "byte '" + shown(body.substr(i, 1)) + "' not allowed in a sentence");
  }
  const std::uint8_t want = checksum(body);
  const auto got = static_cast<std::uint8_t>(hi * 16 + lo);
  if (got != want) {
    char b[96];
    std::snprintf(b, sizeof b, "checksum *%02X does not match the body's *%02X", got, want);
    return make_error(ErrorCode::SerialChecksum, "'" + shown(line) + "': " + b, std::string(source), 0,
                      static_cast<std::uint32_t>(star + 2));
  }
  Sentence s;
  std::size_t start = 0;
  bool first = true;
  for (;;) {
    const std::size_t comma = body.find(',', start);
    const std::string_view f =
        body.substr(start, comma == std::string_view::npos ? body.npos : comma - start);
    if (first)
      s.type = std::string(f);
    else
      s.fields.emplace_back(f);
    first = false;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (s.type.empty()) return syntax(source, 2, "sentence without a type");
  return s;
}

std::string_view probe_error_text(ProbeError e) noexcept {
  switch (e) {
    case ProbeError::NoSurface: return "no surface in range";
    case ProbeError::Busy: return "busy";
    case ProbeError::BadRequest: return "bad request";
  }
  return "unknown";
}

std::string encode(const Message& m) {
  struct V {
    std::string operator()(const MeasureRequest& r) const { return frame("MEAS," + std::to_string(r.id)); }
    std::string operator()(const PingRequest&) const { return frame("PING"); }
    std::string operator()(const PointReply& r) const {
      return frame("POS," + std::to_string(r.id) + "," + mm(r.x_mm) + "," + mm(r.y_mm) + "," + mm(r.z_mm));
    }
    std::string operator()(const ErrorReply& r) const {
      std::string text;
      for (char c : r.text) text += (c == ',' || c == '*' || c == '$' || c < 0x20 || c > 0x7E) ? ' ' : c;
      return frame("ERR," + std::to_string(r.id) + "," + std::to_string(static_cast<int>(r.code)) + "," +
                   text);
    }
    std::string operator()(const PongReply& r) const { return frame("PONG," + r.model + "," + r.firmware); }
  };
  return std::visit(V{}, m);
}

Result<Message> decode(std::string_view line, std::string_view source) {
  auto s = parse_sentence(line, source);
  if (!s) return s.error();
  const Sentence& sen = s.value();
  auto bad = [&](std::string what) { return syntax(source, 2, "$" + sen.type + ": " + std::move(what)); };
  auto count = [&](std::size_t n) -> bool { return sen.fields.size() == n; };
  if (sen.type == "MEAS") {
    MeasureRequest r;
    if (!count(1)) return bad("expected 1 field (id), found " + std::to_string(sen.fields.size()));
    if (!parse_id(sen.fields[0], r.id, false))
      return bad("id '" + sen.fields[0] + "' is not an integer 1 … 65535");
    return Message{r};
  }
  if (sen.type == "PING") {
    if (!count(0)) return bad("expected no fields");
    return Message{PingRequest{}};
  }
  if (sen.type == "POS") {
    PointReply r;
    if (!count(4)) return bad("expected 4 fields (id, x, y, z), found " + std::to_string(sen.fields.size()));
    if (!parse_id(sen.fields[0], r.id, false))
      return bad("id '" + sen.fields[0] + "' is not an integer 1 … 65535");
    double* out[3] = {&r.x_mm, &r.y_mm, &r.z_mm};
    for (int i = 0; i < 3; ++i)
      if (!parse_mm(sen.fields[1 + i], *out[i]))
        return bad(std::string(1, "xyz"[i]) + " '" + sen.fields[1 + i] + "' is not a number");
    return Message{r};
  }
  if (sen.type == "ERR") {
    ErrorReply r;
    if (!count(3))
      return bad("expected 3 fields (id, code, text), found " + std::to_string(sen.fields.size()));
    std::uint16_t code = 0;
    if (!parse_id(sen.fields[0], r.id, true))
      return bad("id '" + sen.fields[0] + "' is not an integer 0 … 65535");
    if (!parse_id(sen.fields[1], code, false) || code > 3)
      return bad("code '" + sen.fields[1] + "' is not 1, 2 or 3");
    r.code = static_cast<ProbeError>(code);
    r.text = sen.fields[2];
    return Message{r};
  }
  if (sen.type == "PONG") {
    if (!count(2)) return bad("expected 2 fields (model, firmware)");
    return Message{PongReply{sen.fields[0], sen.fields[1]}};
  }
  return bad("unknown sentence type; expected MEAS, PING, POS, ERR or PONG");
}

}  // namespace lcnc::drivers::probe
