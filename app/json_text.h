// JSON as the CLI prints it (--json). Strings from outside — file names, a
// daemon's messages — need not be UTF-8, and nlohmann's dump() throws on a
// bad byte: here each prints as U+FFFD instead.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace lcnc::app {

[[nodiscard]] inline std::string json_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace lcnc::app
