// The process database's rows as CSV (docs/design.md §6): what `lasercnc drill`
// runs, and the import/export format of the HMI's process database.
//
//   hole,x_mm,y_mm,z_mm,a_deg,c_deg,feed_mm_min,layer_feed_mm,layer_count,
//   total_depth_mm,power_pct,start_radius_mm,end_radius_mm,radius_turns,
//   scan_speed_mm_s,wedge_speed_rpm,beam_offset_mm,process,shape
//
// One header line with exactly these names (in any order; `shape` may be
// left out when no row is a free shape), then one row per hole, fields 1–18
// in the units of the names. `process` is 0/helix, 1/circle or 2/free_shape.
// `shape` is the free shape's polygon about the hole centre,
// `r@angle` pairs separated by `;` (mm @ deg), empty for the other
// processes. Blank lines and lines starting with `#` are skipped.
//
// Every row is checked as the hole processes need it (hole_processes.h:
// validate) and hole numbers must be unique. The first problem is an error
// `file:line:col` naming the column and what was expected; nothing is
// returned then.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/result.h"
#include "holes/hole_processes.h"

namespace lcnc {

// Parses CSV text (`file` names it in errors). `row_lines`, if given, gets
// the 1-based line of each row (for errors found later, e.g. the travel).
[[nodiscard]] Result<std::vector<HoleProcessParams>> parse_hole_table(
    std::string_view text, const std::string& file, std::vector<std::uint32_t>* row_lines = nullptr);
[[nodiscard]] Result<std::vector<HoleProcessParams>> read_hole_table(
    const std::string& path, std::vector<std::uint32_t>* row_lines = nullptr);
// The rows as CSV (with the header); parse_hole_table reads it back exactly
// (numbers with 17 significant digits).
[[nodiscard]] std::string write_hole_table(const std::vector<HoleProcessParams>& rows);

}  // namespace lcnc
