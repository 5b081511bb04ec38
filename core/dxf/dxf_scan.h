// First pass over a DXF file, before dxflib sees it.
//
// dxflib parses leniently (a bad number reads as 0, a truncated file ends
// quietly) and reports no line numbers. So this pass reads the group
// code/value pairs itself and:
//  * rejects what is malformed, with file:line: a group code that is not an
//    integer, a number that does not parse, a value missing at the end, a
//    section never closed, no EOF, declared counts (LWPOLYLINE vertices,
//    SPLINE knots / control / fit points) that disagree with what follows;
//  * records the line of every entity the reader uses, per callback kind, in
//    file order — dxflib calls back in the same order, so the k-th addArc is
//    the k-th ARC here;
//  * reads $INSUNITS and $ACADVER;
//  * hands dxflib a filtered copy holding only the header version and the
//    BLOCKS and ENTITIES sections with the entity kinds used (no tables,
//    objects, hatches, texts, dimensions): less of the parser is exercised
//    on untrusted input, and nothing it would do with them matters here.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/result.h"

namespace lcnc::dxf {

struct ScanResult {
  std::string filtered;  // the DXF text dxflib reads
  // DXF line (1-based) of each entity's "0 / TYPE" pair, in file order, per
  // dxflib callback: addLine, addArc, addCircle, addPolyline (LWPOLYLINE and
  // POLYLINE both), addSpline, addInsert.
  std::vector<std::uint32_t> line_lines, arc_lines, circle_lines, poly_lines, spline_lines, insert_lines;
  std::vector<bool> poly_is_lw;  // per addPolyline: LWPOLYLINE (true) or POLYLINE
  int insunits = -1;             // $INSUNITS, -1 when absent
  // Entities skipped because they never cut (TEXT, DIMENSION, HATCH, ...):
  // "3 TEXT" — reported as notes, not errors.
  std::vector<std::string> ignored;
};

// `text` is the whole file; `file` names it in diagnostics.
[[nodiscard]] Result<ScanResult> scan_dxf(std::string_view text, const std::string& file);

}  // namespace lcnc::dxf
