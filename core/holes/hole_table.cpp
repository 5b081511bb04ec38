#include "holes/hole_table.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

namespace lcnc {
namespace {

enum Column : int {
  kHole, kX, kY, kZ, kA, kC, kFeed, kLayerFeed, kLayers, kDepth, kPower, kStartR, kEndR, kTurns,
  kScanSpeed, kWedge, kOffset, kProcess, kShape, kColumnCount
};
constexpr std::array<const char*, kColumnCount> kNames = {
    "hole", "x_mm", "y_mm", "z_mm", "a_deg", "c_deg", "feed_mm_min", "layer_feed_mm", "layer_count",
    "total_depth_mm", "power_pct", "start_radius_mm", "end_radius_mm", "radius_turns",
    "scan_speed_mm_s", "wedge_speed_rpm", "beam_offset_mm", "process", "shape"};

struct Cell {
  std::string_view text;
  std::uint32_t col = 1;  // 1-based column of its first character
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<Cell> split(std::string_view line) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    const std::string_view raw = line.substr(start, comma == std::string_view::npos ? comma : comma - start);
    std::size_t lead = 0;
    while (lead < raw.size() && (raw[lead] == ' ' || raw[lead] == '\t')) ++lead;
    cells.push_back(Cell{trim(raw), static_cast<std::uint32_t>(start + lead + 1)});
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

bool parse_double(std::string_view t, double& out) {
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(out);
}

bool parse_uint(std::string_view t, std::uint32_t& out) {
  if (t.empty()) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  // the shortest that reads back exactly, for people
  for (int prec = 1; prec < 17; ++prec) {
    char t[40];
    std::snprintf(t, sizeof t, "%.*g", prec, v);
    if (std::strtod(t, nullptr) == v) return t;
  }
  return b;
}

}  // namespace

Result<std::vector<HoleProcessParams>> parse_hole_table(std::string_view text, const std::string& file,
                                                        std::vector<std::uint32_t>* row_lines) {
  if (row_lines) row_lines->clear();
  std::array<int, kColumnCount> where{};  // column index of each field, −1 absent
  where.fill(-1);
  bool have_header = false;
  std::vector<HoleProcessParams> rows;
  std::set<std::uint32_t> numbers;
  std::uint32_t line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? nl : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    if (line_no == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 BOM
    const std::string_view t = trim(line);
    if (t.empty() || t.front() == '#') continue;
    const std::vector<Cell> cells = split(line);
    const auto err = [&](ErrorCode code, std::uint32_t col, const std::string& msg) {
      return make_error(code, msg, file, line_no, col);
    };
    if (!have_header) {
      for (std::size_t i = 0; i < cells.size(); ++i) {
        int found = -1;
        for (int k = 0; k < kColumnCount; ++k)
          if (cells[i].text == kNames[k]) found = k;
        if (found < 0)
          return err(ErrorCode::HoleTableSyntax, cells[i].col,
                     "unknown column '" + std::string(cells[i].text) + "'; expected the fields of DESIGN §6: hole, x_mm, …, process, shape");
        if (where[found] >= 0)
          return err(ErrorCode::HoleTableSyntax, cells[i].col, "column '" + std::string(kNames[found]) + "' twice");
        where[found] = static_cast<int>(i);
      }
      for (int k = 0; k < kColumnCount; ++k)
        if (where[k] < 0 && k != kShape)
          return err(ErrorCode::HoleTableSyntax, 1, std::string("the header lacks column '") + kNames[k] + "'");
      have_header = true;
      continue;
    }
    std::size_t expected = 0;
    for (int k = 0; k < kColumnCount; ++k)
      if (where[k] >= 0) ++expected;
    if (cells.size() != expected)
      return err(ErrorCode::HoleTableSyntax, cells.back().col,
                 std::to_string(cells.size()) + " fields; expected " + std::to_string(expected) + " as the header");
    const auto cell = [&](Column c) { return cells[static_cast<std::size_t>(where[c])]; };
    HoleProcessParams p;
    const auto number = [&](Column c, double& out) -> Status {
      const Cell x = cell(c);
      if (!parse_double(x.text, out))
        return err(ErrorCode::HoleTableSyntax, x.col,
                   std::string(kNames[c]) + ": found '" + std::string(x.text) + "'; expected a number");
      return {};
    };
    const auto count = [&](Column c, std::uint32_t& out) -> Status {
      const Cell x = cell(c);
      if (!parse_uint(x.text, out))
        return err(ErrorCode::HoleTableSyntax, x.col,
                   std::string(kNames[c]) + ": found '" + std::string(x.text) + "'; expected a whole number ≥ 0");
      return {};
    };
    double a = 0, c = 0;
    const std::pair<Column, double*> numbers_of[] = {
        {kX, &p.position[0]}, {kY, &p.position[1]}, {kZ, &p.position[2]}, {kA, &a}, {kC, &c},
        {kFeed, &p.feed_mm_min}, {kLayerFeed, &p.layer_feed_mm}, {kDepth, &p.total_depth_mm},
        {kPower, &p.power_pct}, {kStartR, &p.head.start_radius_mm}, {kEndR, &p.head.end_radius_mm},
        {kScanSpeed, &p.head.scan_speed_mm_s}, {kWedge, &p.head.wedge_speed_rpm},
        {kOffset, &p.head.beam_offset_mm}};
    if (Status s = count(kHole, p.hole_number); !s) return s.error();
    for (const auto& [col, out] : numbers_of)
      if (Status s = number(col, *out); !s) return s.error();
    p.position[3] = a;
    p.position[5] = c;
    if (Status s = count(kLayers, p.layer_count); !s) return s.error();
    if (Status s = count(kTurns, p.head.radius_turns); !s) return s.error();
    const Cell proc = cell(kProcess);
    if (proc.text == "0" || proc.text == "helix") p.process = HoleProcessId::Helix;
    else if (proc.text == "1" || proc.text == "circle") p.process = HoleProcessId::Circle;
    else if (proc.text == "2" || proc.text == "free_shape") p.process = HoleProcessId::FreeShape;
    else
      return err(ErrorCode::HoleTableSyntax, proc.col,
                 "process: found '" + std::string(proc.text) + "'; expected 0/helix, 1/circle or 2/free_shape");
    if (where[kShape] >= 0) {
      const Cell sh = cell(kShape);
      std::string_view rest = sh.text;
      std::uint32_t col = sh.col;
      while (!rest.empty()) {
        const std::size_t semi = rest.find(';');
        const std::string_view v = rest.substr(0, semi);
        const std::size_t at = v.find('@');
        PolarVertex pv;
        if (at == std::string_view::npos || !parse_double(trim(v.substr(0, at)), pv.radius_mm) ||
            !parse_double(trim(v.substr(at + 1)), pv.angle_deg))
          return err(ErrorCode::HoleTableSyntax, col,
                     "shape: found '" + std::string(v) + "'; expected radius@angle (mm@deg), separated by ';'");
        p.shape.push_back(pv);
        if (semi == std::string_view::npos) break;
        rest.remove_prefix(semi + 1);
        col += static_cast<std::uint32_t>(semi + 1);
      }
    }
    if (p.process == HoleProcessId::FreeShape && where[kShape] < 0)
      return err(ErrorCode::HoleTableSyntax, proc.col, "a free shape needs the shape column");
    if (Status s = validate(p); !s)
      return err(ErrorCode::HoleTableBadValue, cell(kHole).col, s.error().message);
    if (!numbers.insert(p.hole_number).second)
      return err(ErrorCode::HoleTableDuplicate, cell(kHole).col,
                 "hole " + std::to_string(p.hole_number) + " is listed twice");
    rows.push_back(std::move(p));
    if (row_lines) row_lines->push_back(line_no);
  }
  if (!have_header)
    return make_error(ErrorCode::HoleTableSyntax, "no header line; expected the fields of DESIGN §6", file, 1, 1);
  return rows;
}

Result<std::vector<HoleProcessParams>> read_hole_table(const std::string& path,
                                                       std::vector<std::uint32_t>* row_lines) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::FileNotFound, "cannot read hole table '" + path + "'", path);
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_hole_table(ss.str(), path, row_lines);
}

std::string write_hole_table(const std::vector<HoleProcessParams>& rows) {
  std::string out;
  for (int k = 0; k < kColumnCount; ++k) {
    if (k > 0) out += ',';
    out += kNames[k];
  }
  out += '\n';
  for (const HoleProcessParams& p : rows) {
    const double fields[] = {p.position[0], p.position[1], p.position[2], p.position[3], p.position[5],
                             p.feed_mm_min, p.layer_feed_mm};
    out += std::to_string(p.hole_number);
    for (double f : fields) out += ',' + num(f);
    out += ',' + std::to_string(p.layer_count) + ',' + num(p.total_depth_mm) + ',' + num(p.power_pct) +
           ',' + num(p.head.start_radius_mm) + ',' + num(p.head.end_radius_mm) + ',' +
           std::to_string(p.head.radius_turns) + ',' + num(p.head.scan_speed_mm_s) + ',' +
           num(p.head.wedge_speed_rpm) + ',' + num(p.head.beam_offset_mm) + ',' +
           std::to_string(static_cast<int>(p.process)) + ',';
    for (std::size_t i = 0; i < p.shape.size(); ++i) {
      if (i > 0) out += ';';
      out += num(p.shape[i].radius_mm) + '@' + num(p.shape[i].angle_deg);
    }
    out += '\n';
  }
  return out;
}

}  // namespace lcnc
