// A number in a message: six significant digits, as people read them
// ("0.001", "1e+06", "-30").
#pragma once

#include <cstdio>
#include <string>

namespace lcnc {

[[nodiscard]] inline std::string six_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace lcnc
