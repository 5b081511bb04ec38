// Orientation interpolators on a path through the A = 0 singularity
// (docs/design.md §5.6, Shao (2022) §4 and Fig. 16): maximum orientation error against
// the great circle and peak A/C speed and acceleration of each, and the CSV
// of the A/C curves and the error along the move for bench/plot_orientation.py.
//
//   build/bench/orientation_bench [--csv DIR]   # DIR default: orientation_csv
//
// The move: from (A, C) = (30°, 0°) to (30°, C1), C1 chosen so that the
// great circle passes the pole at δ (tan δ = tan 30°·sin((180° − C1)/2)),
// as a post-processor keeping A ≥ 0 writes it; 1 s rest to rest with 0.25 s
// ramps (80°/s along the 60° arc), sampled every 100 µs. Limits: A and C of
// share/machines/default.toml. Cases: δ = 0.005° (within the 0.01°
// tolerance), δ = 0 (exactly through the pole), δ = 0.5° (beyond it: the
// improved interpolator stays exact and needs re-timing instead). Each move
// is also re-timed within the A/C limits (orientation_retiming.h): the
// duration says what the interpolator costs when the limits are enforced.
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>

#include "kinematics/orientation_interpolation.h"
#include "kinematics/orientation_retiming.h"
#include "machine/machine_config.h"

namespace {

using namespace lcnc;

constexpr double kSampleDt = 1e-4;
constexpr TimeLaw kLaw{1.0, 0.25};
// Its peak du/dt and d²u/dt²: the caps of the re-timed law.
constexpr double kPeakURate = 1.0 / (1.0 * (1.0 - 0.25));
constexpr double kPeakUAccel = kPeakURate / 0.25;

double end_c(double delta_deg) {
  return 180.0 - 2.0 * std::asin(std::tan(delta_deg * kRadPerDeg) / std::tan(30.0 * kRadPerDeg)) / kRadPerDeg;
}

void write_csv(const std::string& path, const OrientationReport& r) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return;
  }
  std::fprintf(f, "t_s,u,a_deg,c_deg,a_vel_deg_s,c_vel_deg_s,a_acc_deg_s2,c_acc_deg_s2,error_deg\n");
  for (const OrientationSample& s : r.samples)
    std::fprintf(f, "%.5f,%.7f,%.7f,%.7f,%.5f,%.5f,%.4f,%.4f,%.9f\n", s.t_s, s.u, s.a_deg, s.c_deg,
                 s.a_vel_deg_s, s.c_vel_deg_s, s.a_acc_deg_s2, s.c_acc_deg_s2, s.error_deg);
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv_dir = "orientation_csv";
  if (argc >= 3 && std::strcmp(argv[1], "--csv") == 0) csv_dir = argv[2];
  ::mkdir(csv_dir.c_str(), 0755);

  RotaryLimits lim;
  const Result<MachineConfig> cfg =
      load_machine_config(std::string(LCNC_SHARE_DIR) + "/machines/default.toml");
  if (cfg) lim = rotary_limits_from(*cfg);
  std::printf("limits: A %.0f °/s, %.0f °/s²; C %.0f °/s, %.0f °/s²; tolerance %.3f°\n",
              lim.a_max_velocity_deg_s, lim.a_max_accel_deg_s2, lim.c_max_velocity_deg_s,
              lim.c_max_accel_deg_s2, kin::kOrientationToleranceDeg);
  std::printf(
      "move (30°, 0°) → (30°, C1), 1 s rest to rest, 0.25 s ramps, "
      "sampled every %.0f µs\n\n",
      kSampleDt * 1e6);
  std::printf(
      "| pole distance δ | interpolator | max orientation error | peak A speed "
      "| peak A accel | peak C speed | peak C accel | within A/C limits | re-timed: duration "
      "| re-timed: peak C speed, accel |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");

  for (double delta : {0.005, 0.0, 0.5}) {
    const RotaryJoints a{30.0, 0.0}, b{30.0, end_c(delta)};
    for (OrientationMethod m :
         {OrientationMethod::JointLinear, OrientationMethod::Vector, OrientationMethod::PoleSmoothed}) {
      const Result<OrientationMove> move = OrientationMove::between_joints(m, a, b, lim);
      if (!move) {
        std::fprintf(stderr, "%s\n", move.error().to_string().c_str());
        return 1;
      }
      const OrientationReport r = evaluate(*move, kLaw, kSampleDt);
      // Re-timing under the A/C limits, capped at the nominal law's peak du/dt
      // and d²u/dt² (orientation_retiming.h).
      const RetimedLaw slow = retime(*move, lim, kPeakURate, kPeakUAccel);
      const OrientationReport rs = evaluate(*move, slow, kSampleDt);
      std::printf(
          "| %.3f° | %s%s | %.4g° | %.0f °/s | %.4g °/s² | %.4g °/s | %.4g °/s² | %s "
          "| %.3g s | %.4g °/s, %.4g °/s² |\n",
          delta, method_name(m), move->pole_snapped() ? " (snapped)" : "", r.max_error_deg,
          r.peak_a_vel_deg_s, r.peak_a_acc_deg_s2, r.peak_c_vel_deg_s, r.peak_c_acc_deg_s2,
          r.within(lim) ? "yes" : "**no**", slow.duration_s(), rs.peak_c_vel_deg_s, rs.peak_c_acc_deg_s2);
      if (delta == 0.005) {
        std::string name = method_name(m);
        for (char& ch : name)
          if (ch == '-') ch = '_';
        write_csv(csv_dir + "/" + name + ".csv", r);
      }
    }
  }
  std::printf("\nCSV (δ = 0.005°) in %s/: joint_linear.csv vector.csv pole_smoothed.csv\n", csv_dir.c_str());
  return 0;
}
