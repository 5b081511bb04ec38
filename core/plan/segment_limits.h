// Path-speed and path-acceleration limits of a segment from the per-axis
// limits of the machine (docs/design.md §5.2: "a segment's path limits follow from its
// direction").
//
// Line: axis i moves k_i = |Δ_i|/L per unit of path, so
//   v ≤ min_i vmax_i / k_i,   a ≤ min_i amax_i / k_i.
// Arc of radius r in the plane (u, w), plane share ρ = r·sweep/L, unit
// tangent t(φ) and unit normal n(φ) (toward the centre) in the plane. Axis i
// sees the in-plane acceleration ρ·a_t·t_i + a_n·n_i, a_n = (ρ·v)²/r. Two
// bounds on it are both true, and an a_t is allowed when either keeps the
// axis within amax_i:
//   |·| ≤ g_i·sqrt((ρ·a_t)² + a_n²),  g_i = sqrt(u_i² + w_i²)   (long arcs)
//   t_i ∈ [t_lo, t_hi], n_i ∈ [n_lo, n_hi] over the sweep, a_n anywhere in
//   [a_n(v_lo), a_n(v)]: the extremes of ρ·a_t·t_i + a_n·n_i over that box,
//   signs kept                                                   (short arcs)
//   or, on a sweep ≤ 0.1 rad, the same at its two ends plus what a sinusoid
//   can bulge between them                          (CAM-chord blends: tighter)
// The norm bound falls as v rises; a box line falls where the centripetal
// part hinders the axis and rises where it helps, so over a phase of speeds
// [v_lo, v] the first are taken at v, the second at v_lo.
// The second is what makes a short blend arc, whose direction hardly turns,
// as fast as the axes allow — and it differs for speeding up and slowing
// down, where the centripetal part helps one and hinders the other. The
// centripetal limit (docs/design.md §5.1) takes a share of the budget:
// a_n·max(|n_lo|, |n_hi|) ≤ kArcNormalShare·amax_i.
// Normal (helix) and rotary axes move linearly with the path, as on a line.
//
// The look-ahead asks for accelerations many times per segment, at speeds
// that differ each time, and for the speed reachable over a length. Both
// must be cheap and the second exact, so the bounds are kept in x = v²:
// a_n = (ρ·v)²/r is linear in x, and so is the box bound (a min of two
// lines per axis and side); the norm bound is sqrt(b − (c·x)²). The
// reachable speed then solves v'² = v² + 2L·a(v') in closed form.
// The limits are the machine's own: an override above 100 % is planned for
// (target_speed's feed_scale), one below it runs the plan slower in the RT.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "machine/machine_config.h"
#include "path/segment.h"
#include "path/segment_geometry.h"

namespace lcnc {

// Tangential acceleration and deceleration (> 0) at one speed (path units/s²).
struct Accel {
  double accel = 0.0;
  double decel = 0.0;
};

// One arc axis's bounds in x = v² (planned units): the box as up to two
// lines per side, a ≤ p − q·x (a missing line has p = ∞, q = 0); the norm as
// sqrt(b − (c·x)²), c shared by the segment's axes.
// (No initializers: segment_limits() writes every one it counts.)
struct ArcAxisBound {
  std::array<double, 2> p_up, q_up, p_down, q_down;
  double b;
  double cap;  // sqrt(b): the norm bound at rest, its largest
};

struct SegmentLimits {
  double v_max = 0.0;  // path units/s: the highest speed the axes allow

  // Tangential acceleration (speeding up) and deceleration (slowing down,
  // > 0) allowed at every speed in [acc_from, v] and [dec_from, v]
  // respectively (planned units): on an arc the centripetal part grows with
  // the speed, and where it hinders an axis the bound is taken at the top
  // of the range, where it helps at the bottom; on a line both are the same
  // whatever v. Per arc axis the larger of its two bounds (both are true).
  [[nodiscard]] Accel at(double v, double acc_from, double dec_from) const noexcept {
    const double x = v * v, x_acc = acc_from * acc_from, x_dec = dec_from * dec_from;
    Accel a{a_linear, a_linear};
    for (int j = 0; j < axis_count; ++j) {
      const ArcAxisBound& ax = axes[j];
      const double up =
          std::min(line(ax.p_up[0], ax.q_up[0], x, x_acc), line(ax.p_up[1], ax.q_up[1], x, x_acc));
      const double down =
          std::min(line(ax.p_down[0], ax.q_down[0], x, x_dec), line(ax.p_down[1], ax.q_down[1], x, x_dec));
      double n = 0.0;  // the norm bound, needed only where a box bound falls below its cap
      if (up < ax.cap || down < ax.cap) {
        const double cx = c * x;
        n = std::sqrt(std::max(0.0, ax.b - cx * cx));
      }
      a.accel = std::min(a.accel, std::max(n, up));
      a.decel = std::min(a.decel, std::max(n, down));
    }
    return {std::max(0.0, a.accel), std::max(0.0, a.decel)};
  }
  // At every speed from rest to v.
  [[nodiscard]] Accel at(double v) const noexcept { return at(v, 0.0, 0.0); }
  // The speed reached from v over length L speeding up (or, read backward,
  // the entry from which v is reached slowing down) at the acceleration
  // allowed over [v, v'] — at(v', v, v) — solved exactly: v'² = v² +
  // 2L·a(v'). a is a min over axes of a max of two bounds, each falling in
  // x' = v'² (a box line where the centripetal part helps is taken at v and
  // does not depend on x'), so x' is the min over axes of the max of the two
  // x' — a linear equation per box line, a quadratic for the norm. Never
  // below v; not capped at v_max.
  [[nodiscard]] double reach_up(double v, double L) const noexcept {
    return std::sqrt(reach_sqr(v * v, L, true));
  }
  [[nodiscard]] double reach_down(double v, double L) const noexcept {
    return std::sqrt(reach_sqr(v * v, L, false));
  }
  // The same in the phase plane, speeds squared (x = v²): the look-ahead's
  // passes chain these with no square root between segments.
  [[nodiscard]] double reach_up_sqr(double x, double L) const noexcept { return reach_sqr(x, L, true); }
  [[nodiscard]] double reach_down_sqr(double x, double L) const noexcept { return reach_sqr(x, L, false); }

  // What at() and reach() need, per segment.
  double a_linear = 0.0;             // the linearly moving axes' bound (planned units)
  double c = 0.0;                    // the norm bounds' a_n per x
  std::array<ArcAxisBound, 3> axes;  // [0, axis_count) are set
  int axis_count = 0;

 private:
  // A box line a ≤ p − q·x over speeds² [x_lo, x]: where q ≥ 0 (the
  // centripetal part hinders) its least value is at x, else at x_lo.
  [[nodiscard]] static double line(double p, double q, double x, double x_lo) noexcept {
    return p - q * (q >= 0.0 ? x : x_lo);
  }
  // x' = x + 2L·(p − q·x') for q ≥ 0; x + 2L·(p − q·x) for q < 0.
  [[nodiscard]] static double reach_line(double p, double q, double x, double two_l) noexcept {
    return q >= 0.0 ? (x + two_l * p) / (1.0 + two_l * q) : x + two_l * (p - q * x);
  }
  [[nodiscard]] double reach_sqr(double x, double L, bool up) const noexcept {
    const double two_l = 2.0 * L;
    double x1 = x + two_l * a_linear;
    for (int j = 0; j < axis_count; ++j) {
      const ArcAxisBound& ax = axes[j];
      const auto& p = up ? ax.p_up : ax.p_down;
      const auto& q = up ? ax.q_up : ax.q_down;
      const double box = std::min(reach_line(p[0], q[0], x, two_l), reach_line(p[1], q[1], x, two_l));
      double xj = box;
      // the norm's x' is at most x + 2L·cap: asked only when that could beat the box
      if (box < x + two_l * ax.cap) {
        const double dc2 = two_l * two_l * c * c;
        const double disc = ax.b * (1.0 + dc2) - c * c * x * x;
        if (disc > 0.0) xj = std::max(xj, (x + two_l * std::sqrt(disc)) / (1.0 + dc2));
      }
      x1 = std::min(x1, xj);
    }
    return std::max(x, x1);
  }
};

// Limits of the segment, written into `lim` (the look-ahead's node: no copy
// of a few hundred bytes per segment). No motion (v_max 0) for a segment of
// no length or one that moves an absent axis.
void segment_limits(const SegmentGeometry& geo, const MachineConfig& machine, SegmentLimits& lim);
[[nodiscard]] inline SegmentLimits segment_limits(const SegmentGeometry& geo, const MachineConfig& machine) {
  SegmentLimits lim;
  segment_limits(geo, machine, lim);
  return lim;
}

// The speed to plan for: rapid → v_max; feed → min(F, v_max); G93 → L/duration.
// A feed move's speed is scaled by feed_scale (the feed override planned
// for, ≥ 1), still within v_max; a rapid's is v_max whatever the override.
[[nodiscard]] double target_speed(const Segment& seg, const SegmentGeometry& geo, const SegmentLimits& lim,
                                  double feed_scale = 1.0);

}  // namespace lcnc
