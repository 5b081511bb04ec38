#include "gcode/parameter_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "common/output_file.h"
#include "common/quote.h"

namespace lcnc::gcode {
namespace {

Diagnostic bad(const std::string& path, std::uint32_t line, std::uint32_t col, std::string msg) {
  return make_error(ErrorCode::ParameterFileBad, std::move(msg), path, line, col);
}

// A number at s[i] (strtod's syntax, finite); i moves past it.
bool number(std::string_view s, std::size_t& i, double& out) {
  const std::string tail(s.substr(i));
  char* end = nullptr;
  errno = 0;
  out = std::strtod(tail.c_str(), &end);
  if (end == tail.c_str() || errno == ERANGE || !std::isfinite(out)) return false;
  i += static_cast<std::size_t>(end - tail.c_str());
  return true;
}

void skip_blanks(std::string_view s, std::size_t& i) {
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
}

// "T<n> X<x> Y<y> Z<z> D<d> ;description"; P and other LinuxCNC tool-table
// letters (A B C U V W I J Q) are read and dropped when 0.
Status tool_line(std::string_view s, const std::string& path, std::uint32_t line,
                 std::vector<ToolConfig>& tools) {
  ToolConfig t;
  std::size_t i = 0;
  bool have_number = false;
  for (;;) {
    skip_blanks(s, i);
    if (i >= s.size()) break;
    if (s[i] == ';') {
      std::string_view d = s.substr(i + 1);
      while (!d.empty() && (d.back() == '\r' || d.back() == ' ')) d.remove_suffix(1);
      t.description = std::string(d);
      break;
    }
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(s[i])));
    const std::size_t at = i++;
    double v = 0.0;
    if (!number(s, i, v))
      return bad(path, line, static_cast<std::uint32_t>(at + 1),
                 "found " + quote(s.substr(at, 1)) +
                     " with no number after it; expected tool words "
                     "T<n> X<mm> Y<mm> Z<mm> D<mm> and a ;description");
    switch (letter) {
      case 'T':
        if (v != std::floor(v) || v < 1 || v > kMaxToolNumber)
          return bad(path, line, static_cast<std::uint32_t>(at + 1),
                     "tool number " + std::string(s.substr(at + 1, i - at - 1)) +
                         "; expected a whole number from 1 to " + std::to_string(kMaxToolNumber));
        t.number = static_cast<int>(v);
        have_number = true;
        break;
      case 'X': t.offset[0] = v; break;
      case 'Y': t.offset[1] = v; break;
      case 'Z': t.offset[2] = v; break;
      case 'D': t.diameter_mm = v; break;
      case 'P': break;  // pocket: no tool changer here
      default:
        if (v != 0.0)
          return bad(path, line, static_cast<std::uint32_t>(at + 1),
                     "found " + quote(s.substr(at, 1)) + " in a tool line; expected T X Y Z D");
    }
  }
  if (!have_number) return bad(path, line, 1, "a tool line without T<n>");
  for (int k = 0; k < 3; ++k) {
    if (std::fabs(t.offset[k]) > kMaxToolOffsetMm)
      return bad(path, line, 1,
                 "tool " + std::to_string(t.number) + " offset beyond ±" +
                     std::to_string(static_cast<int>(kMaxToolOffsetMm)) + " mm");
  }
  tools.push_back(std::move(t));
  return {};
}

}  // namespace

Result<ParameterFileData> read_parameter_file(const std::string& path) {
  ParameterFileData data;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (!std::filesystem::exists(path)) return data;  // no job has saved one yet
    return bad(path, 0, 0, "cannot read the parameter file: " + std::string(std::strerror(errno)));
  }
  std::string text;
  std::uint32_t line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::string_view s(text);
    std::size_t i = 0;
    skip_blanks(s, i);
    if (i >= s.size() || s[i] == ';' || s[i] == '#') continue;  // blank or a comment
    if (s[i] == 'T' || s[i] == 't') {
      if (Status st = tool_line(s.substr(i), path, line, data.tools); !st) return st.error();
      continue;
    }
    const std::size_t at = i;
    double index = 0.0, value = 0.0;
    if (!number(s, i, index) || index != std::floor(index) || index < kParamPersistentFirst ||
        index > kParamPersistentLast)
      return bad(path, line, static_cast<std::uint32_t>(at + 1),
                 "found " + quote(s.substr(at), 24) +
                     "; expected '<parameter> <value>' "
                     "with a parameter from " +
                     std::to_string(kParamPersistentFirst) + " to " + std::to_string(kParamPersistentLast) +
                     ", or a tool line 'T<n> Z<mm> …'");
    skip_blanks(s, i);
    const std::size_t vat = i;
    if (!number(s, i, value)) {
      std::size_t end = vat;
      while (end < s.size() && s[end] != ' ' && s[end] != '\t' && s[end] != '\r') ++end;
      const std::string p = "parameter " + std::to_string(static_cast<int>(index));
      if (end == vat)
        return bad(path, line, static_cast<std::uint32_t>(vat + 1),
                   p + " with no value; expected a finite number after it");
      return bad(path, line, static_cast<std::uint32_t>(vat + 1),
                 "found " + quote(s.substr(vat, end - vat), 24) + " as the value of " + p + ": " +
                     (std::isdigit(static_cast<unsigned char>(s[vat])) || s[vat] == '-' || s[vat] == '+' ||
                              s[vat] == '.'
                          ? "not a finite number (beyond the largest, about 1.8e308)"
                          : "not a number") +
                     "; expected a finite number such as 12.5 or -3e-2");
    }
    skip_blanks(s, i);
    if (i < s.size())
      return bad(path, line, static_cast<std::uint32_t>(i + 1),
                 "found " + quote(s.substr(i), 24) +
                     " after the value; expected the "
                     "line's end");
    data.params.emplace_back(static_cast<int>(index), value);
  }
  return data;
}

Status write_parameter_file(const std::string& path, const std::vector<double>& numbered,
                            const std::vector<ToolConfig>& tools) {
  std::ostringstream out;
  out.precision(17);
  for (int k = kParamPersistentFirst; k <= kParamPersistentLast; ++k)
    out << k << '\t' << numbered[static_cast<std::size_t>(k)] << '\n';
  for (const ToolConfig& t : tools) {
    out << 'T' << t.number << " X" << t.offset[0] << " Y" << t.offset[1] << " Z" << t.offset[2] << " D"
        << t.diameter_mm;
    if (!t.description.empty()) out << " ;" << t.description;
    out << '\n';
  }
  // through the one door for outputs: replaced whole (synced, renamed over
  // it), or left as it was
  const std::string text = out.str();
  if (Status s = write_output(path, {}, [&text](std::ostream& o) { o << text; }); !s)
    return bad(path, 0, 0, "cannot write it: " + s.error().message);
  return {};
}

}  // namespace lcnc::gcode
