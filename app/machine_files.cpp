#include "app/machine_files.h"

#include "common/share_path.h"

namespace lcnc::app {

std::string shipped_machine_file(const std::string& name) { return share_path("machines/" + name + ".toml"); }

std::string default_machine_file() { return shipped_machine_file("default"); }

}  // namespace lcnc::app
