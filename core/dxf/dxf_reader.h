// Reading a DXF drawing (docs/design.md §5.7, Kondratenko et al. (2015) "DXF input"): LINE, ARC,
// CIRCLE, LWPOLYLINE and POLYLINE (bulges as arcs), SPLINE (NURBS, sampled at
// exact arc lengths), INSERT of blocks (base point, scale, rotation, column
// and row arrays, nested), in the drawing's units ($INSUNITS) converted to mm.
// 2D entities in a mirrored object coordinate system (extrusion 0,0,−1, as
// many CAD programs write mirrored arcs) are mapped back to the XY plane.
//
// Pipeline: dxf_scan (structure, numbers, line numbers; malformed → error
// with file:line) → dxflib (entities) → blocks expanded → Drawing. Errors
// name the file, the DXF line of the entity and what was expected. Entities
// that never cut (text, dimensions, hatches, paper space) are skipped and
// listed in `notes`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "common/result.h"
#include "dxf/drawing.h"

namespace lcnc::dxf {

struct ReadOptions {
  // mm per drawing unit; 0 = from $INSUNITS (unitless drawings read as mm).
  double unit_mm = 0.0;
};

struct ReadResult {
  Drawing drawing;
  std::vector<std::string> notes;  // "ignored: 3 TEXT", "units: inch (25.4 mm)"
};

[[nodiscard]] Result<ReadResult> read_dxf_file(const std::string& path, const ReadOptions& opt = {});
// The same from text in memory; `file` names it in diagnostics.
[[nodiscard]] Result<ReadResult> read_dxf_text(std::string_view text, const std::string& file,
                                               const ReadOptions& opt = {});

// mm per unit of a $INSUNITS code; 0 when the code is not a length unit.
[[nodiscard]] double insunits_mm(int code, std::string* name);

}  // namespace lcnc::dxf
