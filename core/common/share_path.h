// Where the shipped files are (machine configs, the Modbus register map, the
// examples, the HAL configurations, the HMI's translations), first found of:
//   $LASERCNC_SHARE (when set and not empty);
//   <the executable's folder>/../share/lasercnc (an installed tree: the
//     .deb's /usr/share/lasercnc, or any `cmake --install` prefix);
//   the source tree's share/ the build was made from.
#pragma once

#include <string>
#include <string_view>

namespace lcnc {

// share/<relative>, e.g. share_path("machines/default.toml").
[[nodiscard]] std::string share_path(std::string_view relative);

}  // namespace lcnc
