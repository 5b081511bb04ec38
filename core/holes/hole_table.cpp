#include "holes/hole_table.h"

#include "common/quote.h"
#include "holes/hole_fields.h"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace lcnc {
namespace {

// The columns: the record's fields in table order (hole_fields.h), then the
// free shape's polygon.
constexpr std::size_t kShape = kHoleFields.size();
constexpr std::size_t kColumnCount = kShape + 1;
constexpr std::string_view kShapeName = "shape";

std::string_view column_name(std::size_t k) { return k == kShape ? kShapeName : kHoleFields[k].column; }

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
        std::size_t found = kColumnCount;
        for (std::size_t k = 0; k < kColumnCount; ++k)
          if (cells[i].text == column_name(k)) found = k;
        if (found == kColumnCount)
          return err(ErrorCode::HoleTableSyntax, cells[i].col,
                     "unknown column '" + std::string(cells[i].text) +
                         "'; expected the fields of docs/design.md §6: hole, x_mm, …, process, shape");
        if (where[found] >= 0)
          return err(ErrorCode::HoleTableSyntax, cells[i].col,
                     "column '" + std::string(column_name(found)) + "' twice");
        where[found] = static_cast<int>(i);
      }
      for (std::size_t k = 0; k < kColumnCount; ++k)
        if (where[k] < 0 && k != kShape)
          return err(ErrorCode::HoleTableSyntax, 1,
                     "the header lacks column '" + std::string(column_name(k)) + "'");
      have_header = true;
      continue;
    }
    std::size_t expected = 0;
    for (std::size_t k = 0; k < kColumnCount; ++k)
      if (where[k] >= 0) ++expected;
    if (cells.size() != expected)
      return err(
          ErrorCode::HoleTableSyntax, cells.back().col,
          std::to_string(cells.size()) + " fields; expected " + std::to_string(expected) + " as the header");
    const auto cell = [&](std::size_t k) { return cells[static_cast<std::size_t>(where[k])]; };
    HoleProcessParams p;
    for (std::size_t k = 0; k < kHoleFields.size(); ++k) {
      const HoleField& f = kHoleFields[k];
      const Cell x = cell(k);
      const std::string found = std::string(f.column) + ": found " + quote(x.text) + "; expected ";
      double v = 0.0;
      std::uint32_t n = 0;
      switch (f.type) {
        case HoleFieldType::Real:
          if (!parse_double(x.text, v)) return err(ErrorCode::HoleTableSyntax, x.col, found + "a number");
          break;
        case HoleFieldType::Count:
          if (!parse_uint(x.text, n))
            return err(ErrorCode::HoleTableSyntax, x.col, found + "a whole number ≥ 0");
          v = n;
          break;
        case HoleFieldType::Process:
          if (x.text == "0" || x.text == "helix")
            v = 0;
          else if (x.text == "1" || x.text == "circle")
            v = 1;
          else if (x.text == "2" || x.text == "free_shape")
            v = 2;
          else
            return err(ErrorCode::HoleTableSyntax, x.col, found + "0/helix, 1/circle or 2/free_shape");
          break;
      }
      f.set(p, v);
    }
    const Cell proc = cell(hole_field_by_column("process").value());
    const Cell hole = cell(0);
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
                     "shape: found " + quote(v) + "; expected radius@angle (mm@deg), separated by ';'");
        p.shape.push_back(pv);
        if (semi == std::string_view::npos) break;
        rest.remove_prefix(semi + 1);
        col += static_cast<std::uint32_t>(semi + 1);
      }
    }
    if (p.process == HoleProcessId::FreeShape && where[kShape] < 0)
      return err(ErrorCode::HoleTableSyntax, proc.col, "a free shape needs the shape column");
    if (Status s = validate(p); !s) return err(ErrorCode::HoleTableBadValue, hole.col, s.error().message);
    if (!numbers.insert(p.hole_number).second)
      return err(ErrorCode::HoleTableDuplicate, hole.col,
                 "hole " + std::to_string(p.hole_number) + " is listed twice");
    rows.push_back(std::move(p));
    if (row_lines) row_lines->push_back(line_no);
  }
  if (!have_header)
    return make_error(ErrorCode::HoleTableSyntax, "no header line; expected the fields of docs/design.md §6",
                      file, 1, 1);
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
  for (std::size_t k = 0; k < kColumnCount; ++k) {
    if (k > 0) out += ',';
    out += column_name(k);
  }
  out += '\n';
  for (const HoleProcessParams& p : rows) {
    for (const HoleField& f : kHoleFields) out += hole_field_text(f, f.get(p)) + ',';
    for (std::size_t i = 0; i < p.shape.size(); ++i) {
      if (i > 0) out += ';';
      out += shortest_number_text(p.shape[i].radius_mm) + '@' + shortest_number_text(p.shape[i].angle_deg);
    }
    out += '\n';
  }
  return out;
}

}  // namespace lcnc
