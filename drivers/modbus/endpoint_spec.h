// A device's endpoint as the command lines give it: `tcp:HOST:PORT` (port 0:
// any free one, for a slave) or `rtu:DEVICE[:BAUD[:PARITY]]` (115200 and N
// by default); a Usage error otherwise.
#pragma once

#include <string_view>

#include "common/result.h"
#include "drivers/modbus/modbus_types.h"

namespace lcnc::drivers {

[[nodiscard]] Result<Endpoint> parse_endpoint(std::string_view spec);

}  // namespace lcnc::drivers
