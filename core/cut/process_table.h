// The cutting process per DXF layer: feed, laser power, pierce time and
// kerf width, read from a small CSV table (lasercnc cut --process FILE).
//
//   # comments and blank lines are skipped
//   layer,feed_mm_min,power_pct,pierce_s,kerf_mm     <- optional header
//   CUT,3000,80,0.5,0.2
//   ENGRAVE,6000,20,,0.1                             <- empty: the default
//
// Layer names match exactly (case-sensitive, as DXF keeps them; spaces
// around fields are trimmed). A layer not in the table, and an empty field,
// take the command line's defaults (--feed, --power, --pierce, --kerf).
// Errors name file:line and the field: feed > 0, 0 ≤ power ≤ 100,
// pierce ≥ 0, kerf ≥ 0, a layer listed once.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "common/result.h"

namespace lcnc::cut {

struct Process {
  double feed_mm_min = 3000.0;
  double power_pct = 80.0;
  double pierce_s = 0.5;
  double kerf_mm = 0.2;
};

struct ProcessTable {
  Process defaults;
  std::map<std::string, Process, std::less<>> layers;

  [[nodiscard]] const Process& for_layer(std::string_view layer) const {
    const auto it = layers.find(layer);
    return it == layers.end() ? defaults : it->second;
  }
};

// The rows of `text` on top of `defaults`; `file` names it in errors.
[[nodiscard]] Result<ProcessTable> parse_process_table(std::string_view text, const std::string& file,
                                                       const Process& defaults);
[[nodiscard]] Result<ProcessTable> read_process_table(const std::string& path, const Process& defaults);

// The first value out of range (feed ≤ 0, power outside 0–100, pierce or
// kerf < 0, any not finite) as "what: found; expected", or empty.
[[nodiscard]] std::string check_process(const Process& p);

}  // namespace lcnc::cut
