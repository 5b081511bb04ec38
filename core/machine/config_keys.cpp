// The machine config's key table (machine/config_keys.h): what each key
// fills, its range and its documentation, in the order the reference prints.
#include "machine/config_keys.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace lcnc {
namespace {

// The setters of the common cases: a member of C of the row's type.
template <class C, double C::*M>
std::string set_number(C& c, const KeyValue& v) {
  c.*M = std::get<double>(v);
  return {};
}
template <class C, double C::*M>
double get_number(const C& c) {
  return c.*M;
}
template <class C, bool C::*M>
std::string set_bool(C& c, const KeyValue& v) {
  c.*M = std::get<bool>(v);
  return {};
}
template <class C, std::string C::*M>
std::string set_string(C& c, const KeyValue& v) {
  c.*M = std::get<std::string>(v);
  return {};
}
template <std::optional<double> AxisConfig::*M>
std::string set_optional(AxisConfig& a, const KeyValue& v) {
  a.*M = std::get<double>(v);
  return {};
}

// A whole number (KeyType::Integer: the reader admits 0 … 2³² − 1 only).
std::uint32_t whole(const KeyValue& v) { return static_cast<std::uint32_t>(std::get<double>(v)); }

constexpr KeyRange range(double lo, double hi) { return {false, lo, hi, false, false}; }
constexpr KeyRange above(double lo, double hi) { return {false, lo, hi, true, false}; }

using M = MachineConfig;
using A = AxisConfig;

const MachineKey kMachineKeys[] = {
    // [machine]
    {"machine",
     "name",
     KeyType::String,
     "",
     "",
     {},
     "any string",
     "\"default\"",
     false,
     "The machine's name, shown in reports and the HMI.",
     &set_string<M, &M::name>},
    {"machine", "period_us", KeyType::Number, "µs", "", range(10, 10000), "", "75", false,
     "RT period: the DDA's and the position buffer's period (rounded to whole ns).",
     [](M& m, const KeyValue& v) {
       // Saturated into the 32-bit ns member; validate() then names the range.
       const double ns = std::get<double>(v) * 1000.0;
       m.period_ns = !(ns > 0.0)          ? 0u
                     : ns >= 4294967295.0 ? std::numeric_limits<std::uint32_t>::max()
                                          : static_cast<std::uint32_t>(std::llround(ns));
       return std::string();
     },
     [](const M& m) { return m.period_ns / 1000.0; }},
    {"machine", "path_tolerance_mm", KeyType::Number, "mm", "", above(0, 10), "", "0.01", false,
     "The P of a G64 without P: how far a blended corner may leave the programmed path. "
     "Programs that never say G64 (and no startup_code G64) run exact path (G61) and do not use it.",
     &set_number<M, &M::path_tolerance_mm>, &get_number<M, &M::path_tolerance_mm>},
    {"machine",
     "startup_code",
     KeyType::String,
     "",
     "",
     {},
     "modal codes only: G17 G18 G19 G20 G21 G90 G91 G90.1 G91.1 G93 G94 G54…G59 G61 G61.1 "
     "G64 [P Q] G40 G49 G80 M5 M9",
     "\"\" (G17 G21 G90 G91.1 G94 G54 G61 M5 M9)",
     false,
     "The modes every program starts in, as if its first line (LinuxCNC's RS274NGC_STARTUP_CODE). "
     "Its G61/G64 is the startup path mode: empty, or naming neither, a program starts in G61 "
     "(exact path) until it says G64. LinuxCNC's configuration tools write G64 (with a small P) "
     "here, as the shipped machine (share/machines/default.toml) does.",
     &set_string<M, &M::startup_code>},
    {"machine",
     "block_delete",
     KeyType::Boolean,
     "",
     "",
     {},
     "true, false",
     "true",
     false,
     "A line that starts with '/' is skipped (LinuxCNC's block delete switch); false: such lines "
     "run like any other.",
     &set_bool<M, &M::block_delete>},
    {"machine", "program_segment_limit", KeyType::Number, "", "", range(1, 1e12), "", "200000000", false,
     "The most moves, dwells and pauses one program may make (its loops and calls run out). A "
     "program past it is an error at the line its loop stands on, so a check always ends. Far "
     "above the longest program a load takes (some 100 million lines).",
     &set_number<M, &M::program_segment_limit>, &get_number<M, &M::program_segment_limit>},
    {"machine", "program_time_limit_h", KeyType::Number, "h", "", range(0.001, 100000), "", "168", false,
     "The longest one program may run, in machine time at its programmed feeds (rapids at the "
     "fastest axis, dwells as written): a loop past it is an error at its line. 168 h: a week.",
     [](M& m, const KeyValue& v) {
       m.program_time_limit_s = std::get<double>(v) * 3600.0;
       return std::string();
     },
     [](const M& m) { return m.program_time_limit_s / 3600.0; }},
    {"machine",
     "optional_stop",
     KeyType::Boolean,
     "",
     "",
     {},
     "true, false",
     "true",
     false,
     "M1 pauses a program like M0 (LinuxCNC's optional stop switch); false: M1 is passed over.",
     &set_bool<M, &M::optional_stop>},
    {"machine",
     "dialect",
     KeyType::String,
     "",
     "",
     {},
     "\"rs274ngc\", \"grbl\"",
     "\"rs274ngc\"",
     false,
     "The G-code the programs are written in: LinuxCNC's RS274NGC, or grbl's as hobby laser design "
     "tools write it (S 0 … 1000 unless laser.s_max says otherwise, grbl system lines ($H, $32=1 …) "
     "passed over with a warning).",
     [](M& m, const KeyValue& v) {
       const std::string& d = std::get<std::string>(v);
       if (d == "grbl") {
         m.dialect = MachineConfig::Dialect::Grbl;
         m.laser.s_max = 1000.0;  // grbl's $30 default, unless [laser] s_max (read after) says
       } else if (d == "rs274ngc") {
         m.dialect = MachineConfig::Dialect::Rs274ngc;
       } else {
         return "is \"" + d + "\"; allowed \"rs274ngc\" (LinuxCNC's, the default) or \"grbl\"";
       }
       return std::string();
     }},
    {"machine",
     "subroutine_path",
     KeyType::Strings,
     "",
     "",
     {},
     "array of folders",
     "[]",
     false,
     "Folders searched, after the program's own, for `<name>.ngc` of a subroutine `o<name>` called "
     "before it is defined (LinuxCNC's SUBROUTINE_PATH). Relative to the config file's folder.",
     [](M& m, const KeyValue& v) {
       m.subroutine_path = std::get<std::vector<std::string>>(v);
       return std::string();
     }},
    {"machine",
     "parameter_file",
     KeyType::String,
     "",
     "",
     {},
     "a file path",
     "\"\" (none)",
     false,
     "Keeps the work offsets (G10, G92, G28.1/G30.1) and the tool table's changes from one job to "
     "the next (LinuxCNC's PARAMETER_FILE). Relative to the config file's folder. Empty: every job "
     "starts from [work_offsets] and [tools].",
     &set_string<M, &M::parameter_file>},
    {"machine", "max_feed_override", KeyType::Number, "", "", range(1, 2), "", "1", false,
     "The highest feed override the operator may set (1 = 100 %). Above 100 % the planner plans "
     "the feed moves faster, within the axes' limits.",
     &set_number<M, &M::max_feed_override>, &get_number<M, &M::max_feed_override>},
    {"machine",
     "allow_unhomed",
     KeyType::Boolean,
     "",
     "",
     {},
     "true, false",
     "false",
     false,
     "Real drives come up unhomed and a job is refused until every axis is homed; true: a machine "
     "without home switches runs from where it stands at power-on (said loudly at start).",
     &set_bool<M, &M::allow_unhomed>},
    {"machine",
     "max_jerk",
     KeyType::Number,
     "mm/s³",
     "",
     {false, kMinMaxJerk, kMaxMaxJerk, false, true},
     "",
     "0 (none)",
     false,
     "Jerk limit of the linear axes (S-curve acceleration by a moving average of the planned "
     "path); its deviation comes out of path_tolerance_mm. 0 or left out: no jerk limit.",
     &set_number<M, &M::max_jerk>,
     &get_number<M, &M::max_jerk>},
    // [dda]
    {"dda", "magnitude_bits", KeyType::Integer, "", "", range(1, 16), "", "4", false,
     "DDA magnitude width: an axis gets 0 … 2^bits − 1 pulses per period.",
     [](M& m, const KeyValue& v) {
       m.dda.magnitude_bits = whole(v);
       return std::string();
     },
     [](const M& m) { return static_cast<double>(m.dda.magnitude_bits); }},
    {"dda",
     "capacity",
     KeyType::Integer,
     "ticks",
     "",
     {},
     "2^magnitude_bits − 1 … 1000000; capacity / period ≤ 100 MHz",
     "30",
     false,
     "N: DDA clock ticks per period (the accumulator's capacity); the DDA clock is capacity / "
     "period.",
     [](M& m, const KeyValue& v) {
       m.dda.capacity = whole(v);
       return std::string();
     }},
    // [laser]
    {"laser", "s_max", KeyType::Number, "", "", above(0, 1e6), "", "100 (1000 with dialect = \"grbl\")",
     false, "The S word value meaning 100 % power.",
     [](M& m, const KeyValue& v) {
       m.laser.s_max = std::get<double>(v);
       return std::string();
     },
     [](const M& m) { return m.laser.s_max; }},
    // [kinematics]: read by its own loader.
    {"kinematics",
     "variant",
     KeyType::String,
     "",
     "",
     {},
     "\"head_head\", \"table_table\"",
     "\"head_head\"",
     false,
     "The 5-axis machine's build: a head-head or a table-table machine."},
    {"kinematics",
     "head_c_to_a_mm",
     KeyType::Numbers,
     "mm",
     "",
     {},
     "[x, y, z], each within ±10000",
     "[0, 0, -80]",
     false,
     "Head-head: from the head reference point (on the C axis) to the A pivot, C-turned frame."},
    {"kinematics",
     "head_pivot_length_mm",
     KeyType::Number,
     "mm",
     "",
     {},
     "> 0 … 10000",
     "120",
     false,
     "Head-head: from the A pivot to the tool tip (focus)."},
    {"kinematics",
     "table_a_pivot_mm",
     KeyType::Numbers,
     "mm",
     "",
     {},
     "[x, y, z], each within ±10000",
     "[500, 225, 100]",
     false,
     "Table-table: a point of the A trunnion axis, machine frame."},
    {"kinematics",
     "table_c_offset_mm",
     KeyType::Numbers,
     "mm",
     "",
     {},
     "[x, y, z], each within ±10000",
     "[0, 0, 50]",
     false,
     "Table-table: from that point to the C table's centre, trunnion frame."},
    {"kinematics",
     "tcp",
     KeyType::Boolean,
     "",
     "",
     {},
     "true, false",
     "false",
     false,
     "Tool-centre-point control of programs: X Y Z program the tip."},
    {"kinematics",
     "orientation",
     KeyType::String,
     "",
     "",
     {},
     "\"joint_linear\", \"vector\", \"pole_smoothed\"",
     "\"pole_smoothed\"",
     false,
     "How the tool orientation is interpolated between blocks."},
    {"kinematics",
     "orientation_tolerance_deg",
     KeyType::Number,
     "deg",
     "",
     {},
     "> 0 … 1",
     "0.01",
     false,
     "Allowed orientation error of the interpolation."},
    {"kinematics",
     "tip_tolerance_mm",
     KeyType::Number,
     "mm",
     "",
     {},
     "> 0 … 0.1",
     "0.001",
     false,
     "Allowed distance of the tip from the programmed path."},
    // [work_offsets]: read by its own loader.
    {"work_offsets",
     "G54 … G59, G59.1 … G59.3",
     KeyType::Numbers,
     "mm, deg",
     "",
     {},
     "[X, Y, Z, A, B, C]",
     "all 0",
     false,
     "Machine coordinates of each work system's zero (the parameter file, when there is one, "
     "holds what programs and the HMI set since)."},
    // [tools.<N>]: read by its own loader.
    {"tools.<N>",
     "z_offset, x_offset, y_offset",
     KeyType::Number,
     "mm",
     "",
     {},
     "−1000 … 1000",
     "0",
     false,
     "Tool length offset applied by G43; N is the T word, 1 … 99999."},
    {"tools.<N>",
     "diameter",
     KeyType::Number,
     "mm",
     "",
     {},
     "0 … 1000",
     "0",
     false,
     "Kerf width used by cutter compensation."},
    {"tools.<N>",
     "description",
     KeyType::String,
     "",
     "",
     {},
     "a string",
     "\"\"",
     false,
     "What the tool (nozzle and lens set) is."},
};

const AxisKey kAxisKeys[] = {
    {"axes.<L>",
     "type",
     KeyType::String,
     "",
     "",
     {},
     "\"linear\" (X Y Z), \"rotary\" (A B C)",
     "by the letter",
     false,
     "Must match the axis letter; for readers of the file.",
     [](A& a, const KeyValue& v) {
       const std::string& t = std::get<std::string>(v);
       const std::string expected = is_rotary(a.axis) ? "rotary" : "linear";
       if (t == expected) return std::string();
       return "is \"" + t + "\"; axis " + letter(a.axis) + " must be \"" + expected + "\"";
     }},
    {"axes.<L>",
     "min",
     KeyType::Number,
     "mm",
     "deg",
     {},
     "min < max",
     "",
     true,
     "Low end of travel, machine coordinates.",
     &set_number<A, &A::min>},
    {"axes.<L>",
     "max",
     KeyType::Number,
     "mm",
     "deg",
     {},
     "min < max",
     "",
     true,
     "High end of travel, machine coordinates.",
     &set_number<A, &A::max>},
    {"axes.<L>", "max_velocity", KeyType::Number, "mm/s", "deg/s", above(0, 1e5),
     "at most the DDA's pulses per period", "", true, "The axis' speed limit.",
     &set_number<A, &A::max_velocity>, &get_number<A, &A::max_velocity>},
    {"axes.<L>", "max_acceleration", KeyType::Number, "mm/s²", "deg/s²", above(0, 1e7), "", "", true,
     "The axis' acceleration limit.", &set_number<A, &A::max_acceleration>,
     &get_number<A, &A::max_acceleration>},
    {"axes.<L>", "steps_per_unit", KeyType::Number, "steps/mm", "steps/deg", above(0, 1e6),
     "travel within 32-bit step counts", "1000", false, "Steps per mm or per degree.",
     &set_number<A, &A::steps_per_unit>, &get_number<A, &A::steps_per_unit>},
    {"axes.<L>",
     "wrap",
     KeyType::Boolean,
     "",
     "",
     {},
     "rotary axes with max − min = 360",
     "false",
     false,
     "Rotary, continuous: the position is kept in [min, max).",
     &set_bool<A, &A::wrap>},
    {"axes.<L>",
     "following_error",
     KeyType::Number,
     "mm",
     "deg",
     {},
     "0 (not checked) … max − min",
     "0",
     false,
     "Largest |commanded − measured| position before the machine stops with a following error "
     "(real drives with feedback only).",
     &set_number<A, &A::following_error>},
    {"axes.<L>",
     "home_position",
     KeyType::Number,
     "mm",
     "deg",
     {},
     "min … max",
     "min",
     false,
     "Machine coordinate where the home switch trips.",
     &set_optional<&A::home_position>},
    {"axes.<L>",
     "home_search_velocity",
     KeyType::Number,
     "mm/s",
     "deg/s",
     {},
     "−max_velocity … max_velocity, not 0",
     "−0.1 · max_velocity",
     false,
     "Speed of the search for the home switch; the sign is the direction toward it.",
     &set_optional<&A::home_search_velocity>},
    {"axes.<L>",
     "home_latch_velocity",
     KeyType::Number,
     "mm/s",
     "deg/s",
     {},
     "> 0 … |home_search_velocity|",
     "|home_search_velocity| / 10",
     false,
     "Speed of the slow second approach to the switch.",
     &set_optional<&A::home_latch_velocity>},
    {"axes.<L>",
     "pitch_compensation",
     KeyType::Table,
     "",
     "",
     {},
     "a table",
     "none",
     false,
     "Leadscrew pitch-error compensation: the table below."},
    {"axes.<L>.pitch_compensation",
     "start",
     KeyType::Number,
     "mm",
     "deg",
     {},
     "the table within min … max",
     "",
     true,
     "Position of values[0]."},
    {"axes.<L>.pitch_compensation",
     "interval",
     KeyType::Number,
     "mm",
     "deg",
     {},
     "> 0",
     "",
     true,
     "Distance between values."},
    {"axes.<L>.pitch_compensation",
     "values",
     KeyType::Numbers,
     "mm",
     "deg",
     {},
     "2 or more, each −1 … 1; slope within the DDA's pulses per period",
     "",
     true,
     "Correction added to the commanded position at start + k·interval, linear in between, the "
     "end values held outside."},
};

std::string fmt_bound(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e9) return std::to_string(static_cast<long long>(v));
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string_view type_name(KeyType t) {
  switch (t) {
    case KeyType::Number: return "number";
    case KeyType::Integer: return "integer";
    case KeyType::Boolean: return "boolean";
    case KeyType::String: return "string";
    case KeyType::Strings: return "array of strings";
    case KeyType::Numbers: return "array of numbers";
    case KeyType::Table: return "table";
  }
  return "";
}

// A table cell: '|' would end it.
std::string cell(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '|')
      out += "\\|";
    else
      out += c;
  }
  return out;
}

template <class C>
void print_rows(std::ostringstream& out, std::span<const ConfigKey<C>> keys) {
  std::string_view table;
  for (const ConfigKey<C>& k : keys) {
    if (k.table != table) {
      table = k.table;
      out << "\n### `[" << table << "]`\n\n"
          << "| key | type | unit | allowed | default | what it does |\n"
          << "| --- | --- | --- | --- | --- | --- |\n";
    }
    std::string unit(k.unit);
    if (!k.unit_rotary.empty()) unit += " (" + std::string(k.unit_rotary) + " on A B C)";
    const std::string_view type = type_name(k.type);
    std::string def = k.required ? "required" : std::string(k.default_value);
    std::string allowed = k.range.none ? std::string(k.allowed) : allowed_text(k);
    if (!k.range.none && !k.allowed.empty()) allowed += "; " + std::string(k.allowed);
    out << "| `" << k.name << "` | " << type << " | " << cell(unit) << " | " << cell(allowed) << " | "
        << cell(def) << " | " << cell(k.doc) << " |\n";
  }
}

}  // namespace

std::span<const MachineKey> machine_keys() { return kMachineKeys; }
std::span<const AxisKey> axis_keys() { return kAxisKeys; }

template <class C>
std::string allowed_text(const ConfigKey<C>& key, bool rotary) {
  const KeyRange& r = key.range;
  if (r.none) return std::string(key.allowed);
  const std::string_view unit = rotary && !key.unit_rotary.empty() ? key.unit_rotary : key.unit;
  std::string s = (r.lo_open ? "> " : "") + fmt_bound(r.lo) + " … " + fmt_bound(r.hi);
  if (!unit.empty()) s += " " + std::string(unit);
  if (r.or_zero) s += ", or 0: none";
  return s;
}
template std::string allowed_text(const MachineKey&, bool);
template std::string allowed_text(const AxisKey&, bool);

std::string config_reference_markdown() {
  std::ostringstream out;
  out << "# Machine config reference\n\n"
         "The machine config is a TOML file (`share/machines/default.toml` is the shipped\n"
         "machine; `--machine FILE` picks another). Every key of it is below; a key not\n"
         "listed is an error, as is a value of the wrong type or outside its range (the\n"
         "error names the file, line, key and the allowed range). `<L>` is an axis letter,\n"
         "X Y Z (linear, mm) or A B C (rotary, deg); `<N>` a tool number.\n\n"
         "Generated by `lasercnc config --reference`; do not edit by hand.\n";
  // [machine] [dda] [laser], the axes, then the tables read by their own
  // loaders ([kinematics] on).
  const std::span<const MachineKey> all = machine_keys();
  std::size_t own = 0;
  while (own < all.size() && all[own].set != nullptr) ++own;
  print_rows<MachineConfig>(out, all.first(own));
  print_rows<AxisConfig>(out, axis_keys());
  print_rows<MachineConfig>(out, all.subspan(own));
  return out.str();
}

}  // namespace lcnc
