#include "plan/segment_limits.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>

#include "core/plan/test_machine.h"
#include "plan/arc_transition.h"
#include "plan/coarse_interpolator.h"
#include "plan/tolerances.h"
#include "support/test_scale.h"

namespace lcnc {
namespace {

// Reference model: the limits as first written — the sinusoid ranges from
// atan2, every bound recomputed per call. segment_limits() precomputes per
// segment, skips atan2 where the answer is certain and keeps the bounds as
// functions of v²; the results must agree to rounding.
struct ReferenceLimits {
  double v_max = 0.0;
  double a_linear = 0.0;
  bool arc = false;
  double rho = 0.0, radius = 0.0;
  std::array<double, 3> a_axis{}, g{}, t_lo{}, t_hi{}, n_lo{}, n_hi{};
  std::array<std::array<double, 2>, 3> t_end{}, n_end{};
  double sweep = 0.0;

  static void sinusoid_range(double a, double b, double sweep, double& lo, double& hi) {
    constexpr double kPi = 3.14159265358979323846;
    auto f = [&](double phi) { return a * std::cos(phi) + b * std::sin(phi); };
    lo = std::min(f(0.0), f(sweep));
    hi = std::max(f(0.0), f(sweep));
    const double amp = std::hypot(a, b);
    double phi = std::atan2(b, a);
    if (phi < 0.0) phi += 2 * kPi;
    for (double p = phi; p <= sweep; p += 2 * kPi) hi = amp;
    for (double p = phi >= kPi ? phi - kPi : phi + kPi; p <= sweep; p += 2 * kPi) lo = -amp;
  }

  static double box_bound(double amax, double rho, double sign, double t_lo, double t_hi, double c_lo,
                          double c_hi) {
    const double x_lo = sign > 0 ? t_lo : -t_hi, x_hi = sign > 0 ? t_hi : -t_lo;
    double a = std::numeric_limits<double>::infinity();
    if (c_hi > amax || c_lo < -amax) return 0.0;
    if (x_hi > 1e-15) a = std::min(a, (amax - c_hi) / (rho * x_hi));
    if (x_lo < -1e-15) a = std::min(a, (amax + c_lo) / (rho * -x_lo));
    return std::max(0.0, a);
  }

  ReferenceLimits(const Segment& seg, const SegmentGeometry& geo, const MachineConfig& m) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    v_max = kInf;
    a_linear = kInf;
    const double L = geo.length();
    Pose lin = (seg.end - seg.start) / L;
    if (geo.is_arc()) lin.head<3>() = geo.tangent(0.0).head<3>() - geo.plane_speed_ratio() * geo.w();
    for (int i = 0; i < kAxisCount; ++i) {
      const double k = std::abs(lin[i]);
      if (k <= 1e-15) continue;
      v_max = std::min(v_max, m.axes[i].max_velocity / k);
      a_linear = std::min(a_linear, m.axes[i].max_acceleration / k);
    }
    if (geo.is_arc() && geo.plane_speed_ratio() > 0.0) arc_limits(geo, m, lin);
  }

  void arc_limits(const SegmentGeometry& geo, const MachineConfig& m, const Pose& lin) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    arc = true;
    rho = geo.plane_speed_ratio();
    radius = geo.radius();
    double a_n_max = kInf;
    for (int i = 0; i < 3; ++i) {
      const double ui = geo.u()[i], wi = geo.w()[i];
      g[i] = std::hypot(ui, wi);
      if (g[i] <= 1e-15) continue;
      a_axis[i] = m.axes[i].max_acceleration;
      sinusoid_range(wi, -ui, geo.sweep_rad(), t_lo[i], t_hi[i]);
      sinusoid_range(-ui, -wi, geo.sweep_rad(), n_lo[i], n_hi[i]);
      // t and n at the ends (φ = 0 and the sweep), from the angle
      for (int e = 0; e < 2; ++e) {
        const double phi = e == 0 ? 0.0 : geo.sweep_rad();
        t_end[i][e] = -std::sin(phi) * ui + std::cos(phi) * wi;
        n_end[i][e] = -std::cos(phi) * ui - std::sin(phi) * wi;
      }
      const double t_abs = std::max(std::abs(t_lo[i]), std::abs(t_hi[i]));
      const double n_abs = std::max(std::abs(n_lo[i]), std::abs(n_hi[i]));
      v_max = std::min(v_max, m.axes[i].max_velocity / (rho * t_abs + std::abs(lin[i])));
      if (n_abs > 1e-15) a_n_max = std::min(a_n_max, a_axis[i] / n_abs);
    }
    if (std::isfinite(a_n_max))
      v_max = std::min(v_max, std::sqrt(plan::kArcNormalShare * a_n_max * radius) / rho);
    sweep = geo.sweep_rad();
  }

  // The box at the ends of a short sweep with the sinusoid's bulge μ
  // between them, for a_n anywhere in [a_lo, a_hi]; NaN where it does not
  // apply (segment_limits.cpp).
  [[nodiscard]] double end_box(int i, double a_lo, double a_hi, double sign) const {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    if (sweep > 0.1) return kNaN;
    const double mu = g[i] * sweep * sweep / 8.0;
    const double vp = rho * v_max;
    const double a_n_top = vp * vp / radius;
    double a = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 2; ++e) {
      const double t = t_end[i][e], n = n_end[i][e];
      if (std::abs(t) <= mu || a_n_top * (std::abs(n) + mu) > a_axis[i]) return kNaN;
      const double sigma = sign * t > 0.0 ? 1.0 : -1.0;
      const double k = sigma * n + mu;  // the worst a_n: the top where it hinders
      a = std::min(a, (a_axis[i] - (k >= 0.0 ? a_hi : a_lo) * k) / (rho * (std::abs(t) + mu)));
    }
    return std::max(0.0, a);
  }

  // Allowed at every speed in [v_lo, v].
  [[nodiscard]] double tangential(double v, double sign, double v_lo = 0.0) const {
    if (!arc) return a_linear;
    const double a_n = (rho * v) * (rho * v) / radius;
    const double a_lo = (rho * v_lo) * (rho * v_lo) / radius;
    double a_t = a_linear;
    for (int i = 0; i < 3; ++i) {
      if (g[i] <= 1e-15) continue;
      const double by_norm = a_axis[i] / g[i];
      const double a1 = std::sqrt(std::max(0.0, by_norm * by_norm - a_n * a_n)) / rho;
      double a2 = end_box(i, a_lo, a_n, sign);
      if (std::isnan(a2)) {
        // the extremes of a_n·n over the sweep and [a_lo, a_n]
        const double c_hi = std::max(a_lo * n_hi[i], a_n * n_hi[i]);
        const double c_lo = std::min(a_lo * n_lo[i], a_n * n_lo[i]);
        a2 = box_bound(a_axis[i], rho, sign, t_lo[i], t_hi[i], c_lo, c_hi);
      }
      a_t = std::min(a_t, std::max(a1, a2));
    }
    return a_t;
  }
};

Pose pose(const Vec3& p) {
  Pose q = Pose::Zero();
  q.head<3>() = p;
  return q;
}

// What the limits are for: on an arc, at any speed up to v and any point of
// the sweep, the tangential acceleration allowed (either way) and the
// centripetal one keep every axis within its acceleration, sampled at 64
// points of the sweep and at a_n from 0 to its value at v.
void expect_within_axes(const SegmentGeometry& geo, const MachineConfig& m, double v_lo, double v,
                        const Accel& a) {
  if (!geo.is_arc() || geo.plane_speed_ratio() <= 0.0) return;
  const double rho = geo.plane_speed_ratio();
  const double a_n_lo = (rho * v_lo) * (rho * v_lo) / geo.radius();
  const double a_n_top = (rho * v) * (rho * v) / geo.radius();
  for (int k = 0; k <= 64; ++k) {
    const double phi = geo.sweep_rad() * k / 64.0;
    for (int i = 0; i < 3; ++i) {
      const double t = -std::sin(phi) * geo.u()[i] + std::cos(phi) * geo.w()[i];
      const double n = -std::cos(phi) * geo.u()[i] - std::sin(phi) * geo.w()[i];
      for (const double share : {0.0, 0.5, 1.0}) {
        const double a_n = a_n_lo + share * (a_n_top - a_n_lo);
        for (const double a_t : {a.accel, -a.decel}) {
          ASSERT_LE(std::abs(rho * a_t * t + a_n * n), m.axes[i].max_acceleration * (1.0 + 1e-9))
              << "axis " << i << " φ " << phi << " v " << v_lo << "…" << v << " a_t " << a_t;
        }
      }
    }
  }
}

// Checks segment_limits() against the reference at speeds from rest to v_max
// (beyond it the look-ahead never asks), and its reach: v'² = v² + 2L·a(v')
// over [v, v'] — and no faster speed satisfies it, since a(v') falls as v'
// rises; a reach past v_max says that v_max is reachable.
void expect_same_limits(const Segment& seg, const MachineConfig& m, std::mt19937& rng) {
  const SegmentGeometry geo(seg);
  const SegmentLimits lim = segment_limits(geo, m);
  const ReferenceLimits ref(seg, geo, m);
  ASSERT_NEAR(lim.v_max, ref.v_max, 1e-12 * ref.v_max);
  // rounding of the two forms: far below any acceleration that matters
  const double tol = 1e-9 * m.axes[0].max_acceleration;
  std::uniform_real_distribution<double> share(0.0, 1.0), length(0.0, 2.0);
  for (int k = 0; k < 20; ++k) {
    const double v = k == 0 ? lim.v_max : share(rng) * lim.v_max;
    const Accel a = lim.at(v);
    ASSERT_NEAR(a.accel, ref.tangential(v, +1.0), tol) << "v " << v;
    ASSERT_NEAR(a.decel, ref.tangential(v, -1.0), tol) << "v " << v;
    expect_within_axes(geo, m, 0.0, v, a);
    // over a phase of speeds [v_lo, v]: where the centripetal part helps
    // an axis, more
    const double v_lo = share(rng) * v;
    const Accel ar = lim.at(v, v_lo, v_lo);
    ASSERT_NEAR(ar.accel, ref.tangential(v, +1.0, v_lo), tol) << "v " << v_lo << "…" << v;
    ASSERT_NEAR(ar.decel, ref.tangential(v, -1.0, v_lo), tol) << "v " << v_lo << "…" << v;
    ASSERT_GE(ar.accel, a.accel - tol);
    ASSERT_GE(ar.decel, a.decel - tol);
    expect_within_axes(geo, m, v_lo, v, ar);
    const double L = std::pow(10.0, -3.0 * length(rng)) * geo.length();
    for (const bool up : {true, false}) {
      const double v1 = up ? lim.reach_up(v, L) : lim.reach_down(v, L);
      // the acceleration over [v, u]
      auto a_at = [&](double u) { return ref.tangential(u, up ? 1.0 : -1.0, v); };
      ASSERT_GE(v1, v);
      if (v1 > lim.v_max) {
        ASSERT_LE(lim.v_max * lim.v_max, v * v + 2.0 * L * a_at(lim.v_max) + 1e-9) << "v " << v;
        continue;
      }
      // the acceleration at v1 carries v to v1 over L, to rounding ...
      ASSERT_NEAR(v1 * v1, v * v + 2.0 * L * a_at(v1), 1e-9 * (v1 * v1 + 1.0)) << "v " << v;
      // ... and 0.1 % faster is more than it allows
      const double over = v1 * 1.001;
      if (a_at(over) > 0.0) {
        ASSERT_GT(over * over, v * v + 2.0 * L * a_at(over)) << "v " << v;
      }
    }
  }
}

TEST(SegmentLimits, BlendArcsMatchTheReferenceModel) {
  const MachineConfig m = testing::test_machine(100.0, 2000.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-20.0, 20.0), turn(-1.0, 1.0);
  const int corners = testing::scaled(3000);
  for (int k = 0; k < corners; ++k) {
    // corners from nearly straight (tiny sweeps, the quick decision) to sharp
    const Vec3 p0(coord(rng), coord(rng), coord(rng));
    const Vec3 p1 = p0 + Vec3(coord(rng), coord(rng), coord(rng));
    const double scale = std::pow(10.0, -6.0 * std::abs(turn(rng)));
    const Vec3 p2 = p1 + (p1 - p0) + scale * (p1 - p0).norm() * Vec3(turn(rng), turn(rng), turn(rng));
    Segment a, b;
    a.kind = b.kind = MotionKind::Linear;
    a.start = pose(p0);
    a.end = b.start = pose(p1);
    b.end = pose(p2);
    const ArcTransition t = arc_transition(a, b, 0.01, 1e9, 1e9);
    if (!t.blended) continue;
    expect_same_limits(t.arc, m, rng);
  }
}

TEST(SegmentLimits, PlaneArcsAndHelicesMatchTheReferenceModel) {
  MachineConfig m = testing::test_machine(100.0, 2000.0);
  m.max_feed_override = 1.5;  // the operator's highest override: no derate
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < 2000; ++k) {
    Segment s;
    s.kind = MotionKind::Arc;
    s.plane = static_cast<Plane>(k % 3);
    s.clockwise = k % 2 == 0;
    s.extra_turns = k % 17 == 0 ? 1 : 0;
    const PlaneAxes pa = plane_axes(s.plane);
    s.center = Vec3(100, 100, 100);
    const double r = 0.1 + 20.0 * unit(rng);
    // start angles on and near the axes, where the extremes sit at the ends
    const double a0 = k % 5 == 0 ? kPi / 2 * (k % 4) + 1e-12 * (unit(rng) - 0.5) : 2 * kPi * unit(rng);
    const double sweep = (s.clockwise ? -1.0 : 1.0) * std::pow(10.0, -6.0 * unit(rng)) * 3.0;
    Vec3 p0 = s.center, p1 = s.center;
    p0[pa.first] += r * std::cos(a0);
    p0[pa.second] += r * std::sin(a0);
    p1[pa.first] += r * std::cos(a0 + sweep);
    p1[pa.second] += r * std::sin(a0 + sweep);
    if (k % 7 == 0) p1[pa.normal] += unit(rng);  // helix
    s.start = pose(p0);
    s.end = pose(p1);
    expect_same_limits(s, m, rng);
  }
}

// A spiral (IJK radii differing within the G-code tolerance) is planned
// with the limits of a circle lowered by its excess: at every speed the
// limits allow and every point of the sweep, the spiral's own velocity
// (v·dp/ds) and acceleration (a_t·dp/ds + v²·d²p/ds²) stay within every
// axis's limits — on machines whose axes differ, and on sharp spirals
// (short sweeps, small radii) as on the rounding kind.
TEST(SegmentLimits, SpiralArcsKeepEveryAxisWithinItsLimits) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr double kPi = 3.14159265358979323846;
  int checked = 0;
  for (int k = 0; k < 600; ++k) {
    MachineConfig m = testing::test_machine(100.0, 2000.0);
    if (k % 2 == 0) {  // unequal axes
      m.axes[0].max_velocity = 300.0;
      m.axes[1].max_acceleration = 800.0;
      m.axes[2].max_acceleration = 5000.0;
    }
    Segment s;
    s.kind = MotionKind::Arc;
    s.plane = static_cast<Plane>(k % 3);
    s.clockwise = k % 4 < 2;
    const PlaneAxes pa = plane_axes(s.plane);
    s.center = Vec3(100, 100, 100);
    const double r = 0.2 + 20.0 * unit(rng);
    const double dr = (unit(rng) - 0.5) * (k % 5 == 0 ? 0.4 * r : 0.0566);
    const double a0 = 2 * kPi * unit(rng);
    const double sweep = (s.clockwise ? -1.0 : 1.0) * (0.01 + 3.0 * unit(rng));
    Vec3 p0 = s.center, p1 = s.center;
    p0[pa.first] += r * std::cos(a0);
    p0[pa.second] += r * std::sin(a0);
    p1[pa.first] += (r + dr) * std::cos(a0 + sweep);
    p1[pa.second] += (r + dr) * std::sin(a0 + sweep);
    if (k % 7 == 0) p1[pa.normal] += 2.0 * unit(rng);  // helix
    s.start = pose(p0);
    s.end = pose(p1);
    const SegmentGeometry geo(s);
    if (!geo.is_spiral()) continue;
    const SegmentLimits lim = segment_limits(geo, m);
    ASSERT_GT(lim.v_max, 0.0);
    ++checked;
    for (const double share : {0.0, 0.5, 1.0}) {
      const double v = share * lim.v_max;
      const Accel a = lim.at(v);
      for (int j = 0; j <= 200; ++j) {
        const double at = geo.length() * j / 200.0;
        const Pose t = geo.tangent(at), c = geo.curvature(at);
        for (int i = 0; i < 3; ++i) {
          ASSERT_LE(std::abs(lim.v_max * t[i]), m.axes[i].max_velocity * (1 + 1e-9))
              << "k " << k << " axis " << i;
          for (const double a_t : {a.accel, -a.decel}) {
            ASSERT_LE(std::abs(a_t * t[i] + v * v * c[i]), m.axes[i].max_acceleration * (1 + 1e-9))
                << "k " << k << " axis " << i << " v " << v << " a_t " << a_t;
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(StepQuantizer, RoundsLikeLlround) {
  const MachineConfig m = testing::test_machine();
  const StepQuantizer q(m, Pose::Zero());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> mm(-2000.0, 2000.0);
  for (int k = 0; k < 100000; ++k) {
    // every fourth value sits on a half step, where the rounding direction shows
    const double x = k % 4 == 0 ? (std::floor(mm(rng) * 1000.0) + 0.5) / 1000.0 : mm(rng);
    ASSERT_EQ(q.to_steps(0, x), std::llround(x * 1000.0)) << x;
  }
  for (const double x : {0.0, -0.0, 0.0005, -0.0005, 0.00049999999999999995, 1e15, -1e15, 3e16})
    EXPECT_EQ(q.to_steps(0, x), std::llround(x * 1000.0)) << x;
}

}  // namespace
}  // namespace lcnc
