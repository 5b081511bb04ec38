// The machine: axes with travel and limits, RT period, DDA preset, laser and
// work offsets. Loaded from TOML (share/machines/default.toml) and validated
// on load; every error names the key, the value and the allowed range.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/result.h"
#include "geom/pose.h"
#include "kinematics/five_axis_geometry.h"

namespace lcnc {

// A leadscrew pitch-error table: values[k] is the correction added to the
// commanded position at start + k·interval. Between points the correction is
// linear, outside the table the end values hold:
//   at(x) = values[0]                           for x ≤ start
//         = values[k] + (values[k+1] − values[k])·(x − x_k)/interval
//                                              for x_k ≤ x ≤ x_k+1, x_k = start + k·interval
//         = values[n−1]                         for x ≥ start + (n−1)·interval
// Units are the axis' (mm or deg) in the config; rt/pitch_compensation.h and
// the simulated machine use the same table scaled to steps. Empty = none.
struct PitchTable {
  double start = 0.0;          // position of values[0]
  double interval = 0.0;       // distance between values, > 0
  std::vector<double> values;  // correction at start + k·interval

  [[nodiscard]] bool empty() const noexcept { return values.empty(); }
  [[nodiscard]] double end() const noexcept {
    return values.empty() ? start : start + interval * static_cast<double>(values.size() - 1);
  }
  // at(x) above. noexcept and allocation-free: safe on the RT path.
  [[nodiscard]] double at(double x) const noexcept;
  // Largest |Δvalue / Δposition| over the table (dimensionless; 0 when empty).
  [[nodiscard]] double max_slope() const noexcept;
  // The same table with positions and values multiplied by k (e.g. by
  // steps_per_unit to work in steps). k > 0.
  [[nodiscard]] PitchTable scaled(double k) const;
};

struct AxisConfig {
  bool present = false;
  Axis axis = Axis::X;
  double min = 0.0;                // mm or deg (machine coordinates)
  double max = 0.0;                // mm or deg
  double max_velocity = 0.0;       // mm/s or deg/s
  double max_acceleration = 0.0;   // mm/s² or deg/s²
  double steps_per_unit = 1000.0;  // steps per mm or per degree
  bool wrap = false;               // rotary, continuous: position kept in [min, max)
  // Largest |commanded − measured| position before the machine stops with a
  // following error naming the axis, mm or deg; 0: not checked (a machine
  // without feedback, as the simulated one). Only where there is feedback:
  // the HAL component's pos-fb pins.
  double following_error = 0.0;

  // Homing. Each is optional in the TOML; when not given the default is
  // derived from the other keys by the *_or_default() functions below, so a
  // config built in code, or one whose max_velocity is changed after loading
  // (--vmax), keeps consistent defaults.
  std::optional<double> home_position;         // machine coordinate of the home switch's trip point
  std::optional<double> home_search_velocity;  // mm/s or deg/s; sign = direction toward the switch
  std::optional<double> home_latch_velocity;   // > 0: the slow second approach to the switch
  // Leadscrew pitch-error compensation, mm or deg (empty = none).
  PitchTable pitch_compensation{};

  // Default min: the switch sits at the low end of travel.
  [[nodiscard]] double home_position_or_default() const noexcept { return home_position.value_or(min); }
  // Default −0.1·max_velocity: toward min at a tenth of full speed.
  [[nodiscard]] double home_search_velocity_or_default() const noexcept {
    return home_search_velocity.value_or(-0.1 * max_velocity);
  }
  // Default |search| / 10.
  [[nodiscard]] double home_latch_velocity_or_default() const noexcept {
    const double search = home_search_velocity_or_default();
    return home_latch_velocity.value_or((search < 0.0 ? -search : search) / 10.0);
  }
};

// Largest |pitch correction| accepted, mm or deg: a real leadscrew's error is
// tens of µm; anything near a millimetre is a typo or a wrong unit.
inline constexpr double kMaxPitchCorrection = 1.0;
// Slack for the table's end landing on max through rounding of
// start + (n−1)·interval, relative to max(1, |limit|).
inline constexpr double kPitchTableEndTolerance = 1e-9;

// DDA fine interpolation preset (docs/design.md §5.4). The period is capacity ticks of
// the DDA clock, so clock_hz = capacity / period.
struct DdaConfig {
  std::uint32_t magnitude_bits = 4;  // pulses per period: 0 .. 2^bits - 1
  std::uint32_t capacity = 30;       // N: clock ticks per period

  [[nodiscard]] std::uint32_t max_pulses() const noexcept { return (1u << magnitude_bits) - 1u; }
};

struct LaserConfig {
  double s_max = 100.0;  // S word value meaning 100 % power
};

// The work coordinate systems: G54 … G59, G59.1 … G59.3 (LinuxCNC's nine).
inline constexpr int kWorkOffsetCount = 9;
inline constexpr std::array<const char*, kWorkOffsetCount> kWorkOffsetNames = {
    "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"};

// A tool of the tool table (LinuxCNC's): on a laser, a nozzle and lens set.
// G43 applies its offset (machine = program + offsets + tool offset); its
// diameter is the kerf width cutter compensation will use.
struct ToolConfig {
  int number = 0;              // the T word: 1 … kMaxToolNumber
  Pose offset = Pose::Zero();  // tool length offset: X Y Z mm (A B C stay 0)
  double diameter_mm = 0.0;
  std::string description;
};
inline constexpr int kMaxToolNumber = 99999;
// Largest |tool offset| and diameter, mm: a nozzle is not a metre long.
inline constexpr double kMaxToolOffsetMm = 1000.0;

// machine.max_jerk range, mm/s³ (0.001 … 10⁷ m/s³). Below the minimum the
// filter's window would grow past ~10⁵ periods.
inline constexpr double kMinMaxJerk = 1.0;
inline constexpr double kMaxMaxJerk = 1e10;

[[nodiscard]] inline std::array<Pose, kWorkOffsetCount> zero_work_offsets() {
  std::array<Pose, kWorkOffsetCount> z;
  for (Pose& p : z) p.setZero();
  return z;
}

struct MachineConfig {
  std::string name = "default";
  std::uint32_t period_ns = 75'000;
  double path_tolerance_mm = 0.01;  // default G64 P when P is not given
  // Modal codes every program starts with, as if its first line
  // (LinuxCNC's RS274NGC_STARTUP_CODE): only G17 G18 G19 G20 G21 G90 G91
  // G90.1 G91.1 G93 G94 G54…G59 G61 G61.1 G64 [P Q] G40 G49 G80 M5 M9. Empty: G17 G21
  // G90 G91.1 G94 G54 G61 M5 M9. The shipped machine starts in G64, so a
  // CAM file without one blends within path_tolerance_mm.
  std::string startup_code;
  // Block delete (LinuxCNC's switch, on by default there): a line that
  // starts with '/' is skipped. false: such lines run like any other.
  bool block_delete = true;
  // The work budget of one reading of a program: its moves, dwells and
  // pauses counted, and its machine time at the programmed feeds (rapids at
  // the fastest axis, dwells as long as they are). A loop that would run
  // past either is an error at its line, so a check always ends. Far above
  // any real program: the longest a load takes (4 GiB, some 100 million
  // lines) and a week of cutting.
  double program_segment_limit = 200e6;
  double program_time_limit_s = 7 * 24 * 3600.0;
  // M1 pauses a program like M0 when on (LinuxCNC's optional stop switch);
  // off, M1 is passed over.
  bool optional_stop = true;
  // The G-code the machine's programs are written in: RS274NGC (LinuxCNC's,
  // the default) or grbl's, as hobby laser design tools (LightBurn) write
  // it: S is 0 … 1000 unless [laser] s_max says otherwise (grbl's $30), M4
  // is its dynamic power (as here), and a grbl system command line ($H,
  // $X, $32=1 …) is passed over with a warning: it configures a grbl
  // board, not the job.
  enum class Dialect : std::uint8_t { Rs274ngc, Grbl };
  Dialect dialect = Dialect::Rs274ngc;
  // Folders searched, after the program's own, for the file <name>.ngc of a
  // subroutine o<name> called before it is defined (LinuxCNC's
  // SUBROUTINE_PATH). A relative folder is taken from the config file's.
  std::vector<std::string> subroutine_path;
  // The file that keeps the work offsets (G10, G92, G28.1 / G30.1 positions:
  // LinuxCNC's parameters #5161 … #5390) and the tool table's changes
  // (G10 L1/L10/L11) from one job to the next, as LinuxCNC's PARAMETER_FILE.
  // A relative path is taken from the config file's folder. Empty: none;
  // every job starts from [work_offsets] and [tools].
  std::string parameter_file;
  // The highest feed override the operator may set (1 = 100 %). No derate:
  // the plan is at the axes' limits; above 100 % the planner plans the feed
  // moves faster within them, below it the RT scales the period
  // (rt/feed_override.h).
  double max_feed_override = 1.0;
  // Real drives (the HAL component) come up unhomed, and a job is refused
  // until every axis is homed. true: a machine without home switches runs
  // from where it stands at power-on, which the daemon says loudly at start
  // and in every job's start answer. The simulated machine's position is
  // always known.
  bool allow_unhomed = false;
  // Jerk limit of the linear axes, mm/s³ (S-curve acceleration by a moving
  // average of the planned path, plan/jerk_filter.h); 0 = none. Planned, like
  // the acceleration, for the highest override: J/K_max³.
  double max_jerk = 0.0;
  DdaConfig dda{};
  LaserConfig laser{};
  // [kinematics]: head-head or table-table, and the offsets (mm); the
  // tool-centre-point control of programs.
  FiveAxisGeometry kinematics{};
  TcpConfig tcp{};
  std::array<AxisConfig, kAxisCount> axes{};
  // G54 … G59.3, machine coords of work zero. Zeroed explicitly: `{}` leaves
  // an Eigen matrix uninitialised. The parameter file, when there is one,
  // holds the offsets programs and the HMI set since.
  std::array<Pose, kWorkOffsetCount> work_offsets = zero_work_offsets();
  // [tools.N], sorted by number.
  std::vector<ToolConfig> tools;

  [[nodiscard]] const AxisConfig& axis(Axis a) const { return axes[index(a)]; }
  [[nodiscard]] AxisConfig& axis(Axis a) { return axes[index(a)]; }
  [[nodiscard]] double period_s() const noexcept { return period_ns * 1e-9; }
  [[nodiscard]] double dda_clock_hz() const noexcept { return dda.capacity / period_s(); }
};

// Validates the whole config (ranges and consistency, e.g. that an axis at its
// max velocity needs no more pulses per period than the DDA preset gives).
[[nodiscard]] Status validate(const MachineConfig& config, const std::string& file = {});

// Loads and validates a TOML machine config.
[[nodiscard]] Result<MachineConfig> load_machine_config(const std::string& path);
[[nodiscard]] Result<MachineConfig> parse_machine_config(std::string_view toml_text,
                                                         const std::string& source_name);

}  // namespace lcnc
