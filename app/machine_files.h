// The machine configs the project ships.
#pragma once

#include <string>

namespace lcnc::app {

// A machine config shipped in share/machines (NAME.toml; $LASERCNC_SHARE
// overrides where share/ is), and the default one (default.toml).
[[nodiscard]] std::string shipped_machine_file(const std::string& name);
[[nodiscard]] std::string default_machine_file();

}  // namespace lcnc::app
