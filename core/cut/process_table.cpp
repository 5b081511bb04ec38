#include "cut/process_table.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace lcnc::cut {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> f;
  for (std::size_t at = 0;;) {
    const std::size_t comma = line.find(',', at);
    f.push_back(trim(line.substr(at, comma == std::string_view::npos ? comma : comma - at)));
    if (comma == std::string_view::npos) return f;
    at = comma + 1;
  }
}

std::string num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

std::string check_process(const Process& p) {
  if (!std::isfinite(p.feed_mm_min) || !(p.feed_mm_min > 0.0))
    return "feed " + num(p.feed_mm_min) + " mm/min; expected more than 0";
  if (!std::isfinite(p.power_pct) || !(p.power_pct >= 0.0 && p.power_pct <= 100.0))
    return "power " + num(p.power_pct) + " %; expected 0 to 100";
  if (!std::isfinite(p.pierce_s) || !(p.pierce_s >= 0.0))
    return "pierce time " + num(p.pierce_s) + " s; expected 0 or more";
  if (!std::isfinite(p.kerf_mm) || !(p.kerf_mm >= 0.0))
    return "kerf " + num(p.kerf_mm) + " mm; expected 0 or more";
  return {};
}

Result<ProcessTable> parse_process_table(std::string_view text, const std::string& file,
                                         const Process& defaults) {
  static constexpr const char* kColumns[] = {"layer", "feed_mm_min", "power_pct", "pierce_s", "kerf_mm"};
  ProcessTable t;
  t.defaults = defaults;
  std::uint32_t line_no = 0;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t nl = text.find('\n', at);
    const std::string_view line =
        trim(text.substr(at, nl == std::string_view::npos ? std::string_view::npos : nl - at));
    at = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    auto fail = [&](const std::string& msg) {
      return make_error(ErrorCode::ProcessTableSyntax, msg, file, line_no);
    };
    const std::vector<std::string_view> f = split(line);
    if (f[0] == "layer") continue;  // the header
    if (f.size() != 5) {
      return fail(std::to_string(f.size()) +
                  " fields; expected 5: layer,feed_mm_min,power_pct,"
                  "pierce_s,kerf_mm");
    }
    if (f[0].empty()) return fail("empty layer name; expected the DXF layer's name");
    if (t.layers.count(f[0]) != 0)
      return fail("layer '" + std::string(f[0]) + "' listed twice; expected each layer once");
    Process p = defaults;
    double* slot[] = {nullptr, &p.feed_mm_min, &p.power_pct, &p.pierce_s, &p.kerf_mm};
    for (std::size_t k = 1; k < 5; ++k) {
      if (f[k].empty()) continue;
      const std::string s(f[k]);
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      if (end == s.c_str() || *end != '\0')
        return fail(std::string(kColumns[k]) + " '" + s + "'; expected a number");
      *slot[k] = v;
    }
    if (const std::string bad = check_process(p); !bad.empty())
      return fail("layer '" + std::string(f[0]) + "': " + bad);
    t.layers.emplace(std::string(f[0]), p);
  }
  return t;
}

Result<ProcessTable> read_process_table(const std::string& path, const Process& defaults) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::FileNotFound, "cannot open the process table", path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_process_table(text.str(), path, defaults);
}

}  // namespace lcnc::cut
