// Where the shipped files are (machine configs, the Modbus register map, the
// examples): $LASERCNC_SHARE when set (an installed tree), else the source
// tree's share/ the build was made from.
#pragma once

#include <string>
#include <string_view>

namespace lcnc {

// share/<relative>, e.g. share_path("machines/default.toml").
[[nodiscard]] std::string share_path(std::string_view relative);

}  // namespace lcnc
