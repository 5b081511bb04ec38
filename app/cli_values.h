// Option values the command line reads alike: a number, an X,Y pair in mm,
// a drawing unit. One parser of numbers for every sub-command and the
// daemon's client, so "1e3" or "nan" means the same to each.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace lcnc::app {

// "COMMAND: MSG", then the command's usage, on standard error; returns the
// exit code of a usage error, 2.
inline int usage_error(std::string_view command, const std::string& msg, const char* usage) {
  std::fprintf(stderr, "%.*s: %s\n%s", static_cast<int>(command.size()), command.data(), msg.c_str(), usage);
  return 2;
}

// argv[i] of a command that takes one file and options with one value each
// (cut, decompose): --help or -h prints the usage and ends the command (0);
// a word not starting with '-', or "-", is the file (a second one is a usage
// error); anything else is an option, whose value follows (i moves on to
// it). The exit code when the command ends here, else nothing, with
// `option` and `value` set — both empty for the file.
inline std::optional<int> file_or_option(std::string_view command, const char* usage, int argc, char** argv,
                                         int& i, std::string& file, std::string_view& option,
                                         std::string_view& value) {
  const std::string_view a = argv[i];
  option = value = {};
  if (a == "--help" || a == "-h") {
    std::fputs(usage, stdout);
    return 0;
  }
  if (a.empty() || a[0] != '-' || a == "-") {
    if (!file.empty()) return usage_error(command, "more than one file: " + std::string(a), usage);
    file = std::string(a);
    return std::nullopt;
  }
  if (i + 1 >= argc) return usage_error(command, std::string(a) + " needs a value", usage);
  option = a;
  value = argv[++i];
  return std::nullopt;
}

// "6m/min" → (6, "m/min"): a finite number, then its unit (maybe empty).
inline std::optional<std::pair<double, std::string>> parse_quantity(std::string_view s) {
  const std::string str(s);
  char* end = nullptr;
  const double v = std::strtod(str.c_str(), &end);
  if (end == str.c_str() || !std::isfinite(v)) return std::nullopt;
  return std::pair{v, std::string(end)};
}

// "12.5" → 12.5: a finite number and nothing after it ("nan", "inf", "",
// "12mm" are not numbers).
inline std::optional<double> parse_number(std::string_view s) {
  const auto q = parse_quantity(s);
  if (!q || !q->second.empty()) return std::nullopt;
  return q->first;
}

// "100,50" → (100, 50).
inline std::optional<std::pair<double, double>> parse_xy(std::string_view s) {
  const std::size_t comma = s.find(',');
  if (comma == std::string_view::npos) return std::nullopt;
  const auto x = parse_number(s.substr(0, comma));
  const auto y = parse_number(s.substr(comma + 1));
  if (!x || !y) return std::nullopt;
  return std::pair{*x, *y};
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
