#include "drivers/modbus/register_bank.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace lcnc::drivers {

RegisterBank::RegisterBank(DeviceMap map) : map_(std::move(map)) {
  bits_[0].assign(map_.table_size(Table::Coil), 0);
  bits_[1].assign(map_.table_size(Table::Discrete), 0);
  words_[0].assign(map_.table_size(Table::Holding), 0);
  words_[1].assign(map_.table_size(Table::Input), 0);
  for (const RegisterDef& r : map_.registers) set_clamped(r, 0.0);
}

std::vector<std::uint8_t>& RegisterBank::bits(Table t) noexcept { return bits_[t == Table::Coil ? 0 : 1]; }

std::vector<std::uint16_t>& RegisterBank::words(Table t) noexcept {
  return words_[t == Table::Holding ? 0 : 1];
}

double RegisterBank::value(const RegisterDef& r) const noexcept {
  if (is_bit_table(r.table)) return bits_[r.table == Table::Coil ? 0 : 1][r.address] ? 1.0 : 0.0;
  const auto& w = words_[r.table == Table::Holding ? 0 : 1];
  return r.decode(std::span<const std::uint16_t>(w.data() + r.address, r.words()));
}

Status RegisterBank::set(const RegisterDef& r, double v) {
  std::uint16_t raw[2] = {0, 0};
  if (Status s = r.encode(v, std::span<std::uint16_t>(raw, r.words())); !s)
    return make_error(s.error().code, map_.name + "." + s.error().message);
  if (is_bit_table(r.table)) {
    bits(r.table)[r.address] = static_cast<std::uint8_t>(raw[0]);
  } else {
    auto& w = words(r.table);
    std::copy(raw, raw + r.words(), w.begin() + r.address);
  }
  return {};
}

void RegisterBank::set_clamped(const RegisterDef& r, double v) noexcept {
  (void)set(r, std::clamp(v, r.min, r.max));  // in range by construction
}

Result<double> RegisterBank::get(std::string_view name) const {
  auto r = map_.lookup(name);
  if (!r) return r.error();
  return value(*r.value());
}

Status RegisterBank::set(std::string_view name, double v) {
  auto r = map_.lookup(name);
  if (!r) return r.error();
  return set(*r.value(), v);
}

const RegisterDef& RegisterBank::def(std::string_view name) const {
  const RegisterDef* r = map_.find(name);
  if (r == nullptr) {
    std::fprintf(stderr, "internal error: register map device '%s' lacks register '%.*s'\n",
                 map_.name.c_str(), static_cast<int>(name.size()), name.data());
    std::abort();
  }
  return *r;
}

}  // namespace lcnc::drivers
