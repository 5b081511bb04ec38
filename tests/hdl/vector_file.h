// The shared increment vectors of the C++ ↔ VHDL co-verification
// (tests/vectors/README.md): one period per line, "D n0 n1 …" — the clock
// divider of the period and the signed increment of each axis (sign =
// direction) — '#' lines are comments, and the one "#!" line names the
// interpolator's generics as key=value pairs (axes, mag_width, capacity and
// the timing generics the GHDL run takes).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace lcnc::hdl_test {

struct VectorPeriod {
  std::int64_t divider = 0;
  std::vector<std::int64_t> steps;  // one per axis
  int line = 0;                     // in the file, 1-based
};

struct VectorFile {
  std::map<std::string, std::string> generics;         // from the "#!" line
  std::int64_t axes = 0, mag_width = 0, capacity = 0;  // the DDA preset among them
  std::vector<VectorPeriod> periods;
};

// Reads and checks a vector file; on error prints file:line: message and
// returns false.
inline bool read_vector_file(const std::string& path, VectorFile& out) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "%s: cannot read\n", path.c_str());
    return false;
  }
  std::string text;
  int line_no = 0;
  bool have_header = false;
  while (std::getline(in, text)) {
    ++line_no;
    if (text.rfind("#!", 0) == 0) {
      std::istringstream ss(text.substr(2));
      std::string kv;
      while (ss >> kv) {
        const auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) {
          std::fprintf(stderr, "%s:%d: expected key=value in the #! line, found '%s'\n", path.c_str(),
                       line_no, kv.c_str());
          return false;
        }
        out.generics[kv.substr(0, eq)] = kv.substr(eq + 1);
      }
      have_header = true;
      continue;
    }
    if (text.empty() || text[0] == '#') continue;
    if (!have_header) {
      std::fprintf(stderr, "%s:%d: data before the #! line of generics\n", path.c_str(), line_no);
      return false;
    }
    std::istringstream ss(text);
    VectorPeriod p;
    p.line = line_no;
    if (!(ss >> p.divider) || p.divider < 1) {
      std::fprintf(stderr, "%s:%d: expected the divider (>= 1) first\n", path.c_str(), line_no);
      return false;
    }
    std::int64_t v = 0;
    while (ss >> v) p.steps.push_back(v);
    if (!ss.eof()) {
      std::fprintf(stderr, "%s:%d: expected integers only\n", path.c_str(), line_no);
      return false;
    }
    out.periods.push_back(std::move(p));
  }
  for (auto [key, value] : {std::pair{"axes", &out.axes}, std::pair{"mag_width", &out.mag_width},
                            std::pair{"capacity", &out.capacity}}) {
    const auto it = out.generics.find(key);
    char* end = nullptr;
    if (it != out.generics.end()) *value = std::strtoll(it->second.c_str(), &end, 10);
    if (it == out.generics.end() || it->second.empty() || *end != '\0' || *value < 1 ||
        (*value > 30 && std::string(key) == "mag_width")) {
      std::fprintf(stderr, "%s: the #! line needs %s= a positive integer\n", path.c_str(), key);
      return false;
    }
  }
  const std::int64_t axes = out.axes;
  const std::int64_t max_n = (std::int64_t{1} << out.mag_width) - 1;
  for (const VectorPeriod& p : out.periods) {
    if (static_cast<std::int64_t>(p.steps.size()) > axes) {
      std::fprintf(stderr, "%s:%d: %zu increments for %lld axes\n", path.c_str(), p.line, p.steps.size(),
                   static_cast<long long>(axes));
      return false;
    }
    for (std::int64_t s : p.steps) {
      if (s > max_n || s < -max_n) {
        std::fprintf(stderr, "%s:%d: increment %lld outside ±%lld (mag_width)\n", path.c_str(), p.line,
                     static_cast<long long>(s), static_cast<long long>(max_n));
        return false;
      }
    }
  }
  return true;
}

}  // namespace lcnc::hdl_test
