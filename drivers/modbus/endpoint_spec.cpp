#include "drivers/modbus/endpoint_spec.h"

#include <charconv>
#include <string>

namespace lcnc::drivers {

Result<Endpoint> parse_endpoint(std::string_view spec) {
  const auto bad = [&](const std::string& why) {
    return make_error(ErrorCode::Usage, "'" + std::string(spec) + "': " + why +
                                            "; expected tcp:HOST:PORT or rtu:DEVICE[:BAUD[:PARITY]]");
  };
  const auto number = [](std::string_view t, int& out) {
    const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  };
  Endpoint e;
  if (spec.substr(0, 4) == "tcp:") {
    const std::string_view rest = spec.substr(4);
    const std::size_t colon = rest.rfind(':');
    if (colon == std::string_view::npos || colon == 0) return bad("no host and port");
    int port = -1;
    if (!number(rest.substr(colon + 1), port) || port < 0 || port > 65535)
      return bad("port must be 0 … 65535 (0: any free port)");
    e.transport = Transport::Tcp;
    e.host = std::string(rest.substr(0, colon));
    e.port = static_cast<std::uint16_t>(port);
    return e;
  }
  if (spec.substr(0, 4) == "rtu:") {
    std::string_view rest = spec.substr(4);
    e.transport = Transport::Rtu;
    const std::size_t c1 = rest.find(':');
    e.device = std::string(rest.substr(0, c1));
    if (e.device.empty()) return bad("no serial device");
    if (c1 != std::string_view::npos) {
      rest = rest.substr(c1 + 1);
      const std::size_t c2 = rest.find(':');
      if (!number(rest.substr(0, c2), e.baud) || e.baud <= 0) return bad("baud must be a positive number");
      if (c2 != std::string_view::npos) {
        const std::string_view parity = rest.substr(c2 + 1);
        if (parity != "N" && parity != "E" && parity != "O") return bad("parity must be N, E or O");
        e.parity = parity[0];
      }
    }
    return e;
  }
  return bad("unknown transport");
}

}  // namespace lcnc::drivers
