// Limits, defaults and tolerances of the main + auxiliary axes decomposition
// (docs/design.md §5.7; the "technological limits" of Kondratenko et al.
// 2015), in one place.
// Units: mm, s, mm/s, mm/s².
#pragma once

#include <cstddef>

namespace lcnc::decompose {

inline constexpr double kG_mm_s2 = 9806.65;  // standard gravity

// Seed 004: main-axis acceleration at most 0.5 g; auxiliary axes up to
// 300 m/min; main axes 10–40 m/min depending on the material.
inline constexpr double kDefaultMainAccel_mm_s2 = 0.5 * kG_mm_s2;
inline constexpr double kDefaultAuxSpeed_mm_s = 300.0 * 1000.0 / 60.0;
inline constexpr double kDefaultMainSpeed_mm_s = 40.0 * 1000.0 / 60.0;
// The auxiliary field: a small stage or a scanner, ±5 mm in P and Q.
inline constexpr double kDefaultAuxHalfField_mm = 5.0;
// Seed mode: a vertex is smoothed when the path turns there by more than
// this (eq. 1 compares the cosine). With step Δ it bounds the curvature of
// S1 to about θ/Δ: 1° at 0.01 mm is a radius of 0.57 mm.
inline constexpr double kDefaultCriticalAngle_deg = 1.0;

// S1 + S2 must equal S within this at every instant (the decomposition's promise: ≤ 1 µm).
inline constexpr double kExactness_mm = 1e-3;

// Seed mode: the smoothing gives up after this many vertex replacements per
// contour point (a bend it cannot spread, e.g. a contour too small for the
// critical angle).
inline constexpr std::size_t kSeedMaxReplacementsPerPoint = 2000;

// The highest feasible contour speed is searched to this relative precision.
inline constexpr double kSpeedSearchRel = 1e-3;

// The main-path filter never spans more than the contour's own time times
// this (beyond it the main axes stand still and the aux does everything).
inline constexpr double kMaxFilterToContourTime = 1.0;

// Work bounds, checked before anything is allocated: a drawing read in the
// wrong units ($INSUNITS metres for a part drawn in mm) or a step far finer
// than the part would otherwise take gigabytes and minutes. The memory of a
// decomposition grows with its points (the polylines, the table's 2 Vec2 +
// 8 doubles per row, the filter's work rows; about 0.2 kB a point at the
// peak), so the points of all contours of a part, estimated from their
// lengths / the step, are bounded: 2 M points is 20 m of contour at the
// default step 0.01 mm, about 0.5 GB at the peak.
inline constexpr std::size_t kMaxPartPoints = 2'000'000;
// Sync mode: the largest filter half-width m (samples) the τ search tries.
// Each trial walks n + 4m rows in three arrays (~50 B a row): m beyond this
// is only asked for by contour speeds near the sum of the axis groups' speed
// limits at a fine step, and is then taken as infeasible (the highest
// feasible speed below it is reported).
inline constexpr std::size_t kMaxFilterSamples = 2'000'000;

// The running window sums of the filter are recomputed from scratch this
// often, so rounding never accumulates over millions of points.
inline constexpr std::size_t kResumEvery = 1u << 14;

}  // namespace lcnc::decompose
