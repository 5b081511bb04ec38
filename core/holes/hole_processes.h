// Hole processes of the process database (docs/design.md §6, field 18; Shao (2022) §4,
// Table 1): one process-DB row → the tool-tip motion that makes the hole,
// plus the laser and four-beam scanning-head events at the moments they
// apply.
//
// Frame. The motion is generated in the hole frame: origin at the hole
// centre on the surface (fields 2–4), +z along the tool axis out of the
// material (so the hole goes toward −z), x and y turned with the head:
//   workpiece = hole_frame(row) · local,  hole_frame = Trans(X, Y, Z)·Rz(C)·Rx(A)
// (the tool axis of five_axis.h). Arcs are G17 (XY) arcs and helices about
// the hole axis, counter-clockwise; every pose carries the row's A and C
// (constant over the hole). FiveAxisKinematics::tip_to_joints() maps the
// tip path to joints at that A, C (on a table-table machine the hole axis
// becomes machine Z, and the arcs stay G17 arcs).
//
// Depth. Layer k (1 … layer_count) is cut at z = −k·layer_feed, so the last
// layer reaches −total_depth = −layer_count·layer_feed (the two must agree
// within 1 µm: fields 8, 9, 10 are stored independently).
//
// Processes:
// * Helix (0): one helical turn per layer, from z = 0 down to −total_depth,
//   at the scan radius. With start_radius ≠ end_radius the hole tapers:
//   layer k runs at r_k = start + (end − start)·(k−1)/(layers−1) and a short
//   radial line joins the layers. Equal radii give a single helix segment of
//   layer_count turns.
// * Circle (1): per layer, a step down along the axis, then radius_turns
//   full circles from start_radius to end_radius (equal steps; concentric
//   rings filling the annulus), joined by radial lines.
// * FreeShape (2): per layer, a step down, then the closed polygon of the
//   `shape` vertices (polar: radius, angle about the hole centre).
//   Vertices in increasing angle with gaps below 180° (the centre is inside
//   and the polygon is simple).
//
// Events: the head parameter block (fields 12–17) before the first segment
// (the approach rapid), LaserOn at the row's power before the first cutting
// segment, LaserOff after the last. The scanning radius of fields 12–13 is
// the radius of the pattern here; whether the axes or the head's wedges
// trace it is the head's mode, not this generator's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "common/result.h"
#include "geom/pose.h"
#include "path/segment.h"

namespace lcnc {

enum class HoleProcessId : std::uint8_t { Helix = 0, Circle = 1, FreeShape = 2 };

[[nodiscard]] const char* process_name(HoleProcessId id) noexcept;

// Four-beam wedge scanning head (fields 12–17): one parameter block, written
// to the head as a whole (Modbus function 16 on the peripheral side).
struct ScanHeadParams {
  double start_radius_mm = 0.5;     // 12: scan radius at the entry (first ring)
  double end_radius_mm = 0.5;       // 13: scan radius at the exit (last ring)
  std::uint32_t radius_turns = 1;   // 14: rings per layer (circle scan; others ignore it)
  double scan_speed_mm_s = 10.0;    // 15: beam speed on the workpiece
  double wedge_speed_rpm = 3000.0;  // 16: wedge rotation speed
  double beam_offset_mm = 0.0;      // 17: lateral beam offset
};

// A vertex of a free-shape hole, polar about the hole centre.
struct PolarVertex {
  double radius_mm = 0.0;
  double angle_deg = 0.0;
};

// The fields of one process-DB row that the generator uses (docs/design.md §6).
struct HoleProcessParams {
  std::uint32_t hole_number = 1;                 // 1
  Pose position = Pose::Zero();                  // 2–6: X Y Z (mm) and A, C (deg) of the hole centre
  double feed_mm_min = 600.0;                    // 7
  double layer_feed_mm = 0.1;                    // 8: depth per layer / helix turn
  std::uint32_t layer_count = 1;                 // 9
  double total_depth_mm = 0.1;                   // 10
  double power_pct = 50.0;                       // 11
  ScanHeadParams head{};                         // 12–17
  HoleProcessId process = HoleProcessId::Helix;  // 18
  std::vector<PolarVertex> shape;                // FreeShape only
};

// Ranges (docs/design.md §6) and the ones the geometry needs.
inline constexpr std::uint32_t kMaxHoleNumber = 10000;
inline constexpr double kMaxHoleFeedMmMin = 2000.0;
inline constexpr double kMaxLayerFeedMm = 1.0;
inline constexpr std::uint32_t kMaxLayerCount = 10000;
// Fields 12–17 are the scanning head's parameter block, written to the head
// as a whole before the hole, so their ranges are the head's: a value the
// head refuses is a hole that cannot be made (see holes/hole_fields.h).
inline constexpr double kMaxTotalDepthMm = 500.0;  // the Z travel
inline constexpr double kMaxScanRadiusMm = 5.0;
inline constexpr std::uint32_t kMaxRadiusTurns = 1000;
inline constexpr double kMaxScanSpeedMmS = 5000.0;
inline constexpr double kMaxWedgeSpeedRpm = 30000.0;
// The beam offset moves the four beams sideways in the head's exit optics by
// a fraction of the scan radius: ±2 mm, as the head takes it (its register,
// i16 at 1 µm, could not carry more than ±32.767 mm in any case).
inline constexpr double kMaxBeamOffsetMm = 2.0;
// A free shape's vertices, polar about the hole centre (traced by the axes).
inline constexpr double kMaxShapeRadiusMm = 50.0;
inline constexpr std::size_t kMaxShapeVertices = 1000;
// total_depth must equal layer_count · layer_feed within this (mm).
inline constexpr double kDepthTolerance = 0.001;

enum class HoleEventKind : std::uint8_t {
  HeadParameters,  // write `head` to the scanning head
  LaserOn,         // laser on at power_pct
  LaserOff,
};

struct HoleEvent {
  HoleEventKind kind = HoleEventKind::LaserOff;
  std::size_t before_segment = 0;  // takes effect before this segment (size(): after the last)
  double power_pct = 0.0;          // LaserOn
  ScanHeadParams head{};           // HeadParameters
};

struct HoleProgram {
  std::vector<Segment> segments;  // hole frame (see above); poses carry the row's A, C
  std::vector<HoleEvent> events;  // in order of before_segment
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  // hole frame → workpiece
};

// Checks every field against its range (holes/hole_fields.h) and the
// geometry's needs; the error (GcodeBadValue) names the hole, the field
// number and name, the value and the allowed range.
[[nodiscard]] Status validate(const HoleProcessParams& params);

// hole_frame above.
[[nodiscard]] Eigen::Isometry3d hole_frame(const HoleProcessParams& params);

// The hole's motion and events (validated first).
[[nodiscard]] Result<HoleProgram> generate_hole(const HoleProcessParams& params);

}  // namespace lcnc
