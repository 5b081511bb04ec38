// The paper's decomposition (Kondratenko et al. 2015 eq. 1–13, "DopOs2"), faithfully.
//
// Smoothing (eq. 1–5): walking the closed polyline S, the cosine of the turn
// at vertex j is
//   α_j = (d1 · d2) / (|d1| |d2|),  d1 = x_j − x_j−1,  d2 = x_j+1 − x_j   (eq. 1)
// If α_j < cos θc (θc the critical angle) the vertex is replaced by the
// midpoint of its neighbours (eq. 2, 3) and the walk steps back one vertex to
// re-check the angle that changed; otherwise it stays (eq. 4, 5). The walk
// goes round the contour until a whole turn passes without a change. The
// result is the main path S1 (same number of vertices).
// S2 = S − S1 vector by vector: step i of S2 is step i of S minus step i of S1.
//
// Kinematics (eq. 6–13), with h1, h2 the lengths of step i of S1 and S2:
//   v0 = vk / 2                                     (6)  speeds at row 0
//   k1 = h1 / (h1 + h2),  k2 = h2 / (h1 + h2)       (7, 8)
//   v1 = 2 v0 k1,  v2 = 2 v0 k2                     (9, 10)
//   t_i = t_i−1 + h1 / v1  (= (h1 + h2) / vk)       (11; the paper prints t_i+1)
//   a1 = Δv1 / Δt,  a2 = Δv2 / Δt                   (12, 13) → at_main, at_aux
// Where S1 = S, h2 = 0 and the main axes carry the whole speed. (The paper's
// prose says unchanged steps weigh 0.5 each, which does not follow from its
// own S2 = S − S1; the equations are implemented, as docs/design.md §5.7 states them.)
//
// What the paper's method does not do, and the table shows: the contour speed is
// h / Δt ≤ vk (it drops where S1 and S2 diverge), the accelerations of
// eq. 12/13 are tangential only, and nothing bounds the main-axis
// acceleration or the auxiliary excursion — Mode::Sync does.
#pragma once

#include <vector>

#include "common/result.h"
#include "decompose/decompose_options.h"
#include "decompose/kinematics_table.h"
#include "dxf/discretize.h"

namespace lcnc::decompose {

// S1 by eq. 1–5 (closed polyline, same size as `s`); error when the walk does
// not settle (a bend the critical angle cannot spread over the contour).
[[nodiscard]] Result<std::vector<Vec2>> seed_smooth(const std::vector<Vec2>& s, double critical_angle_deg);

// The whole seed decomposition of one contour: rows 0 … n (row n is point 0
// again, closing the contour).
[[nodiscard]] Result<KinematicsTable> seed_decompose(const dxf::Polyline& s, const Options& opt);

}  // namespace lcnc::decompose
