// Machine config loading (TOML through toml++) and validation. Every error
// names the key, the value found and what is allowed, with file:line:col where
// the TOML source has it. Unknown keys are errors: a misspelt key must never
// leave a default silently in force.
#include "machine/machine_config.h"
#include "common/quote.h"

#include "machine/config_keys.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <string_view>

#include <toml++/toml.h>

namespace lcnc {

double PitchTable::at(double x) const noexcept {
  if (values.empty()) return 0.0;
  if (!(x > start) || values.size() < 2) return values.front();
  if (x >= end()) return values.back();
  // start < x < end, so 0 < u < n − 1; the clamp only guards rounding.
  const double u = (x - start) / interval;
  const std::size_t k = std::min(static_cast<std::size_t>(u), values.size() - 2);
  const double f = u - static_cast<double>(k);
  return values[k] + (values[k + 1] - values[k]) * f;
}

double PitchTable::max_slope() const noexcept {
  double slope = 0.0;
  for (std::size_t k = 0; k + 1 < values.size(); ++k)
    slope = std::max(slope, std::abs(values[k + 1] - values[k]) / interval);
  return slope;
}

PitchTable PitchTable::scaled(double k) const {
  PitchTable t{start * k, interval * k, values};
  for (double& v : t.values) v *= k;
  return t;
}

namespace {

struct Loader {
  std::string file;
  Diagnostic err;
  bool failed = false;

  bool fail(ErrorCode code, const toml::source_region& where, std::string msg) {
    if (!failed) {
      failed = true;
      err = make_error(code, std::move(msg), file, where.begin.line, where.begin.column);
    }
    return false;
  }

  // Reject keys of `table` not listed in `allowed`.
  bool only_keys(const toml::table& table, std::string_view prefix,
                 std::initializer_list<std::string_view> allowed) {
    return only_keys_in(table, prefix, std::span(allowed.begin(), allowed.size()));
  }
  bool only_keys_in(const toml::table& table, std::string_view prefix,
                    std::span<const std::string_view> allowed) {
    for (const auto& [key, node] : table) {
      bool known = false;
      for (auto a : allowed) known = known || key.str() == a;
      if (!known) {
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        return fail(
            ErrorCode::ConfigUnknownKey, node.source(),
            "unknown key '" + std::string(prefix) + std::string(key.str()) + "'; expected one of: " + list);
      }
    }
    return true;
  }

  // Reads a number (integer or float) into `out` when present.
  bool number(const toml::table& t, std::string_view prefix, std::string_view key, double& out,
              bool required) {
    const toml::node* n = t.get(key);
    if (n == nullptr) {
      if (!required) return true;
      return fail(ErrorCode::ConfigMissingKey, t.source(),
                  "missing key '" + std::string(prefix) + std::string(key) + "'");
    }
    if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) {
      out = *v;
      return true;
    }
    return fail(ErrorCode::ConfigBadValue, n->source(),
                "'" + std::string(prefix) + std::string(key) + "' must be a number");
  }

  bool boolean(const toml::table& t, std::string_view prefix, std::string_view key, bool& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return true;
    if (auto v = n->value<bool>(); v && n->is_boolean()) {
      out = *v;
      return true;
    }
    return fail(ErrorCode::ConfigBadValue, n->source(),
                "'" + std::string(prefix) + std::string(key) + "' must be true or false");
  }

  bool string(const toml::table& t, std::string_view prefix, std::string_view key, std::string& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return true;
    if (auto v = n->value<std::string>(); v && n->is_string()) {
      out = *v;
      return true;
    }
    return fail(ErrorCode::ConfigBadValue, n->source(),
                "'" + std::string(prefix) + std::string(key) + "' must be a string");
  }

  // Reads an optional array of strings.
  bool strings(const toml::table& t, std::string_view prefix, std::string_view key,
               std::vector<std::string>& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return true;
    const toml::array* arr = n->as_array();
    if (arr == nullptr)
      return fail(ErrorCode::ConfigBadValue, n->source(),
                  "'" + std::string(prefix) + std::string(key) + "' must be an array of strings");
    out.clear();
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::node& e = *arr->get(i);
      auto v = e.value<std::string>();
      if (!v || !e.is_string() || v->empty())
        return fail(ErrorCode::ConfigBadValue, e.source(),
                    "'" + std::string(prefix) + std::string(key) + "[" + std::to_string(i) +
                        "]' must be a non-empty string");
      out.push_back(*v);
    }
    return true;
  }

  // Reads an optional number: `out` stays empty when the key is absent.
  bool optional_number(const toml::table& t, std::string_view prefix, std::string_view key,
                       std::optional<double>& out) {
    if (t.get(key) == nullptr) return true;
    double v = 0.0;
    if (!number(t, prefix, key, v, false)) return false;
    out = v;
    return true;
  }

  // Reads an array of numbers (integers or floats).
  bool numbers(const toml::table& t, std::string_view prefix, std::string_view key,
               std::vector<double>& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr)
      return fail(ErrorCode::ConfigMissingKey, t.source(),
                  "missing key '" + std::string(prefix) + std::string(key) + "'");
    const toml::array* arr = n->as_array();
    if (arr == nullptr)
      return fail(ErrorCode::ConfigBadValue, n->source(),
                  "'" + std::string(prefix) + std::string(key) + "' must be an array of numbers");
    out.clear();
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::node& e = *arr->get(i);
      auto v = e.value<double>();
      if (!v || !(e.is_floating_point() || e.is_integer()))
        return fail(
            ErrorCode::ConfigBadValue, e.source(),
            "'" + std::string(prefix) + std::string(key) + "[" + std::to_string(i) + "]' must be a number");
      out.push_back(*v);
    }
    return true;
  }

  // Reject keys of `table` that are not rows of `name` in the key table.
  template <class C>
  bool only_rows(const toml::table& table, std::string_view prefix, std::span<const ConfigKey<C>> keys,
                 std::string_view name) {
    std::vector<std::string_view> allowed;
    for (const ConfigKey<C>& k : keys)
      if (k.table == name) allowed.push_back(k.name);
    return only_keys_in(table, prefix, allowed);
  }

  // Reads the rows of `name` that have a setter from `t` into `c`: the type
  // is checked here, the range by validate(). A number the member cannot
  // hold (a negative period) is reported with the row's range.
  template <class C>
  bool read_rows(const toml::table& t, std::string_view prefix, std::span<const ConfigKey<C>> keys,
                 std::string_view name, C& c, bool rotary = false) {
    for (const ConfigKey<C>& k : keys) {
      if (k.table != name || k.set == nullptr) continue;
      const toml::node* n = t.get(k.name);
      const std::string path = std::string(prefix) + std::string(k.name);
      if (n == nullptr) {
        if (!k.required) continue;
        return fail(ErrorCode::ConfigMissingKey, t.source(), "missing key '" + path + "'");
      }
      KeyValue v;
      switch (k.type) {
        case KeyType::Number:
        case KeyType::Integer: {
          double d = 0.0;
          if (!number(t, prefix, k.name, d, false)) return false;
          if (k.type == KeyType::Integer && !(d == std::floor(d) && d >= 0.0 && d <= 4294967295.0))
            return fail(ErrorCode::ConfigBadValue, n->source(),
                        "'" + path + "' = " + fmt_value(d) + " must be a whole number; allowed " +
                            allowed_text(k, rotary));
          v = d;
          break;
        }
        case KeyType::Boolean: {
          bool b = false;
          if (!boolean(t, prefix, k.name, b)) return false;
          v = b;
          break;
        }
        case KeyType::String: {
          std::string str;
          if (!string(t, prefix, k.name, str)) return false;
          v = std::move(str);
          break;
        }
        case KeyType::Strings: {
          std::vector<std::string> list;
          if (!strings(t, prefix, k.name, list)) return false;
          v = std::move(list);
          break;
        }
        case KeyType::Numbers:
        case KeyType::Table: continue;
      }
      if (std::string why = k.set(c, v); !why.empty())
        return fail(ErrorCode::ConfigBadValue, n->source(), "'" + path + "' " + why);
      if (k.get != nullptr && std::holds_alternative<double>(v)) {
        const double d = std::get<double>(v);
        if (!(k.get(c) == d) && !k.range.contains(d))
          return fail(ErrorCode::ConfigBadValue, n->source(),
                      path + " = " + fmt_value(d) + "; allowed " + allowed_text(k, rotary));
      }
    }
    return true;
  }

  static std::string fmt_value(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  // Runs load on the table t[key] when there is one: false when t[key] is
  // no table or load fails.
  template <class F>
  bool section(const toml::table& t, std::string_view key, F&& load) {
    const toml::table* s = subtable(t, key);
    if (s == nullptr) return !failed;
    return load(*s) && !failed;
  }

  const toml::table* subtable(const toml::table& t, std::string_view key, std::string_view prefix = {}) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) {
      fail(ErrorCode::ConfigBadValue, n->source(),
           "'" + std::string(prefix) + std::string(key) + "' must be a table");
      return nullptr;
    }
    return n->as_table();
  }
};

std::string fmt(double v) { return Loader::fmt_value(v); }

// [axes.X.pitch_compensation]: start, interval and values, all required.
bool load_pitch_table(Loader& L, const toml::table& axis_table, const std::string& axis_prefix,
                      PitchTable& table) {
  const toml::table* t = L.subtable(axis_table, "pitch_compensation", axis_prefix);
  if (t == nullptr) return !L.failed;
  const std::string p = axis_prefix + "pitch_compensation.";
  if (!(L.only_rows(*t, p, axis_keys(), "axes.<L>.pitch_compensation") &&
        L.number(*t, p, "start", table.start, true) && L.number(*t, p, "interval", table.interval, true) &&
        L.numbers(*t, p, "values", table.values)))
    return false;
  // Caught here, not only in validate(): `values = []` would otherwise read
  // as "no table" and silently switch the compensation off.
  if (table.values.size() < 2)
    return L.fail(ErrorCode::ConfigBadValue, t->get("values")->source(),
                  p + "values has " + std::to_string(table.values.size()) +
                      " value(s); allowed 2 or more (one per interval end)");
  return true;
}

// Homing and pitch-compensation keys of one axis; the axis' own ranges
// (min < max, max_velocity > 0) are already checked.
Status validate_home_and_pitch(const MachineConfig& m, const AxisConfig& a, const std::string& file,
                               std::string& key) {
  const std::string p = std::string("axes.") + letter(a.axis) + ".";
  auto bad = [&](std::string_view k, std::string msg) {
    key = p + std::string(k);
    return Status(make_error(ErrorCode::ConfigBadValue, std::move(msg), file));
  };
  const std::string unit = is_rotary(a.axis) ? "deg" : "mm";
  const double home = a.home_position_or_default();
  if (!(std::isfinite(home) && home >= a.min && home <= a.max))
    return bad("home_position", p + "home_position = " + fmt(home) + "; allowed min … max = " + fmt(a.min) +
                                    " … " + fmt(a.max) + " " + unit);
  if (!(std::isfinite(a.following_error) && a.following_error >= 0.0 && a.following_error <= a.max - a.min))
    return bad("following_error", p + "following_error = " + fmt(a.following_error) +
                                      "; allowed 0 (not checked) … max − min = " + fmt(a.max - a.min) + " " +
                                      unit);
  const double search = a.home_search_velocity_or_default();
  if (!(std::isfinite(search) && search != 0.0 && std::abs(search) <= a.max_velocity))
    return bad("home_search_velocity",
               p + "home_search_velocity = " + fmt(search) + "; allowed " + fmt(-a.max_velocity) + " … " +
                   fmt(a.max_velocity) + " " + unit +
                   "/s (±max_velocity), not 0: the sign is the direction toward the home switch");
  const double latch = a.home_latch_velocity_or_default();
  if (!(std::isfinite(latch) && latch > 0.0 && latch <= std::abs(search)))
    return bad("home_latch_velocity", p + "home_latch_velocity = " + fmt(latch) + "; allowed > 0 … " +
                                          fmt(std::abs(search)) + " " + unit + "/s (|home_search_velocity|)");

  const PitchTable& t = a.pitch_compensation;
  if (t.empty()) return {};
  const std::string pp = p + "pitch_compensation.";
  if (t.values.size() < 2)
    return bad("pitch_compensation.values", pp + "values has " + std::to_string(t.values.size()) +
                                                " value(s); allowed 2 or more (one per interval end)");
  if (!(std::isfinite(t.interval) && t.interval > 0.0))
    return bad("pitch_compensation.interval", pp + "interval = " + fmt(t.interval) + "; allowed > 0 " + unit);
  for (std::size_t k = 0; k < t.values.size(); ++k) {
    if (!(std::isfinite(t.values[k]) && std::abs(t.values[k]) <= kMaxPitchCorrection))
      return bad("pitch_compensation.values", pp + "values[" + std::to_string(k) + "] = " + fmt(t.values[k]) +
                                                  "; allowed " + fmt(-kMaxPitchCorrection) + " … " +
                                                  fmt(kMaxPitchCorrection) + " " + unit);
  }
  auto slack = [](double limit) { return kPitchTableEndTolerance * std::max(1.0, std::abs(limit)); };
  if (!(std::isfinite(t.start) && t.start >= a.min - slack(a.min) && t.end() <= a.max + slack(a.max)))
    return bad("pitch_compensation.start",
               pp + "start … start + (n−1)·interval = " + fmt(t.start) + " … " + fmt(t.end()) + " " + unit +
                   "; the table must lie within min … max = " + fmt(a.min) + " … " + fmt(a.max) + " " + unit);
  // The RT kernel outputs commanded + correction(commanded): at max_velocity
  // a period moves pulses·(1 + slope) steps, +1 for the rounding of the
  // correction to whole steps. That must still fit the DDA preset.
  const double slope = t.max_slope();
  if (slope > 0.0) {
    const double pulses = a.max_velocity * a.steps_per_unit * m.period_s() * (1.0 + slope) + 1.0;
    if (pulses > m.dda.max_pulses())
      return bad("pitch_compensation.values",
                 pp + "values: slope " + fmt(slope) + " at max_velocity = " + fmt(a.max_velocity) + " " +
                     unit + "/s needs " + fmt(pulses) +
                     " pulses per period (with 1 for rounding); the DDA preset gives at most " +
                     std::to_string(m.dda.max_pulses()) +
                     " (flatten the table, raise dda.magnitude_bits or lower max_velocity)");
  }
  return {};
}

// [kinematics]: the variant and the offsets of kinematics/five_axis_geometry.h.
bool load_kinematics(Loader& L, const toml::table& t, FiveAxisGeometry& g, TcpConfig& tcp) {
  constexpr std::string_view kPre = "kinematics.";
  if (!L.only_rows(t, kPre, machine_keys(), "kinematics")) return false;
  if (!L.boolean(t, kPre, "tcp", tcp.enabled)) return false;
  std::string method;
  if (!L.string(t, kPre, "orientation", method)) return false;
  if (const toml::node* n = t.get("orientation")) {
    if (method == "joint_linear")
      tcp.orientation = OrientationMethod::JointLinear;
    else if (method == "vector")
      tcp.orientation = OrientationMethod::Vector;
    else if (method == "pole_smoothed")
      tcp.orientation = OrientationMethod::PoleSmoothed;
    else
      return L.fail(ErrorCode::ConfigBadValue, n->source(),
                    "kinematics.orientation = \"" + method +
                        "\"; allowed \"joint_linear\", \"vector\" or \"pole_smoothed\"");
  }
  const auto bounded = [&](std::string_view key, double& out, double hi, const char* unit) {
    if (!L.number(t, kPre, key, out, false)) return false;
    if (out > 0.0 && out <= hi) return true;
    return L.fail(
        ErrorCode::ConfigBadValue, t.get(key)->source(),
        "kinematics." + std::string(key) + " = " + fmt(out) + "; allowed > 0 … " + fmt(hi) + " " + unit);
  };
  if (!bounded("orientation_tolerance_deg", tcp.orientation_tolerance_deg, 1.0, "deg") ||
      !bounded("tip_tolerance_mm", tcp.tip_tolerance_mm, 0.1, "mm"))
    return false;
  std::string variant;
  if (!L.string(t, kPre, "variant", variant)) return false;
  if (const toml::node* n = t.get("variant")) {
    if (variant == "head_head")
      g.variant = MachineVariant::HeadHead;
    else if (variant == "table_table")
      g.variant = MachineVariant::TableTable;
    else
      return L.fail(ErrorCode::ConfigBadValue, n->source(),
                    "kinematics.variant = \"" + variant + "\"; allowed \"head_head\" or \"table_table\"");
  }
  const auto vec3 = [&](std::string_view key, Vec3& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return true;
    std::vector<double> v;
    if (!L.numbers(t, kPre, key, v)) return false;
    bool ok = v.size() == 3;
    for (double x : v) ok = ok && std::isfinite(x) && std::abs(x) <= 10000.0;
    if (!ok)
      return L.fail(ErrorCode::ConfigBadValue, n->source(),
                    "kinematics." + std::string(key) + " must be [x, y, z] in mm, each within ±10000");
    out = Vec3(v[0], v[1], v[2]);
    return true;
  };
  if (!vec3("head_c_to_a_mm", g.head_c_to_a_mm) || !vec3("table_a_pivot_mm", g.table_a_pivot_mm) ||
      !vec3("table_c_offset_mm", g.table_c_offset_mm))
    return false;
  if (!L.number(t, kPre, "head_pivot_length_mm", g.head_pivot_length_mm, false)) return false;
  if (!(g.head_pivot_length_mm > 0.0 && g.head_pivot_length_mm <= 10000.0))
    return L.fail(
        ErrorCode::ConfigBadValue, t.get("head_pivot_length_mm")->source(),
        "kinematics.head_pivot_length_mm = " + fmt(g.head_pivot_length_mm) + "; allowed > 0 … 10000 mm");
  return true;
}

// [tools.N]: z_offset, x_offset, y_offset (mm), diameter (mm), description.
// N is the T word, 1 … kMaxToolNumber.
bool load_tools(Loader& L, const toml::table& t, std::vector<ToolConfig>& tools) {
  for (const auto& [key, node] : t) {
    const std::string k(key.str());
    int number = 0;
    const auto [end, ec] = std::from_chars(k.data(), k.data() + k.size(), number);
    if (ec != std::errc{} || end != k.data() + k.size() || number < 1 || number > kMaxToolNumber)
      return L.fail(ErrorCode::ConfigBadValue, node.source(),
                    "tools." + k +
                        ": a tool is named by its number; expected [tools.N] with N "
                        "from 1 to " +
                        std::to_string(kMaxToolNumber) + " (the T word)");
    const toml::table* tt = L.subtable(t, key.str(), "tools.");
    if (tt == nullptr) return false;
    const std::string p = "tools." + k + ".";
    ToolConfig tool;
    tool.number = number;
    double x = 0.0, y = 0.0, z = 0.0;
    if (!(L.only_keys(*tt, p, {"z_offset", "x_offset", "y_offset", "diameter", "description"}) &&
          L.number(*tt, p, "z_offset", z, false) && L.number(*tt, p, "x_offset", x, false) &&
          L.number(*tt, p, "y_offset", y, false) && L.number(*tt, p, "diameter", tool.diameter_mm, false) &&
          L.string(*tt, p, "description", tool.description)))
      return false;
    tool.offset << x, y, z, 0.0, 0.0, 0.0;
    for (const double v : {x, y, z}) {
      if (!(std::fabs(v) <= kMaxToolOffsetMm))
        return L.fail(ErrorCode::ConfigBadValue, tt->source(),
                      p + "*_offset = " + fmt(v) + "; allowed −" + fmt(kMaxToolOffsetMm) + " … " +
                          fmt(kMaxToolOffsetMm) + " mm");
    }
    if (!(tool.diameter_mm >= 0.0 && tool.diameter_mm <= kMaxToolOffsetMm))
      return L.fail(
          ErrorCode::ConfigBadValue, tt->source(),
          p + "diameter = " + fmt(tool.diameter_mm) + "; allowed 0 … " + fmt(kMaxToolOffsetMm) + " mm");
    tools.push_back(std::move(tool));
  }
  std::sort(tools.begin(), tools.end(),
            [](const ToolConfig& a, const ToolConfig& b) { return a.number < b.number; });
  return true;
}

// [work_offsets]: G54 … G59.3 = [X, Y, Z, A, B, C].
bool load_work_offsets(Loader& L, const toml::table& t, std::array<Pose, kWorkOffsetCount>& offsets) {
  if (!L.only_keys(t, "work_offsets.", {"G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"}))
    return false;
  for (int i = 0; i < kWorkOffsetCount; ++i) {
    const std::string key = kWorkOffsetNames[i];
    const toml::node* n = t.get(key);
    if (n == nullptr) continue;
    const toml::array* arr = n->as_array();
    bool okay = arr != nullptr && arr->size() == kAxisCount;
    for (int k = 0; okay && k < kAxisCount; ++k) {
      auto v = arr->get(static_cast<std::size_t>(k))->value<double>();
      okay = v.has_value();
      if (okay) offsets[i][k] = *v;
    }
    if (!okay)
      return L.fail(ErrorCode::ConfigBadValue, n->source(),
                    "work_offsets." + key + " must be an array of 6 numbers [X, Y, Z, A, B, C]");
  }
  return true;
}

bool load_axis(Loader& L, const toml::table& t, Axis axis, AxisConfig& a) {
  const std::string p = std::string("axes.") + letter(axis) + ".";
  a.present = true;
  a.axis = axis;
  return L.only_rows(t, p, axis_keys(), "axes.<L>") &&
         L.read_rows(t, p, axis_keys(), "axes.<L>", a, is_rotary(axis)) &&
         load_pitch_table(L, t, p, a.pitch_compensation);
}

// What is wrong with a startup code (empty when nothing): words of the
// modal codes a program may start with, separated by blanks; P and Q only
// after G64, as numbers. The G-code reader runs it; this only admits it.
std::string startup_code_problem(const std::string& code) {
  static constexpr std::array<const char*, 23> kAllowed = {
      "G17", "G18", "G19", "G20", "G21", "G90", "G91",   "G90.1", "G91.1", "G93", "G94", "G54",
      "G55", "G56", "G57", "G58", "G59", "G61", "G61.1", "G64",   "G40",   "G49", "G80"};
  bool after_g64 = false;
  std::size_t i = 0;
  while (i < code.size()) {
    if (code[i] == ' ' || code[i] == '\t') {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < code.size() && code[j] != ' ' && code[j] != '\t') ++j;
    std::string w = code.substr(i, j - i);
    for (char& c : w) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    i = j;
    if ((w[0] == 'P' || w[0] == 'Q') && after_g64) {
      char* end = nullptr;
      const double v = std::strtod(w.c_str() + 1, &end);
      if (w.size() == 1 || *end != '\0' || !(v >= 0.0 && v <= 10.0))
        return "found " + quote(w) + "; expected " + w[0] + " as a number of mm from 0 to 10 after G64";
      continue;
    }
    if (w == "M5" || w == "M9") continue;
    bool known = false;
    for (const char* a : kAllowed) known = known || w == a;
    if (!known)
      return "found " + quote(w) +
             "; expected only G17 G18 G19 G20 G21 G90 G91 G90.1 G91.1 G93 G94 "
             "G54…G59 G61 G61.1 G64 [P Q] G40 G49 G80 M5 M9 (modes a program starts in, no "
             "motion)";
    after_g64 = w == "G64";
  }
  return {};
}

// The range of each row of the key table, then what depends on more than
// one key. `key` gets the path of the key at fault ("axes.X.max_velocity"),
// for the parser to say where it stands in the file.
Status check(const MachineConfig& m, const std::string& file, std::string& key) {
  auto bad = [&](std::string k, std::string msg) {
    key = std::move(k);
    return Status(make_error(ErrorCode::ConfigBadValue, std::move(msg), file));
  };
  for (const MachineKey& k : machine_keys()) {
    if (k.get == nullptr) continue;
    const std::string path = std::string(k.table) + "." + std::string(k.name);
    if (const double v = k.get(m); !k.range.contains(v))
      return bad(path, path + " = " + fmt(v) + "; allowed " + allowed_text(k));
  }
  if (std::string why = startup_code_problem(m.startup_code); !why.empty())
    return bad("machine.startup_code", "machine.startup_code = \"" + m.startup_code + "\": " + why);
  if (m.dda.capacity < m.dda.max_pulses() || m.dda.capacity > 1'000'000)
    return bad("dda.capacity", "dda.capacity = " + std::to_string(m.dda.capacity) + "; allowed " +
                                   std::to_string(m.dda.max_pulses()) +
                                   " (one pulse per tick at the largest magnitude) … 1000000");
  if (m.dda_clock_hz() > 100e6)
    return bad("dda.capacity", "dda clock = capacity / period = " + fmt(m.dda_clock_hz() / 1e6) +
                                   " MHz; allowed up to 100 MHz");
  bool any = false;
  for (const AxisConfig& a : m.axes) {
    if (!a.present) continue;
    any = true;
    const std::string p = std::string("axes.") + letter(a.axis) + ".";
    const bool rotary = is_rotary(a.axis);
    const char* unit = rotary ? "deg" : "mm";
    for (const AxisKey& k : axis_keys()) {
      if (k.get == nullptr) continue;
      const std::string path = p + std::string(k.name);
      if (const double v = k.get(a); !k.range.contains(v))
        return bad(path, path + " = " + fmt(v) + "; allowed " + allowed_text(k, rotary));
    }
    if (!(std::isfinite(a.min) && std::isfinite(a.max) && a.min < a.max))
      return bad(p + "max", p + "min = " + fmt(a.min) + ", max = " + fmt(a.max) + "; need min < max");
    const double span_steps = std::max(std::abs(a.min), std::abs(a.max)) * a.steps_per_unit;
    if (span_steps > 2.0e9)
      return bad(p + "steps_per_unit", p + "travel of " + fmt(a.max - a.min) + " " + unit + " at " +
                                           fmt(a.steps_per_unit) + " steps/" + unit +
                                           " overflows 32-bit step counters");
    if (a.wrap && !rotary) return bad(p + "wrap", p + "wrap = true; only rotary axes (A B C) can wrap");
    if (a.wrap && std::abs((a.max - a.min) - 360.0) > 1e-9)
      return bad(p + "wrap", p + "wrap = true needs max − min = 360 deg; found " + fmt(a.max - a.min));
    const double pulses = a.max_velocity * a.steps_per_unit * m.period_s();
    if (pulses > m.dda.max_pulses())
      return bad(p + "max_velocity", p + "max_velocity = " + fmt(a.max_velocity) + " " + unit + "/s needs " +
                                         fmt(pulses) + " pulses per " + fmt(m.period_ns / 1000.0) +
                                         " µs period; the DDA preset gives at most " +
                                         std::to_string(m.dda.max_pulses()) +
                                         " (raise dda.magnitude_bits or lower max_velocity)");
    if (Status s = validate_home_and_pitch(m, a, file, key); !s) return s;
  }
  if (!any) return bad("axes", "no axes configured; expected at least one [axes.X] … [axes.C] table");
  return {};
}

}  // namespace

Status validate(const MachineConfig& m, const std::string& file) {
  std::string key;
  return check(m, file, key);
}

Result<MachineConfig> parse_machine_config(std::string_view text, const std::string& name) {
  Loader L{name, {}, false};
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(name));
  } catch (const toml::parse_error& e) {
    return make_error(ErrorCode::ConfigSyntax, std::string(e.description()), name, e.source().begin.line,
                      e.source().begin.column);
  }
  MachineConfig m;
  m.axes = {};
  m.work_offsets.fill(Pose::Zero());
  if (!L.only_keys(root, "", {"machine", "dda", "laser", "axes", "kinematics", "work_offsets", "tools"}))
    return L.err;

  // [machine], [dda], [laser], in this order: dialect = "grbl" sets the
  // s_max a [laser] s_max overrides. Then the axes and the tables with
  // loaders of their own; the first error ends the reading.
  bool ok = true;
  for (const std::string_view table : {"machine", "dda", "laser"}) {
    const std::string prefix = std::string(table) + ".";
    ok = ok && L.section(root, table, [&](const toml::table& t) {
      return L.only_rows(t, prefix, machine_keys(), table) &&
             L.read_rows(t, prefix, machine_keys(), table, m);
    });
  }
  ok = ok && L.section(root, "axes", [&](const toml::table& t) {
    if (!L.only_keys(t, "axes.", {"X", "Y", "Z", "A", "B", "C"})) return false;
    for (Axis a : kAllAxes) {
      if (!L.section(t, std::string(1, letter(a)),
                     [&](const toml::table& at) { return load_axis(L, at, a, m.axis(a)); }))
        return false;
    }
    return true;
  });
  ok = ok && L.section(root, "kinematics",
                       [&](const toml::table& t) { return load_kinematics(L, t, m.kinematics, m.tcp); });
  ok = ok && L.section(root, "work_offsets",
                       [&](const toml::table& t) { return load_work_offsets(L, t, m.work_offsets); });
  ok = ok && L.section(root, "tools", [&](const toml::table& t) { return load_tools(L, t, m.tools); });
  if (!ok) return L.err;
  const std::filesystem::path config_dir = std::filesystem::path(name).parent_path();
  for (std::string& dir : m.subroutine_path) {
    if (std::filesystem::path(dir).is_relative() && !config_dir.empty()) {
      dir = (config_dir / dir).lexically_normal().string();
    }
  }
  if (!m.parameter_file.empty() && std::filesystem::path(m.parameter_file).is_relative() &&
      !config_dir.empty()) {
    m.parameter_file = (config_dir / m.parameter_file).lexically_normal().string();
  }
  std::string key;
  if (Status s = check(m, name, key); !s) {
    // Where the key at fault stands in the file; a default's nearest
    // enclosing table when it is not written.
    Diagnostic d = s.error();
    for (std::string path = key; !path.empty();) {
      if (const toml::node* n = root.at_path(path).node(); n != nullptr) {
        d.line = n->source().begin.line;
        d.col = n->source().begin.column;
        break;
      }
      const auto dot = path.rfind('.');
      path = dot == std::string::npos ? std::string() : path.substr(0, dot);
    }
    return d;
  }
  return m;
}

Result<MachineConfig> load_machine_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::FileNotFound, "cannot open machine config '" + path + "'", path);
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_machine_config(buf.str(), path);
}

}  // namespace lcnc
