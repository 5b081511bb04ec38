// The time-synchronous decomposition (docs/design.md §5.7).
//
// The beam runs the contour S at constant speed vk: with Δ the discretization
// step, point k is reached at t_k = kΔt, Δt = Δ/vk (before and after, the
// beam stands at point 0, laser off). The main path is S filtered by two
// moving averages of m samples (a triangle of half-width τ = mΔt):
//   S1[i] = Σ_{|k|<m} (m − |k|)/m² · S[i + k]
// and the auxiliary axes take the rest, S2[i] = S[i] − S1[i], so
// S1 + S2 = S holds at every row (to rounding, ~1e-12 mm) and, with both
// interpolated linearly, at every instant in between.
//
// Why this filter: its second difference is a single second difference of S,
//   a1[i] = (S[i+m] − 2S[i] + S[i−m]) / τ²,
// so |a1| ≤ 2vk/τ for any contour (|S[i±m] − S[i]| ≤ vkτ), |v1| ≤ vk, and the
// auxiliary offset is at most vkτ/3 (|S2| ≤ Δ(m² − 1)/(3m)), its speed at
// most 2vk. And because S is linear between samples and τ is a whole number
// of samples, a1 is linear between rows: its largest value over all time is
// the largest row — checking the table checks the motion. The main path
// starts at rest m samples before the beam moves and ends at rest m samples
// after; main acceleration is continuous.
//
// τ (Options::goal): by default the main axes move as evenly as possible, so
// τ is the largest that keeps the auxiliary offset in its field and its
// speed under its limit, and the main-axis limits must hold there
// (SmoothestMain); or τ is the smallest the main-axis limits allow, which
// shortens the 2τ the main axes spend moving while the beam stands at the
// start and end of each contour (ShortestLeadIn). If no τ meets all limits,
// the contour speed is infeasible and the highest feasible one is searched
// (bisection). The searches double then bisect τ to 1 %.
#pragma once

#include <cstddef>
#include <string>

#include "common/result.h"
#include "decompose/decompose_options.h"
#include "decompose/kinematics_table.h"
#include "dxf/discretize.h"

namespace lcnc::decompose {

struct SyncResult {
  KinematicsTable table;
  std::size_t m = 0;  // filter half-width in samples
  double tau_s = 0.0;
};

// The decomposition at opt.speed_mm_s, or DecomposeInfeasible naming the
// contour, the limit that fails and the highest feasible contour speed.
// `name` is the contour's name for that message.
[[nodiscard]] Result<SyncResult> sync_decompose(const dxf::Polyline& s, const Options& opt,
                                                const std::string& name);

// The highest contour speed the limits allow for this contour (0 if none:
// e.g. a field too small for even the slowest speed is impossible — the
// offset needed shrinks with vk, so this never happens for a field > 0).
[[nodiscard]] double highest_feasible_speed(const dxf::Polyline& s, const Options& opt);

}  // namespace lcnc::decompose
