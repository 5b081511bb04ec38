// The kinematics table of a decomposed contour (Kondratenko et al. 2015 Fig. 7: X, Y, P, Q,
// TIME, Vbig, Vsmall, Abig …), one row per point in time.
//
// Main axes X, Y follow S1; auxiliary axes P, Q hold the offset S2 = S − S1,
// so the beam is at S = (X + P, Y + Q). (Seed Fig. 7 prints absolute
// coordinates in P, Q; an auxiliary axis is commanded in its own field, so
// the offset is what the machine needs.)
//
// Derived columns, from positions and times alone (the same for both modes):
//   v_i   = |x_i − x_i−1| / (t_i − t_i−1)                 (seed eq. 9, 10)
//   at_i  = (v_i − v_i−1) / (t_i − t_i−1)                 (seed eq. 12, 13:
//                                                          tangential only)
//   a_i   = |(x_i+1 − x_i)/Δt_i+1 − (x_i − x_i−1)/Δt_i| / ((Δt_i + Δt_i+1)/2)
//           the whole vector acceleration, centripetal part included — what
//           the drives feel; the limits are checked on it.
//   a_eff = the same for the beam S: the effective acceleration (Fig. 8).
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "dxf/drawing.h"

namespace lcnc::decompose {

using dxf::Vec2;

struct KinematicsTable {
  std::uint32_t contour = 0;
  std::vector<Vec2> beam;  // S
  std::vector<Vec2> main;  // S1 (X, Y)
  std::vector<double> t_s;
  std::vector<double> v_main, v_aux, at_main, at_aux, a_main, a_aux, a_eff;

  [[nodiscard]] std::size_t size() const { return beam.size(); }
  [[nodiscard]] Vec2 aux(std::size_t i) const { return beam[i] - main[i]; }  // (P, Q)
};

struct Peaks {
  double v_main = 0, v_aux = 0, a_main = 0, a_aux = 0, a_eff = 0;
  double aux_excursion = 0;  // max(|P|, |Q|)
  double exactness = 0;      // max |S1 + S2 − S|
  double duration_s = 0;
};

// Fills v_*, at_*, a_* from beam, main and t_s; v_main[0] and v_aux[0] are
// `v0_main`, `v0_aux` (the paper's method starts both at vk/2; the synchronous mode at
// rest).
void fill_derivatives(KinematicsTable& t, double v0_main, double v0_aux);

// The acceleration where a closed loop passes its start: rows `first` and
// `last` are the same point, so the motion runs … last−1 → last ≡ first →
// first+1 … (the one-sided differences at the table's ends would read the
// start of the cut as a jump).
[[nodiscard]] double loop_accel(const std::vector<Vec2>& x, const std::vector<double>& t_s, std::size_t first,
                                std::size_t last);

[[nodiscard]] Peaks peaks(const KinematicsTable& t);

// CSV, one header line then one row per point of every table:
// contour,i,x_mm,y_mm,p_mm,q_mm,t_s,v_main_mm_s,v_aux_mm_s,a_main_mm_s2,
// a_aux_mm_s2,at_main_mm_s2,at_aux_mm_s2,a_eff_mm_s2,sx_mm,sy_mm
void write_csv(std::ostream& out, const std::vector<const KinematicsTable*>& tables);

}  // namespace lcnc::decompose
