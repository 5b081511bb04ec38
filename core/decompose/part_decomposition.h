// A whole part, DXF drawing to kinematics tables (docs/design.md §5.7, Kondratenko et al. (2015) Fig. 4):
// chain the entities into contours → discretize every contour with the
// user's step → check every contour closed and free of crossings → decompose
// each contour (seed or synchronous mode). Nothing is decomposed unless the
// whole drawing passes the checks.
#pragma once

#include <string>
#include <vector>

#include "common/result.h"
#include "decompose/decompose_options.h"
#include "decompose/kinematics_table.h"
#include "dxf/discretize.h"
#include "dxf/drawing.h"

namespace lcnc::decompose {

struct ContourResult {
  dxf::Contour contour;
  dxf::Polyline polyline;
  KinematicsTable table;
  Peaks peaks;
  double tau_s = 0.0;  // Sync: the main-path filter's half-width
  // Seed mode: which limits the table breaks (the paper's method guarantees none);
  // empty when it keeps them all. Sync mode: always empty.
  std::vector<std::string> exceeded;
};

struct PartResult {
  std::vector<ContourResult> contours;
  std::size_t points = 0;  // contour points decomposed
};

[[nodiscard]] Result<PartResult> decompose_part(const dxf::Drawing& d, double step_mm, const Options& opt);

// Checks the options (speeds, limits, field, angle > 0; in sync mode a
// contour speed the two axis groups can reach together); the error names the
// first bad one.
[[nodiscard]] Status check_options(const Options& opt);

// DecomposeTooLarge when the contours at `step_mm` would make more than
// kMaxPartPoints points (estimated from their lengths, before anything is
// allocated); the message gives the length, the points and the units.
[[nodiscard]] Status check_part_size(const dxf::Drawing& d, const std::vector<dxf::Contour>& contours,
                                     double step_mm);

// The part's contours prepared for decomposition (chained, discretized,
// checked) — decompose_part's first half, for callers that time the halves.
struct PreparedPart {
  std::vector<dxf::Contour> contours;
  std::vector<dxf::Polyline> polylines;
};
[[nodiscard]] Result<PreparedPart> prepare_part(const dxf::Drawing& d, double step_mm);
[[nodiscard]] Result<PartResult> decompose_prepared(const PreparedPart& p, const Options& opt);

}  // namespace lcnc::decompose
