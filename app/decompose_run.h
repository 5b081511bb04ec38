// `lasercnc decompose PART.dxf --run`: a decomposed part cut on the
// simulated machine with its main and auxiliary axes as two axis groups.
//
// The main group is the machine's X, Y (the heavy table: share/machines/
// default.toml); the auxiliary group is a fast stage or scanner with its own
// controller (share/machines/aux_stage.toml, whose X, Y are P, Q). Each group
// has its own RT kernel, position buffer and simulated drives; both kernels
// run at the same period from the same epoch (RtOptions::epoch_ns), so period
// k of one is period k of the other — one time base, as drive groups on a
// distributed clock. The kinematics tables are sampled at the period's end
// times: during a contour S1(t) to the main group and S2(t) to the auxiliary
// one, laser on while the beam moves; between contours each group makes its
// own rest-to-rest traverse (trapezoid at its speed and acceleration
// limits), laser off; the auxiliary group returns to the centre at the end.
//
// The report is measured from the kernels' traces: per group the steps sent
// against the steps commanded, peak speed and acceleration (over windows of
// kSpeedWindow / kAccelWindow periods: one step of quantization over a
// single period would read as ~10⁵ mm/s²), and the beam X + P, Y + Q against
// the contour at the same instant.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/result.h"
#include "decompose/decompose_svg.h"
#include "decompose/part_decomposition.h"
#include "machine/machine_config.h"
#include "rt/rt_clock.h"

namespace lcnc::app {

inline constexpr int kSpeedWindow = 4;   // periods: 0.3 ms at 75 µs
inline constexpr int kAccelWindow = 64;  // periods: 4.8 ms at 75 µs
// The most RT periods a run may take: every period's targets are computed
// before the run (about 150 B a period for the two groups), and the run
// takes its machine time in real time. 4 M periods: 5 min at 75 µs, 0.6 GB.
inline constexpr std::uint64_t kMaxRunPeriods = 4'000'000;

struct GroupReport {
  std::string name;               // "main" / "aux"
  std::array<char, 2> letters{};  // X Y / P Q
  std::array<std::int64_t, 2> steps_sent{}, steps_commanded{};
  double peak_speed = 0.0;  // mm/s, vector
  double peak_accel = 0.0;  // mm/s², vector, over kAccelWindow
  // The same while cutting (the window wholly within laser-on periods): what
  // the decomposition promised, without the traverses between contours.
  double cutting_speed = 0.0, cutting_accel = 0.0;
  double speed_limit = 0.0, accel_limit = 0.0;
  // What one step of quantization reads as over the windows: a peak within
  // limit + resolution keeps the limit.
  double speed_resolution = 0.0, accel_resolution = 0.0;
  std::uint64_t underruns = 0;
  bool fault = false;
  // The group's RT thread: how late it woke after the shared period
  // boundaries (p99.9 and worst).
  double latency_p999_us = 0.0, latency_max_us = 0.0;
};

struct DecomposeRunReport {
  GroupReport main, aux;
  std::uint64_t periods = 0;
  double cycle_time_s = 0.0;         // machine time of the whole run
  double cutting_time_s = 0.0;       // laser on
  double beam_deviation_mm = 0.0;    // max |(X + P, Y + Q) − S(t)| while cutting
  std::uint64_t traced_periods = 0;  // periods both groups' traces held, paired by index
  std::string warning;               // RT scheduling not available, …
  decompose::AxisCurves curves;      // executed positions, decimated
};

struct DecomposeRunOptions {
  bool realtime = true;  // try SCHED_FIFO + mlockall (wall clock only)
  // The wall clock, or the simulated clock (`--fast`; rt/rt_kernel.h RtClock):
  // each group's kernel then waits for its entries instead of running dry.
  rt::RtClock clock = rt::RtClock::Wall;
  // Where the part's origin is on the main axes (mm, machine coordinates).
  double origin_x_mm = 0.0, origin_y_mm = 0.0;
};

// The decomposition options the groups' configs allow: the main group's speed
// and acceleration limits (the lower of X, Y), the auxiliary group's speed
// and half field (the smaller of P, Q's travel about the centre). Fails with
// DecomposeBadOption when the aux stage's travel does not contain its centre.
[[nodiscard]] Result<decompose::Options> group_limits(const MachineConfig& main, const MachineConfig& aux,
                                                      decompose::Options opt);

// Runs the part. Fails before anything moves when the groups' periods differ,
// the part leaves a group's travel (DecomposeBeyondTravel, naming the
// contour and the point) or the run would take more than kMaxRunPeriods
// (DecomposeTooLarge, counted before any period is computed).
[[nodiscard]] Result<DecomposeRunReport> run_decomposition(const decompose::PartResult& part,
                                                           const MachineConfig& main,
                                                           const MachineConfig& aux,
                                                           const DecomposeRunOptions& options);

}  // namespace lcnc::app
