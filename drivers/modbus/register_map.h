// The Modbus register map (share/modbus/register_map.toml): the single source
// of truth for both sides (docs/design.md §8). The master's typed accessors, the
// CNC's slave and the virtual devices all look registers up here by name;
// no address is written in code.
//
// A register holds one value in an engineering unit; on the wire it is
//   raw = round(value · scale)      value = raw / scale
// as bool (one bit), u16/i16 (one word) or u32/i32 (two words, high word
// first, "ABCD"). A value is valid when min ≤ value ≤ max and raw fits the
// type. Loading validates the whole file and names file:line:col, the device
// and the entry in every error; nothing half-valid is returned.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/result.h"

namespace lcnc::drivers {

// The four Modbus data tables.
enum class Table : std::uint8_t { Coil, Discrete, Holding, Input };
inline constexpr std::size_t kTableCount = 4;

enum class ValueType : std::uint8_t { Bool, U16, I16, U32, I32 };
enum class Access : std::uint8_t { Read, ReadWrite };

[[nodiscard]] std::string_view table_name(Table t) noexcept;  // "holding"
// A value for messages: shortest form, up to 10 significant digits ("12.5").
[[nodiscard]] std::string format_number(double v);
[[nodiscard]] std::string_view type_name(ValueType t) noexcept;  // "u32"
// Coils and discrete inputs hold bits; holding and input registers words.
[[nodiscard]] constexpr bool is_bit_table(Table t) noexcept {
  return t == Table::Coil || t == Table::Discrete;
}
// Words (or bits) a value of this type occupies: 1, or 2 for u32/i32.
[[nodiscard]] constexpr std::uint16_t word_count(ValueType t) noexcept {
  return (t == ValueType::U32 || t == ValueType::I32) ? 2 : 1;
}

struct RegisterDef {
  std::string name;
  Table table = Table::Holding;
  std::uint16_t address = 0;
  ValueType type = ValueType::U16;
  std::string unit;
  double scale = 1.0;
  double min = 0.0;
  double max = 0.0;
  Access access = Access::Read;
  std::string doc;
  std::uint32_t line = 0;  // in the map file, for messages

  [[nodiscard]] std::uint16_t words() const noexcept { return word_count(type); }
  [[nodiscard]] bool writable() const noexcept { return access == Access::ReadWrite; }
  [[nodiscard]] bool in_range(double value) const noexcept { return value >= min && value <= max; }
  // value → raw words (1 or 2, high word first) in `out`. Fails with
  // PeripheralValueOutOfRange naming the register, value and range.
  [[nodiscard]] Status encode(double value, std::span<std::uint16_t> out) const;
  // raw words (1 or 2) → value. Never fails: the range check is the caller's.
  [[nodiscard]] double decode(std::span<const std::uint16_t> raw) const noexcept;
  // "laser_source.power_setpoint_pct (holding 0, 0…100 %)"
  [[nodiscard]] std::string describe(std::string_view device) const;
};

struct DeviceMap {
  std::string name;
  std::uint8_t unit_id = 1;
  std::string doc;
  std::vector<RegisterDef> registers;

  [[nodiscard]] const RegisterDef* find(std::string_view reg_name) const noexcept;
  // The register that holds `address` of table `t` (either word of a 32-bit
  // one), or nullptr when nothing is mapped there.
  [[nodiscard]] const RegisterDef* at(Table t, std::uint16_t address) const noexcept;
  // One past the highest mapped address of table `t` (0 when empty).
  [[nodiscard]] std::uint16_t table_size(Table t) const noexcept;
  // Like find(), but an error naming the device and the register when absent.
  [[nodiscard]] Result<const RegisterDef*> lookup(std::string_view reg_name) const;
};

struct RegisterMap {
  std::string file;  // where it was loaded from
  std::vector<DeviceMap> devices;

  [[nodiscard]] const DeviceMap* device(std::string_view name) const noexcept;
  [[nodiscard]] Result<DeviceMap> device_copy(std::string_view name) const;
};

// The shipped map: share/modbus/register_map.toml of the source tree.
[[nodiscard]] std::string default_register_map_path();
[[nodiscard]] Result<RegisterMap> load_register_map(const std::string& path);
// `file_name` is only used in messages.
[[nodiscard]] Result<RegisterMap> parse_register_map(std::string_view toml_text, std::string_view file_name);
// One device of the shipped map (loaded once, thread-safe), or the error of
// loading it / of a device name it does not have.
[[nodiscard]] Result<DeviceMap> shipped_device(std::string_view name);

}  // namespace lcnc::drivers
