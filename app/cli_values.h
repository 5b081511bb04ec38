// Option values the DXF sub-commands (decompose, cut) read alike: a plain
// number, an X,Y pair in mm, a drawing unit.
#pragma once

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace lcnc::app {

// "12.5" → 12.5; nothing else may follow the number.
inline std::optional<double> parse_plain(std::string_view s) {
  const std::string str(s);
  char* end = nullptr;
  const double v = std::strtod(str.c_str(), &end);
  if (end == str.c_str() || *end != '\0') return std::nullopt;
  return v;
}

// "100,50" → (100, 50), both finite.
inline std::optional<std::pair<double, double>> parse_xy(std::string_view s) {
  const std::string str(s);
  char* end = nullptr;
  const double x = std::strtod(str.c_str(), &end);
  if (end == str.c_str() || *end != ',') return std::nullopt;
  const char* ys = end + 1;
  const double y = std::strtod(ys, &end);
  if (end == ys || *end != '\0' || !std::isfinite(x) || !std::isfinite(y)) return std::nullopt;
  return std::pair{x, y};
}

// mm per drawing unit of "mm", "cm", "m", "inch" (or "in").
inline std::optional<double> parse_unit_mm(std::string_view v) {
  if (v == "mm") return 1.0;
  if (v == "cm") return 10.0;
  if (v == "m") return 1000.0;
  if (v == "inch" || v == "in") return 25.4;
  return std::nullopt;
}

}  // namespace lcnc::app
