// Register map loading (TOML through toml++) and validation, and the value ↔
// raw conversion. Every error names file:line:col, the device and the entry
// (by name, or by index while the name is unknown) and what was expected.
#include "drivers/modbus/register_map.h"

#include "common/share_path.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>

#include <toml++/toml.h>

namespace lcnc::drivers {

std::string_view table_name(Table t) noexcept {
  switch (t) {
    case Table::Coil: return "coil";
    case Table::Discrete: return "discrete";
    case Table::Holding: return "holding";
    case Table::Input: return "input";
  }
  return "?";
}

std::string_view type_name(ValueType t) noexcept {
  switch (t) {
    case ValueType::Bool: return "bool";
    case ValueType::U16: return "u16";
    case ValueType::I16: return "i16";
    case ValueType::U32: return "u32";
    case ValueType::I32: return "i32";
  }
  return "?";
}

namespace {

// The raw integer range a type can carry.
struct RawRange {
  double lo, hi;
};
constexpr RawRange raw_range(ValueType t) noexcept {
  switch (t) {
    case ValueType::Bool: return {0, 1};
    case ValueType::U16: return {0, 65535};
    case ValueType::I16: return {-32768, 32767};
    case ValueType::U32: return {0, 4294967295.0};
    case ValueType::I32: return {-2147483648.0, 2147483647.0};
  }
  return {0, 0};
}

std::string fmt(double v) { return format_number(v); }

}  // namespace

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

Status RegisterDef::encode(double value, std::span<std::uint16_t> out) const {
  if (!std::isfinite(value) || !in_range(value))
    return make_error(
        ErrorCode::PeripheralValueOutOfRange,
        name + " = " + fmt(value) + " " + unit + " is outside " + fmt(min) + " … " + fmt(max) + " " + unit);
  if (type == ValueType::Bool) {
    out[0] = value != 0.0 ? 1 : 0;
    return {};
  }
  const double raw_d = std::round(value * scale);
  const RawRange r = raw_range(type);
  if (raw_d < r.lo || raw_d > r.hi)  // only a map with an inconsistent range gets here
    return make_error(ErrorCode::PeripheralValueOutOfRange,
                      name + " = " + fmt(value) + " does not fit a " + std::string(type_name(type)));
  const auto raw = static_cast<std::int64_t>(raw_d);
  const auto bits = static_cast<std::uint32_t>(raw);  // two's complement for i16/i32
  if (words() == 2) {
    out[0] = static_cast<std::uint16_t>(bits >> 16);
    out[1] = static_cast<std::uint16_t>(bits & 0xFFFFu);
  } else {
    out[0] = static_cast<std::uint16_t>(bits & 0xFFFFu);
  }
  return {};
}

double RegisterDef::decode(std::span<const std::uint16_t> raw) const noexcept {
  switch (type) {
    case ValueType::Bool: return raw[0] != 0 ? 1.0 : 0.0;
    case ValueType::U16: return raw[0] / scale;
    case ValueType::I16: return static_cast<std::int16_t>(raw[0]) / scale;
    case ValueType::U32: return ((static_cast<std::uint32_t>(raw[0]) << 16) | raw[1]) / scale;
    case ValueType::I32:
      return static_cast<std::int32_t>((static_cast<std::uint32_t>(raw[0]) << 16) | raw[1]) / scale;
  }
  return 0.0;
}

std::string RegisterDef::describe(std::string_view device) const {
  std::string s = std::string(device) + "." + name + " (" + std::string(table_name(table)) + " " +
                  std::to_string(address);
  if (type != ValueType::Bool) s += ", " + fmt(min) + " … " + fmt(max) + (unit.empty() ? "" : " " + unit);
  return s + ")";
}

const RegisterDef* DeviceMap::find(std::string_view reg_name) const noexcept {
  for (const RegisterDef& r : registers)
    if (r.name == reg_name) return &r;
  return nullptr;
}

const RegisterDef* DeviceMap::at(Table t, std::uint16_t address) const noexcept {
  for (const RegisterDef& r : registers)
    if (r.table == t && address >= r.address && address < r.address + r.words()) return &r;
  return nullptr;
}

std::uint16_t DeviceMap::table_size(Table t) const noexcept {
  std::uint32_t n = 0;
  for (const RegisterDef& r : registers)
    if (r.table == t) n = std::max<std::uint32_t>(n, r.address + r.words());
  return static_cast<std::uint16_t>(std::min<std::uint32_t>(n, 65535));
}

Result<const RegisterDef*> DeviceMap::lookup(std::string_view reg_name) const {
  if (const RegisterDef* r = find(reg_name)) return r;
  std::string names;
  for (const RegisterDef& r : registers) names += (names.empty() ? "" : ", ") + r.name;
  return make_error(ErrorCode::PeripheralUnknownRegister, "device '" + name + "' has no register '" +
                                                              std::string(reg_name) + "'; it has: " + names);
}

const DeviceMap* RegisterMap::device(std::string_view name) const noexcept {
  for (const DeviceMap& d : devices)
    if (d.name == name) return &d;
  return nullptr;
}

Result<DeviceMap> RegisterMap::device_copy(std::string_view name) const {
  if (const DeviceMap* d = device(name)) return *d;
  std::string names;
  for (const DeviceMap& d : devices) names += (names.empty() ? "" : ", ") + d.name;
  return make_error(ErrorCode::PeripheralUnknownRegister,
                    "register map " + file + " has no device '" + std::string(name) + "'; it has: " + names);
}

namespace {

constexpr std::uint32_t kMapVersion = 1;

struct MapLoader {
  std::string file;
  Diagnostic err;
  bool failed = false;

  bool fail(const toml::source_region& where, std::string msg) {
    if (!failed) {
      failed = true;
      err = make_error(ErrorCode::RegisterMapInvalid, std::move(msg), file, where.begin.line,
                       where.begin.column);
    }
    return false;
  }

  bool only_keys(const toml::table& t, const std::string& where,
                 std::initializer_list<std::string_view> allowed) {
    for (const auto& [key, node] : t) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      return fail(node.source(),
                  where + ": unknown key '" + std::string(key.str()) + "'; expected one of: " + list);
    }
    return true;
  }

  bool string(const toml::table& t, const std::string& where, std::string_view key, std::string& out,
              bool required) {
    const toml::node* n = t.get(key);
    if (n == nullptr) {
      if (!required) return true;
      return fail(t.source(), where + ": missing key '" + std::string(key) + "'");
    }
    if (!n->is_string()) return fail(n->source(), where + ": '" + std::string(key) + "' must be a string");
    out = *n->value<std::string>();
    return true;
  }

  bool number(const toml::table& t, const std::string& where, std::string_view key, double& out,
              bool required) {
    const toml::node* n = t.get(key);
    if (n == nullptr) {
      if (!required) return true;
      return fail(t.source(), where + ": missing key '" + std::string(key) + "'");
    }
    if (!(n->is_integer() || n->is_floating_point()))
      return fail(n->source(), where + ": '" + std::string(key) + "' must be a number");
    out = *n->value<double>();
    return true;
  }

  template <typename E>
  bool choice(const toml::table& t, const std::string& where, std::string_view key, E& out,
              std::initializer_list<std::pair<std::string_view, E>> options) {
    std::string s;
    if (!string(t, where, key, s, true)) return false;
    std::string list;
    for (const auto& [name, value] : options) {
      if (s == name) {
        out = value;
        return true;
      }
      list += (list.empty() ? "" : ", ") + std::string(name);
    }
    return fail(t.get(key)->source(),
                where + ": " + std::string(key) + " = '" + s + "'; expected one of: " + list);
  }

  bool parse_register(const toml::table& t, const std::string& device, std::size_t index, RegisterDef& r) {
    std::string where = device + ".registers[" + std::to_string(index) + "]";
    if (!only_keys(t, where,
                   {"name", "table", "address", "type", "unit", "scale", "min", "max", "access", "doc"}) ||
        !string(t, where, "name", r.name, true))
      return false;
    where = device + "." + r.name;
    if (r.name.empty() || !std::all_of(r.name.begin(), r.name.end(), [](char c) {
          return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
        }))
      return fail(t.get("name")->source(), where + ": name must be non-empty snake_case (a–z, 0–9, _)");
    r.line = t.source().begin.line;
    double address = -1;
    if (!choice<Table>(t, where, "table", r.table,
                       {{"coil", Table::Coil},
                        {"discrete", Table::Discrete},
                        {"holding", Table::Holding},
                        {"input", Table::Input}}) ||
        !choice<ValueType>(t, where, "type", r.type,
                           {{"bool", ValueType::Bool},
                            {"u16", ValueType::U16},
                            {"i16", ValueType::I16},
                            {"u32", ValueType::U32},
                            {"i32", ValueType::I32}}) ||
        !choice<Access>(t, where, "access", r.access, {{"r", Access::Read}, {"rw", Access::ReadWrite}}) ||
        !number(t, where, "address", address, true) || !string(t, where, "doc", r.doc, false))
      return false;
    if (address < 0 || address != std::floor(address) || address + word_count(r.type) > 65536)
      return fail(t.get("address")->source(), where + ": address = " + fmt(address) +
                                                  "; expected an integer 0 … " +
                                                  std::to_string(65536 - word_count(r.type)));
    r.address = static_cast<std::uint16_t>(address);

    const bool bit_table = is_bit_table(r.table);
    if (bit_table != (r.type == ValueType::Bool))
      return fail(t.get("type")->source(),
                  where + ": type " + std::string(type_name(r.type)) + " in table " +
                      std::string(table_name(r.table)) +
                      (bit_table ? "; coils and discrete inputs are bool"
                                 : "; holding and input registers are u16, i16, u32 or i32"));
    if ((r.table == Table::Discrete || r.table == Table::Input) && r.writable())
      return fail(t.get("access")->source(), where + ": access = 'rw' in table " +
                                                 std::string(table_name(r.table)) +
                                                 ", which is read-only in Modbus; expected 'r'");
    if (r.type == ValueType::Bool) {
      for (std::string_view k : {"unit", "scale", "min", "max"})
        if (t.get(k) != nullptr)
          return fail(t.get(k)->source(),
                      where + ": '" + std::string(k) + "' given for a bool register; bools have none");
      r.scale = 1.0;
      r.min = 0.0;
      r.max = 1.0;
      return true;
    }
    if (!string(t, where, "unit", r.unit, true) || !number(t, where, "scale", r.scale, true) ||
        !number(t, where, "min", r.min, true) || !number(t, where, "max", r.max, true))
      return false;
    if (!(r.scale > 0.0) || !std::isfinite(r.scale))
      return fail(t.get("scale")->source(),
                  where + ": scale = " + fmt(r.scale) + "; expected a finite number > 0");
    if (!(r.min <= r.max))
      return fail(t.get("min")->source(), where + ": min = " + fmt(r.min) + " > max = " + fmt(r.max));
    const RawRange rr = raw_range(r.type);
    const double lo = std::round(r.min * r.scale), hi = std::round(r.max * r.scale);
    if (lo < rr.lo || hi > rr.hi)
      return fail(t.get("max")->source(), where + ": range " + fmt(r.min) + " … " + fmt(r.max) +
                                              " at scale " + fmt(r.scale) + " needs raw " + fmt(lo) + " … " +
                                              fmt(hi) + ", which a " + std::string(type_name(r.type)) +
                                              " cannot hold (" + fmt(rr.lo) + " … " + fmt(rr.hi) + ")");
    return true;
  }

  bool parse_device(const toml::table& t, const std::string& name, DeviceMap& d) {
    const std::string where = "devices." + name;
    d.name = name;
    double unit_id = 0;
    if (!only_keys(t, where, {"unit_id", "doc", "registers"}) ||
        !number(t, where, "unit_id", unit_id, true) || !string(t, where, "doc", d.doc, false))
      return false;
    if (unit_id < 1 || unit_id > 247 || unit_id != std::floor(unit_id))
      return fail(t.get("unit_id")->source(),
                  where + ": unit_id = " + fmt(unit_id) + "; expected an integer 1 … 247");
    d.unit_id = static_cast<std::uint8_t>(unit_id);
    const toml::node* regs_node = t.get("registers");
    if (regs_node == nullptr) return fail(t.source(), where + ": missing key 'registers'");
    const toml::array* regs = regs_node->as_array();
    if (regs == nullptr || regs->empty())
      return fail(regs_node->source(), where + ": 'registers' must be a non-empty array of inline tables");
    for (std::size_t i = 0; i < regs->size(); ++i) {
      const toml::table* rt = regs->get(i)->as_table();
      if (rt == nullptr)
        return fail(regs->get(i)->source(),
                    where + ".registers[" + std::to_string(i) + "]: expected an inline table { name = … }");
      RegisterDef r;
      if (!parse_register(*rt, name, i, r)) return false;
      for (const RegisterDef& o : d.registers) {
        if (o.name == r.name)
          return fail(rt->source(),
                      where + "." + r.name + ": name already used on line " + std::to_string(o.line));
        const bool overlap =
            o.table == r.table && r.address < o.address + o.words() && o.address < r.address + r.words();
        if (overlap)
          return fail(rt->get("address")->source(),
                      where + "." + r.name + ": " + std::string(table_name(r.table)) + " " +
                          std::to_string(r.address) +
                          (r.words() == 2 ? "–" + std::to_string(r.address + 1) : "") + " overlaps " +
                          o.name + " (line " + std::to_string(o.line) + ")");
      }
      d.registers.push_back(std::move(r));
    }
    return true;
  }
};

}  // namespace

Result<RegisterMap> parse_register_map(std::string_view text, std::string_view file_name) {
  const std::string name(file_name);
  toml::table root;
  try {
    root = toml::parse(text, file_name);
  } catch (const toml::parse_error& e) {
    return make_error(ErrorCode::RegisterMapSyntax, std::string(e.description()), name, e.source().begin.line,
                      e.source().begin.column);
  }
  MapLoader L{name, {}, false};
  RegisterMap map;
  map.file = name;
  double version = 0;
  if (!L.only_keys(root, "register map", {"version", "devices"}) ||
      !L.number(root, "register map", "version", version, true))
    return L.err;
  if (version != kMapVersion)
    return make_error(
        ErrorCode::RegisterMapInvalid,
        "version = " + fmt(version) + "; this build reads version " + std::to_string(kMapVersion), name,
        root.get("version")->source().begin.line, root.get("version")->source().begin.column);
  const toml::table* devices = root.get("devices") ? root.get("devices")->as_table() : nullptr;
  if (devices == nullptr || devices->empty())
    return make_error(ErrorCode::RegisterMapInvalid,
                      "missing [devices.<name>] tables; expected at least one device", name, 1, 1);
  for (const auto& [key, node] : *devices) {
    const toml::table* dt = node.as_table();
    if (dt == nullptr) {
      L.fail(node.source(), "devices." + std::string(key.str()) + " must be a table");
      return L.err;
    }
    DeviceMap d;
    if (!L.parse_device(*dt, std::string(key.str()), d)) return L.err;
    for (const DeviceMap& o : map.devices)
      if (o.unit_id == d.unit_id) {
        L.fail(dt->get("unit_id")->source(),
               "devices." + d.name + ": unit_id " + std::to_string(d.unit_id) + " already used by " + o.name);
        return L.err;
      }
    map.devices.push_back(std::move(d));
  }
  // TOML tables are unordered; list devices by unit id (the file's order).
  std::sort(map.devices.begin(), map.devices.end(),
            [](const DeviceMap& a, const DeviceMap& b) { return a.unit_id < b.unit_id; });
  return map;
}

Result<RegisterMap> load_register_map(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::FileNotFound, "cannot open register map", path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_register_map(text.str(), path);
}

std::string default_register_map_path() { return share_path("modbus/register_map.toml"); }

Result<DeviceMap> shipped_device(std::string_view name) {
  static std::once_flag once;
  static std::optional<Result<RegisterMap>> shipped;
  std::call_once(once, [] { shipped.emplace(load_register_map(default_register_map_path())); });
  if (!shipped->ok()) return shipped->error();
  return shipped->value().device_copy(name);
}

}  // namespace lcnc::drivers
