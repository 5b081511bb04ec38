// The machine config's keys, one row each: the TOML table it sits in, its
// name, type, unit, allowed range, default and what it does.
//
// One table, three readers:
//   * parse_machine_config() reads a key through its row's `set` (type only:
//     a number, a whole number, true/false, a string, one of the choices);
//   * validate() checks the row's `range` against the value in the config,
//     whether it came from a file or was built in code; it is the only place
//     a range is checked;
//   * config_reference_markdown() prints the table (`lasercnc config
//     --reference`, docs/machine_config.md).
// Rows without `set` are read by their own loader (work offsets, tools,
// kinematics, pitch tables: arrays and sub-tables); they are listed so that
// the reference is complete and an unknown key is one not in this table.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "machine/machine_config.h"

namespace lcnc {

enum class KeyType : std::uint8_t {
  Number,   // integer or float
  Integer,  // a whole number (stored in 32 bits)
  Boolean,
  String,
  Strings,  // array of non-empty strings
  Numbers,  // array of numbers (rows read by their own loader)
  Table     // a sub-table (rows read by their own loader)
};

// A number's allowed range: lo … hi, lo excluded when lo_open; or_zero also
// admits 0 (the key's "off"). Unbounded (none = true) when the range depends
// on other keys and validate() checks it with them.
struct KeyRange {
  bool none = true;
  double lo = 0.0;
  double hi = 0.0;
  bool lo_open = false;
  bool or_zero = false;

  [[nodiscard]] bool contains(double v) const noexcept {
    if (none) return true;
    if (or_zero && v == 0.0) return true;
    return (lo_open ? v > lo : v >= lo) && v <= hi;
  }
};

// The value a row's `set` receives, by KeyType: double (Number, Integer),
// bool, std::string, std::vector<std::string>.
using KeyValue = std::variant<double, bool, std::string, std::vector<std::string>>;

// C is MachineConfig (tables [machine], [dda], [laser]) or AxisConfig
// ([axes.<L>], <L> one of X Y Z A B C).
template <class C>
struct ConfigKey {
  std::string_view table;  // "machine", "dda", "laser", "axes.<L>", …
  std::string_view name;
  KeyType type = KeyType::Number;
  std::string_view unit;         // of a linear axis, or the machine's
  std::string_view unit_rotary;  // of a rotary axis (axis keys), else empty
  KeyRange range{};
  // The allowed values in words, when `range` cannot say them (choices, a
  // range that depends on other keys); printed after the range.
  std::string_view allowed;
  std::string_view default_value;
  bool required = false;
  std::string_view doc;
  // Stores a value of `type`; returns what is wrong with it ("" when
  // nothing), e.g. a choice not among the allowed. Never a range check.
  std::string (*set)(C&, const KeyValue&) = nullptr;
  // The stored value as validate() checks it against `range` (numbers).
  double (*get)(const C&) = nullptr;
};

using MachineKey = ConfigKey<MachineConfig>;
using AxisKey = ConfigKey<AxisConfig>;

// Rows of [machine], [dda], [laser] and the document-only rows of
// [kinematics], [work_offsets], [tools.<N>] (in reference order).
[[nodiscard]] std::span<const MachineKey> machine_keys();
// Rows of [axes.<L>] and [axes.<L>.pitch_compensation].
[[nodiscard]] std::span<const AxisKey> axis_keys();

// The allowed range of a row in words, e.g. "> 0 … 10 mm" or
// "1 … 1e+10 mm/s³, or 0: none"; `rotary` picks the rotary unit.
template <class C>
[[nodiscard]] std::string allowed_text(const ConfigKey<C>& key, bool rotary = false);

// The whole table as Markdown: a section per TOML table, a row per key
// (key, type, unit, allowed, default, doc). docs/machine_config.md is this
// text.
[[nodiscard]] std::string config_reference_markdown();

}  // namespace lcnc
