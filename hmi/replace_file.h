// Writing a file the HMI hands on (an export, the hole table it sends the
// controller): written beside the target as PATH.part, then renamed over
// it. A reader that opened the old file — the daemon loading the last hole
// table sent — keeps reading it whole; nobody sees a file half-written.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace lcnc::hmi {

// Writes `path` through `write`; on failure leaves any old file as it was,
// removes the partial one and says why in `error`.
[[nodiscard]] bool replace_file(const std::string& path, const std::function<void(std::ostream&)>& write,
                                std::string& error);

}  // namespace lcnc::hmi
