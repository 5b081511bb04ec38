// The 18 fields of a hole's process record (process DB row, hole-table CSV
// column, Modbus parameter block register): the one table that names them,
// gives their units and ranges and reaches them in HoleProcessParams.
// validate() checks the ranges from it, the CSV reader and writer take their
// columns from it, the process database builds its schema, insert and select
// from it, and the CNC's Modbus slave maps its parameter block with it. A
// test holds share/modbus/register_map.toml to it, field by field.
//
// Ranges are the allowed values in the field's unit, lo … hi inclusive
// (lo excluded where `lo_open`: a hole needs a feed and a layer depth).
// Cross-field rules (total depth = layer count · layer feed, a circle scan
// across radii needs two or more turns, the free-shape polygon) stay in
// validate(); the table holds what one field alone must satisfy.
//
// Fields 12–17 are the scanning head's parameter block, written to the head
// as a whole before the hole: their ranges are the head's (register map
// device scan_head, the HMI's adjust page), since a value the head refuses
// is a hole that cannot be made. The beam offset in particular is ±2 mm
// (kMaxBeamOffsetMm, hole_processes.h, which says why).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "holes/hole_processes.h"

namespace lcnc {

enum class HoleFieldType : std::uint8_t {
  Count,    // a whole number ≥ 0 (hole number, layer count, radius turns)
  Real,     // a number in the field's unit
  Process,  // HoleProcessId: 0 helix, 1 circle, 2 free shape
};

struct HoleField {
  int number;                      // 1 … 18 (docs/design.md §6)
  std::string_view column;         // CSV header and SQL column
  std::string_view register_name;  // register of the "cnc" device's parameter block
  std::string_view label;          // in messages: "field 17 beam offset"
  HoleFieldType type;
  std::string_view unit;  // "" for counts and the process id
  double lo;
  double hi;
  bool lo_open;      // lo itself is not allowed
  bool scan_radius;  // fields 12–13: not used (nor checked) by a free shape
  double (*get)(const HoleProcessParams&);
  void (*set)(HoleProcessParams&, double);
  std::string_view doc;
};

namespace hole_fields_detail {
template <typename T>
constexpr double to_double(T v) {
  if constexpr (std::is_enum_v<T>)
    return static_cast<double>(static_cast<std::underlying_type_t<T>>(v));
  else
    return static_cast<double>(v);
}
// Counts and the process id from a number already range-checked by its
// source (register map, SQL CHECK); out of reach values saturate, never UB.
template <typename T>
constexpr T from_double(double v) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<T>(v);
  } else if constexpr (std::is_enum_v<T>) {
    return static_cast<T>(from_double<std::underlying_type_t<T>>(v));
  } else {
    if (!(v >= 0.0)) return T{0};
    constexpr T kMax = std::numeric_limits<T>::max();
    if (v >= static_cast<double>(kMax)) return kMax;
    return static_cast<T>(v);
  }
}
template <auto M>
constexpr double get(const HoleProcessParams& p) {
  return to_double(p.*M);
}
template <auto M>
constexpr void set(HoleProcessParams& p, double v) {
  p.*M = from_double<std::remove_reference_t<decltype(p.*M)>>(v);
}
template <auto M>
constexpr double get_head(const HoleProcessParams& p) {
  return to_double(p.head.*M);
}
template <auto M>
constexpr void set_head(HoleProcessParams& p, double v) {
  p.head.*M = from_double<std::remove_reference_t<decltype(p.head.*M)>>(v);
}
// Fields 2–6: X Y Z A C of the X Y Z A B C pose.
template <Axis A>
constexpr double get_pose(const HoleProcessParams& p) {
  return p.position[index(A)];
}
template <Axis A>
constexpr void set_pose(HoleProcessParams& p, double v) {
  p.position[index(A)] = v;
}
}  // namespace hole_fields_detail

// number, column, register, label, type, unit, lo, hi, lo_open, scan_radius,
// get, set, doc
inline constexpr std::array<HoleField, 18> kHoleFields = {{
    {1, "hole", "hole_number", "hole number", HoleFieldType::Count, "", 1, kMaxHoleNumber, false, false,
     hole_fields_detail::get<&HoleProcessParams::hole_number>,
     hole_fields_detail::set<&HoleProcessParams::hole_number>, "hole number, the row's key"},
    {2, "x_mm", "hole_x_mm", "X", HoleFieldType::Real, "mm", 0, 1000, false, false,
     hole_fields_detail::get_pose<Axis::X>, hole_fields_detail::set_pose<Axis::X>,
     "hole centre X (the travel)"},
    {3, "y_mm", "hole_y_mm", "Y", HoleFieldType::Real, "mm", 0, 450, false, false,
     hole_fields_detail::get_pose<Axis::Y>, hole_fields_detail::set_pose<Axis::Y>, "hole centre Y"},
    {4, "z_mm", "hole_z_mm", "Z", HoleFieldType::Real, "mm", 0, 500, false, false,
     hole_fields_detail::get_pose<Axis::Z>, hole_fields_detail::set_pose<Axis::Z>, "hole centre Z"},
    {5, "a_deg", "hole_a_deg", "A", HoleFieldType::Real, "deg", -95, 95, false, false,
     hole_fields_detail::get_pose<Axis::A>, hole_fields_detail::set_pose<Axis::A>, "tool axis tilt A"},
    {6, "c_deg", "hole_c_deg", "C", HoleFieldType::Real, "deg", 0, 359.999, false, false,
     hole_fields_detail::get_pose<Axis::C>, hole_fields_detail::set_pose<Axis::C>, "tool axis rotation C"},
    {7, "feed_mm_min", "feed_mm_min", "feed rate", HoleFieldType::Real, "mm/min", 0, kMaxHoleFeedMmMin, true,
     false, hole_fields_detail::get<&HoleProcessParams::feed_mm_min>,
     hole_fields_detail::set<&HoleProcessParams::feed_mm_min>, "feed along the hole path (a hole needs one)"},
    {8, "layer_feed_mm", "layer_feed_mm", "single-layer feed", HoleFieldType::Real, "mm", 0, kMaxLayerFeedMm,
     true, false, hole_fields_detail::get<&HoleProcessParams::layer_feed_mm>,
     hole_fields_detail::set<&HoleProcessParams::layer_feed_mm>, "Z per helix turn / layer"},
    {9, "layer_count", "layer_count", "layer count", HoleFieldType::Count, "", 1, kMaxLayerCount, false,
     false, hole_fields_detail::get<&HoleProcessParams::layer_count>,
     hole_fields_detail::set<&HoleProcessParams::layer_count>, "layers (helix turns) to the total depth"},
    {10, "total_depth_mm", "total_depth_mm", "total depth", HoleFieldType::Real, "mm", 0, kMaxTotalDepthMm,
     false, false, hole_fields_detail::get<&HoleProcessParams::total_depth_mm>,
     hole_fields_detail::set<&HoleProcessParams::total_depth_mm>, "layer count × single-layer feed"},
    {11, "power_pct", "laser_power_pct", "laser power", HoleFieldType::Real, "%", 0, 100, false, false,
     hole_fields_detail::get<&HoleProcessParams::power_pct>,
     hole_fields_detail::set<&HoleProcessParams::power_pct>, "% of rated power"},
    {12, "start_radius_mm", "scan_start_radius_mm", "start radius", HoleFieldType::Real, "mm", 0,
     kMaxScanRadiusMm, true, true, hole_fields_detail::get_head<&ScanHeadParams::start_radius_mm>,
     hole_fields_detail::set_head<&ScanHeadParams::start_radius_mm>, "scan radius at the entry (first ring)"},
    {13, "end_radius_mm", "scan_end_radius_mm", "end radius", HoleFieldType::Real, "mm", 0, kMaxScanRadiusMm,
     true, true, hole_fields_detail::get_head<&ScanHeadParams::end_radius_mm>,
     hole_fields_detail::set_head<&ScanHeadParams::end_radius_mm>, "scan radius at the exit (last ring)"},
    {14, "radius_turns", "scan_radius_turns", "radius turns", HoleFieldType::Count, "", 1, kMaxRadiusTurns,
     false, false, hole_fields_detail::get_head<&ScanHeadParams::radius_turns>,
     hole_fields_detail::set_head<&ScanHeadParams::radius_turns>, "rings per layer (circle scan)"},
    {15, "scan_speed_mm_s", "scan_speed_mm_s", "scan speed", HoleFieldType::Real, "mm/s", 0, kMaxScanSpeedMmS,
     false, false, hole_fields_detail::get_head<&ScanHeadParams::scan_speed_mm_s>,
     hole_fields_detail::set_head<&ScanHeadParams::scan_speed_mm_s>, "beam speed on the workpiece"},
    {16, "wedge_speed_rpm", "wedge_speed_rpm", "wedge speed", HoleFieldType::Real, "rpm", 0,
     kMaxWedgeSpeedRpm, false, false, hole_fields_detail::get_head<&ScanHeadParams::wedge_speed_rpm>,
     hole_fields_detail::set_head<&ScanHeadParams::wedge_speed_rpm>, "wedge rotation speed"},
    {17, "beam_offset_mm", "beam_offset_mm", "beam offset", HoleFieldType::Real, "mm", -kMaxBeamOffsetMm,
     kMaxBeamOffsetMm, false, false, hole_fields_detail::get_head<&ScanHeadParams::beam_offset_mm>,
     hole_fields_detail::set_head<&ScanHeadParams::beam_offset_mm>, "lateral beam offset in the head"},
    {18, "process", "process_id", "process id", HoleFieldType::Process, "", 0, 2, false, false,
     hole_fields_detail::get<&HoleProcessParams::process>,
     hole_fields_detail::set<&HoleProcessParams::process>, "0 helix, 1 circle, 2 free shape"},
}};

// The scanning head's parameter block (fields 12–17) as the head's
// registers take it: (register of the scan_head device, which is the field's
// column name; value), in field order.
[[nodiscard]] std::vector<std::pair<std::string, double>> scan_head_block(const ScanHeadParams& head);

// The field of a CSV/SQL column or of a register name; nullopt when none.
[[nodiscard]] std::optional<std::size_t> hole_field_by_column(std::string_view column) noexcept;
[[nodiscard]] std::optional<std::size_t> hole_field_by_register(std::string_view name) noexcept;

// Whether `value` is allowed in field `f` (finite, in lo … hi).
[[nodiscard]] bool hole_field_in_range(const HoleField& f, double value) noexcept;
// "field 17 beam offset = 3 mm; allowed -2 … 2 mm" (the process id lists its values).
[[nodiscard]] std::string hole_field_range_message(const HoleField& f, double value);
// The shortest decimal that reads back exactly, for people.
[[nodiscard]] std::string shortest_number_text(double value);
// The value as text: whole numbers for counts and the process id, else
// shortest_number_text().
[[nodiscard]] std::string hole_field_text(const HoleField& f, double value);

}  // namespace lcnc
