#include "decompose/sync_decomposition.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"

namespace lcnc::decompose {
namespace {

// The rows of the beam for half-width m, padded by m more on each side for
// the filter windows: m samples at rest at point 0, the contour's n points,
// point 0 again, m samples at rest. Coordinates relative to point 0 (small
// numbers: the running sums keep their precision). Row r ∈ [−m, N + m) is
// x[r + m], N = n + 2m + 1 the table's rows.
struct BeamRows {
  BeamRows(const dxf::Polyline& s, std::size_t m) : m(m), origin(s.pts.front()) {
    const std::size_t n = s.size();
    rows = n + 2 * m + 1;
    x.assign(rows + 2 * m, Vec2::Zero());
    for (std::size_t j = 1; j < n; ++j) x[2 * m + j] = s.pts[j] - origin;
  }
  [[nodiscard]] const Vec2& at(std::size_t r) const { return x[r + m]; }  // row r ≥ 0

  std::size_t m;
  Vec2 origin;
  std::size_t rows;
  std::vector<Vec2> x;
};

// S1 for half-width m, relative to point 0: forward box C[k] = mean of rows
// k … k+m−1, then S1[i] = mean of C[i−m+1] … C[i]. Running sums, recomputed
// every kResumEvery rows.
void main_path(const BeamRows& b, std::vector<Vec2>& c, std::vector<Vec2>& s1) {
  const std::size_t M = b.m, N = b.rows;
  const double inv_m = 1.0 / static_cast<double>(M);
  // c[k] = C[k − (M − 1)] = mean of x[k + 1 … k + M] (rows k−M+1 … k), k = 0 … N+M−2.
  c.resize(N + M - 1);
  Vec2 sum = Vec2::Zero();
  for (std::size_t k = 0; k < N + M - 1; ++k) {
    if (k % kResumEvery == 0) {
      sum.setZero();
      for (std::size_t j = 1; j <= M; ++j) sum += b.x[k + j];
    } else {
      sum += b.x[k + M] - b.x[k];
    }
    c[k] = sum * inv_m;
  }
  s1.resize(N);
  Vec2 sum2 = Vec2::Zero();
  for (std::size_t i = 0; i < N; ++i) {  // S1[i] = mean of c[i … i + M − 1]
    if (i % kResumEvery == 0) {
      sum2.setZero();
      for (std::size_t k = 0; k < M; ++k) sum2 += c[i + k];
    } else {
      sum2 += c[i + M - 1] - c[i - 1];
    }
    s1[i] = sum2 * inv_m;
  }
}

// Room left under each limit for rounding of the table's own numbers.
constexpr double kMargin = 1.0 - 1e-6;

enum class Fail : std::uint8_t { None, MainAccel, MainSpeed, AuxSpeed, AuxField };

// Walks the rows for half-width m: the limit broken (or None). Stops at the
// first row that breaks an auxiliary limit (what the field search asks).
Fail evaluate(const dxf::Polyline& s, const Options& opt, double vk, std::size_t m) {
  std::vector<Vec2> c, s1;
  const BeamRows b(s, m);
  main_path(b, c, s1);
  const double dt = s.step_mm / vk;
  const double tau = static_cast<double>(m) * dt;
  const double field = opt.aux_half_field_mm * kMargin;
  // Squared bounds on the row differences, so the loop needs no root.
  const double acc_sqr = std::pow(opt.main_accel_mm_s2 * kMargin * tau * tau, 2);
  const double vmain_sqr = std::pow(opt.main_speed_mm_s * kMargin * dt, 2);
  const double vaux_sqr = std::pow(opt.aux_speed_mm_s * kMargin * dt, 2);
  const std::size_t M = m;
  Fail fail = Fail::None;
  double exc = 0, a2 = 0, v1 = 0, v2 = 0;
  for (std::size_t r = 0; r < b.rows; ++r) {
    const Vec2& beam = b.x[r + M];
    const Vec2 aux = beam - s1[r];
    exc = std::max(exc, std::max(std::abs(aux.x()), std::abs(aux.y())));
    // a1[r] = (S[r+m] − 2S[r] + S[r−m]) / τ²
    a2 = std::max(a2, (b.x[r + 2 * M] - 2.0 * beam + b.x[r]).squaredNorm());
    if (r > 0) {
      const Vec2 d1 = s1[r] - s1[r - 1];
      v1 = std::max(v1, d1.squaredNorm());
      v2 = std::max(v2, (beam - b.x[r + M - 1] - d1).squaredNorm());
    }
    if (exc > field || v2 > vaux_sqr) break;
  }
  if (exc > field)
    fail = Fail::AuxField;
  else if (v2 > vaux_sqr)
    fail = Fail::AuxSpeed;
  else if (a2 > acc_sqr)
    fail = Fail::MainAccel;
  else if (v1 > vmain_sqr)
    fail = Fail::MainSpeed;
  return fail;
}

bool aux_ok(Fail f) { return f != Fail::AuxField && f != Fail::AuxSpeed; }

// The largest m in [lo, cap] for which ok(m) holds, given ok(lo): doubling
// from lo, then bisection to 1 % (the main path barely changes within it).
template <typename Ok>
std::size_t largest(std::size_t lo, std::size_t cap, Ok ok) {
  std::size_t hi = lo;
  while (hi < cap) {
    const std::size_t next = std::min(cap, 2 * hi);
    if (!ok(next)) {
      hi = next;
      break;
    }
    lo = hi = next;
  }
  if (lo == hi) return lo;
  while (hi - lo > std::max<std::size_t>(1, lo / 100)) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (ok(mid))
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// The half-width for contour speed vk, or 0 with the limit that failed.
std::size_t choose_m(const dxf::Polyline& s, const Options& opt, double vk, Fail* why) {
  const double dt = s.step_mm / vk;
  const auto m_cap = std::max<std::size_t>(
      1, static_cast<std::size_t>(kMaxFilterToContourTime * static_cast<double>(s.size())));
  // The auxiliary motion always fits at m = 1 (S1 = S); by the bounds
  // |S2| ≤ vkτ/3 and |v2| ≤ 2vk it fits up to m = 3F/Δ when 2vk is allowed.
  std::size_t m0 = 1;
  if (2.0 * vk <= opt.aux_speed_mm_s * kMargin) {
    m0 = std::clamp<std::size_t>(static_cast<std::size_t>(3.0 * opt.aux_half_field_mm * kMargin / s.step_mm),
                                 1, m_cap);
  }
  // Largest m whose auxiliary motion fits: the main axes as even as can be.
  const std::size_t m_f = largest(m0, m_cap, [&](std::size_t m) { return aux_ok(evaluate(s, opt, vk, m)); });
  const Fail at_f = evaluate(s, opt, vk, m_f);
  if (at_f == Fail::None && opt.goal == SyncGoal::SmoothestMain) return m_f;
  // Otherwise the main axes decide: the smallest m that keeps them within
  // their limits (the bound 2vk/τ ≤ a guarantees the acceleration at m_acc),
  // if the auxiliary motion still fits there.
  const double m_acc = std::ceil(2.0 * vk / (opt.main_accel_mm_s2 * kMargin * dt));
  // (bounded: every trial allocates n + 4m rows, see kMaxFilterSamples)
  std::size_t lo = m_f,
              hi = static_cast<std::size_t>(std::min<double>(m_acc, static_cast<double>(kMaxFilterSamples)));
  if (at_f == Fail::None) {  // ShortestLeadIn: the smallest m ≤ m_f that keeps them
    lo = 0;
    hi = m_f;
    while (hi - lo > std::max<std::size_t>(1, lo / 100)) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (evaluate(s, opt, vk, mid) == Fail::None)
        hi = mid;
      else
        lo = mid;
    }
    return hi;
  }
  if (hi > lo) {
    while (hi - lo > 1) {
      const std::size_t mid = lo + (hi - lo) / 2;
      const Fail f = evaluate(s, opt, vk, mid);
      if (f == Fail::None) return mid;
      if (aux_ok(f))
        lo = mid;  // main limits: needs a larger m
      else
        hi = mid;  // the field or aux speed: a smaller one
    }
    const Fail f = evaluate(s, opt, vk, hi);
    if (f == Fail::None) return hi;
  }
  *why = at_f == Fail::MainAccel || at_f == Fail::MainSpeed ? at_f : Fail::AuxField;
  return 0;
}

const char* fail_text(Fail f) {
  switch (f) {
    case Fail::MainAccel: return "the main-axis acceleration limit within the auxiliary field";
    case Fail::MainSpeed: return "the main-axis speed limit";
    case Fail::AuxSpeed: return "the auxiliary speed limit";
    case Fail::AuxField: return "the auxiliary field";
    case Fail::None: break;
  }
  return "?";
}

}  // namespace

double highest_feasible_speed(const dxf::Polyline& s, const Options& opt) {
  Fail why = Fail::None;
  double hi = opt.speed_mm_s;
  if (choose_m(s, opt, hi, &why) != 0) return hi;
  double lo = hi;
  for (int k = 0; k < 60; ++k) {
    lo *= 0.5;
    if (choose_m(s, opt, lo, &why) != 0) break;
    hi = lo;
    if (k == 59) return 0.0;
  }
  while (hi - lo > kSpeedSearchRel * lo) {
    const double mid = 0.5 * (lo + hi);
    if (choose_m(s, opt, mid, &why) != 0)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

Result<SyncResult> sync_decompose(const dxf::Polyline& s, const Options& opt, const std::string& name) {
  const double vk = opt.speed_mm_s;
  Fail why = Fail::None;
  const std::size_t m = choose_m(s, opt, vk, &why);
  if (m == 0) {
    const double best = highest_feasible_speed(s, opt);
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s: contour speed %.1f mm/s (%.2f m/min) exceeds %s; the highest "
                  "feasible is %.1f mm/s (%.2f m/min)",
                  name.c_str(), vk, vk * 0.06, fail_text(why), best, best * 0.06);
    return make_error(ErrorCode::DecomposeInfeasible, buf);
  }
  SyncResult out;
  out.m = m;
  const double dt = s.step_mm / vk;
  out.tau_s = static_cast<double>(m) * dt;
  const BeamRows b(s, m);
  std::vector<Vec2> c, s1;
  main_path(b, c, s1);
  KinematicsTable& t = out.table;
  t.contour = s.contour;
  const std::size_t rows = s1.size();
  t.beam.resize(rows);
  t.main.resize(rows);
  t.t_s.resize(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    t.beam[r] = b.at(r) + b.origin;
    t.main[r] = s1[r] + b.origin;
    t.t_s[r] = static_cast<double>(r) * dt;
  }
  fill_derivatives(t, 0.0, 0.0);
  // The effective acceleration is the path's (the beam runs at constant
  // speed): where the cut starts and ends, the curvature at point 0, not the
  // step from rest to vk (a galvo's few microseconds, which a main-axes-only
  // machine would need as well).
  t.a_eff[m] = t.a_eff[m + s.size()] = loop_accel(t.beam, t.t_s, m, m + s.size());
  // The output checks itself against the limits it was made for.
  const Peaks p = peaks(t);
  if (p.a_main > opt.main_accel_mm_s2 || p.aux_excursion > opt.aux_half_field_mm ||
      p.v_aux > opt.aux_speed_mm_s || p.v_main > opt.main_speed_mm_s || p.exactness > kExactness_mm) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s: the table breaks a limit it was made for (main %.3f mm/s2, %.3f mm/s; "
                  "aux %.6f mm, %.3f mm/s; exactness %.3g mm)",
                  name.c_str(), p.a_main, p.v_main, p.aux_excursion, p.v_aux, p.exactness);
    return make_error(ErrorCode::Internal, buf);
  }
  return out;
}

}  // namespace lcnc::decompose
