// The hole record's field table; described in hole_fields.h.
#include "holes/hole_fields.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace lcnc {

std::optional<std::size_t> hole_field_by_column(std::string_view column) noexcept {
  for (std::size_t i = 0; i < kHoleFields.size(); ++i)
    if (kHoleFields[i].column == column) return i;
  return std::nullopt;
}

std::optional<std::size_t> hole_field_by_register(std::string_view name) noexcept {
  for (std::size_t i = 0; i < kHoleFields.size(); ++i)
    if (kHoleFields[i].register_name == name) return i;
  return std::nullopt;
}

bool hole_field_in_range(const HoleField& f, double v) noexcept {
  return std::isfinite(v) && (f.lo_open ? v > f.lo : v >= f.lo) && v <= f.hi;
}

std::string hole_field_text(const HoleField& f, double v) {
  if (f.type != HoleFieldType::Real && std::isfinite(v) && v == std::trunc(v)) {
    char b[40];
    std::snprintf(b, sizeof b, "%.0f", v);
    return b;
  }
  return shortest_number_text(v);
}

std::string shortest_number_text(double v) {
  char b[40];
  for (int prec = 1; prec < 17; ++prec) {
    std::snprintf(b, sizeof b, "%.*g", prec, v);
    if (std::strtod(b, nullptr) == v) return b;
  }
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string hole_field_range_message(const HoleField& f, double v) {
  // Six significant digits, as people read them (the field's own text for
  // the whole numbers).
  const auto text = [&](double x) {
    if (f.type != HoleFieldType::Real) return hole_field_text(f, x);
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", x);
    return std::string(b);
  };
  const std::string unit = f.unit.empty() ? std::string() : " " + std::string(f.unit);
  std::string m = "field " + std::to_string(f.number) + " " + std::string(f.label) + " = " + text(v) + unit +
                  "; allowed " + (f.lo_open ? "> " : "") + text(f.lo) + " … " + text(f.hi) + unit;
  if (f.type == HoleFieldType::Process) m += " (" + std::string(f.doc) + ")";
  return m;
}

std::vector<std::pair<std::string, double>> scan_head_block(const ScanHeadParams& head) {
  HoleProcessParams p;
  p.head = head;
  std::vector<std::pair<std::string, double>> out;
  for (const HoleField& f : kHoleFields)
    if (f.number >= 12 && f.number <= 17) out.emplace_back(std::string(f.column), f.get(p));
  return out;
}

}  // namespace lcnc
