// Planner benchmark: cycle time against the time-optimal
// traversal of the same blended path, contour deviation against P, and
// planner throughput and memory.
//
//   build/bench/planner_bench [--csv DIR] [PROGRAM.ngc]   # the four cases (and
//                                     # their speed profiles as CSV), the square and
//                                     # the gear with a jerk limit, then throughput
//   build/bench/planner_bench --throughput-only PROGRAM.ngc [runs]
//   build/bench/planner_bench --stages PROGRAM.ngc [runs]   # the time of each
//                                     # stage: the pipeline cut after each one
//
// The reference is computed here, independently of the planner: the blended
// path the planner produced is sampled on a fine arc-length grid (ds), and the
// fastest traversal under the same per-axis limits is found by numerical
// integration in the phase plane (s, v²) — forward from rest at the largest
// tangential acceleration a_t with |t_i·a_t + κ_i·v²| ≤ amax_i on every axis i
// (t = dp/ds, κ = d²p/ds²), backward from rest at the largest deceleration,
// under the velocity limit curve v ≤ min(F, vmax_i/|t_i|, sqrt(amax_i/|κ_i|)),
// and the minimum of the two (Bobrow / Shin–McKay).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "common/share_path.h"
#include "gcode/program_reader.h"
#include "path/deviation_meter.h"
#include "plan/entry_stream.h"
#include "plan/lookahead.h"
#include "plan/path_blender.h"
#include "plan/planner.h"
#include "plan/program_source.h"

using namespace lcnc;

namespace {

constexpr double kVmax = 100.0;      // mm/s per axis
constexpr double kAmax = 2000.0;     // mm/s² per axis
constexpr double kTolerance = 0.01;  // G64 P, mm

MachineConfig bench_machine() {
  MachineConfig m;
  m.name = "bench";
  m.period_ns = 75'000;
  m.dda = DdaConfig{8, 300};
  m.max_feed_override = 1.0;  // the limits are the limits: no override headroom
  for (int i = 0; i < 3; ++i) {
    AxisConfig& a = m.axes[i];
    a.present = true;
    a.axis = static_cast<Axis>(i);
    a.min = 0.0;
    a.max = 1000.0;
    a.max_velocity = kVmax;
    a.max_acceleration = kAmax;
    a.steps_per_unit = 1000.0;
  }
  return m;
}

std::string fmt_xy(double x, double y) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "X%.4f Y%.4f", x, y);
  return buf;
}

// --- the four programs -------------------------------------------------------
std::string square_program() {
  std::string g = "G21 G90 G64 P0.01\nG1 F6000\n";
  for (int lap = 0; lap < 3; ++lap) g += "G1 X150 Y100\nG1 X150 Y150\nG1 X100 Y150\nG1 X100 Y100\n";
  return g + "M2\n";
}

std::string circle_program() {
  std::string g = "G21 G90 G64 P0.01\nG1 F6000\n";
  for (int k = 1; k <= 2000; ++k) {
    const double a = 2 * std::numbers::pi * k / 2000.0;
    g += "G1 " + fmt_xy(200 + 40 * std::cos(a), 200 + 40 * std::sin(a)) + "\n";
  }
  return g + "M2\n";
}

std::string zigzag_program() {
  // 200 strokes of 10 mm, 60° between consecutive strokes
  std::string g = "G21 G90 G64 P0.01\nG1 F3000\n";
  double x = 100, y = 100;
  for (int k = 0; k < 200; ++k) {
    const double a = (k % 2 == 0 ? 30.0 : -30.0) * std::numbers::pi / 180.0;
    x += 10 * std::cos(a);
    y += 10 * std::sin(a);
    g += "G1 " + fmt_xy(x, y) + "\n";
  }
  return g + "M2\n";
}

// A spur-gear-like outline, 20 teeth, r(φ) = 30 + 2.5·tanh(3 sin 20φ)/tanh 3,
// as CAM output: chords of 0.05 mm.
std::string gear_program(std::size_t* segments = nullptr) {
  auto radius = [](double phi) {
    return 30.0 + 2.5 * std::tanh(3.0 * std::sin(20.0 * phi)) / std::tanh(3.0);
  };
  std::string g = "G21 G90 G64 P0.01\n";
  double phi = 0.0;
  const double cx = 200, cy = 200;
  g += "G1 F6000\n";
  std::size_t n = 0;
  while (phi < 2 * std::numbers::pi) {
    // advance φ so the chord is 0.05 mm
    double dphi = 0.05 / 32.5;
    for (int it = 0; it < 20; ++it) {
      const double x0 = radius(phi) * std::cos(phi), y0 = radius(phi) * std::sin(phi);
      const double p1 = phi + dphi;
      const double x1 = radius(p1) * std::cos(p1), y1 = radius(p1) * std::sin(p1);
      const double len = std::hypot(x1 - x0, y1 - y0);
      dphi *= 0.05 / len;
      if (std::abs(len - 0.05) < 1e-6) break;
    }
    phi = std::min(phi + dphi, 2 * std::numbers::pi);
    g += "G1 " + fmt_xy(cx + radius(phi) * std::cos(phi), cy + radius(phi) * std::sin(phi)) + "\n";
    ++n;
  }
  if (segments) *segments = n;
  return g + "M2\n";
}

// --- the planner pipeline ----------------------------------------------------
struct PlannerRun {
  double cycle_s = 0.0;
  double max_dev_mm = 0.0;
  double peak_jerk = 0.0;               // mm/s³, largest |third difference|/T³ of a linear axis' poses
  JerkLimit jerk;                       // the filter the planner used
  std::vector<PlannedSegment> planned;  // the blended path, for the reference
  std::uint64_t segments = 0;
};

PlannerRun run_planner(const std::string& program, const Pose& start, const MachineConfig& m) {
  PlannerRun out;
  ReaderOptions opt;
  opt.start = start;
  auto reader = ProgramReader::from_string(program, "bench.ngc", m, opt);
  auto ref = ProgramReader::from_string(program, "bench.ngc", m, opt);
  Planner ci(m, reader_source(*reader));
  ci.on_planned([&](const PlannedSegment& p) { out.planned.push_back(p); });
  DeviationMeter dm(reader_source(*ref));
  // what a machine runs: the entries of the one chain from plan to RT
  // (quantized, ramp room, guarded), as `lasercnc run` pushes them
  EntryStream stream(m, ci, opt.start);
  std::array<std::int64_t, kAxisCount> pos{};
  for (int i = 0; i < kAxisCount; ++i) pos[i] = stream.start_steps(i);
  out.jerk = ci.jerk_limit();
  std::array<Pose, 4> last;  // the last poses, newest first
  last.fill(opt.start);
  const double T = m.period_s();
  PeriodIncrement inc;
  EntryStream::Next got;
  while ((got = stream.next(inc)) == EntryStream::Next::Entry) {
    for (std::size_t k = last.size() - 1; k > 0; --k) last[k] = last[k - 1];
    last[0] = stream.pose();
    for (int i = 0; i < 3; ++i) {
      const double d3 = last[0][i] - 3 * last[1][i] + 3 * last[2][i] - last[3][i];
      out.peak_jerk = std::max(out.peak_jerk, std::abs(d3) / (T * T * T));
    }
    for (int i = 0; i < 3; ++i) pos[i] += inc.steps[i];
    // rapids are not part of the contour
    if (inc.kind != MotionKind::Rapid) {
      dm.add(Vec3(pos[0] / 1000.0, pos[1] / 1000.0, pos[2] / 1000.0), inc.segment);
    }
  }
  if (got == EntryStream::Next::Limit) {  // a plan that breaks a limit measures nothing
    std::fprintf(stderr, "planner_bench: %s\n", stream.limit_error().to_string().c_str());
    std::exit(1);
  }
  out.cycle_s = static_cast<double>(ci.periods()) * m.period_s();
  out.max_dev_mm = dm.max_mm();
  return out;
}

// --- the time-optimal reference ----------------------------------------------
struct GridPoint {
  Vec3 t, k;     // dp/ds, d²p/ds²
  double v_lim;  // velocity limit curve
  double ds;     // step to the next point
};

// Largest (sign = +1) or smallest (sign = −1) tangential acceleration allowed
// at speed² v2 with |t_i·a + κ_i·v2| ≤ amax on every axis.
double a_bound(const GridPoint& g, double v2, double sign) {
  double lo = -1e300, hi = 1e300;
  for (int i = 0; i < 3; ++i) {
    const double c = g.k[i] * v2;
    if (std::abs(g.t[i]) < 1e-12) continue;  // axis does not see a_t
    double a1 = (-kAmax - c) / g.t[i], a2 = (kAmax - c) / g.t[i];
    if (a1 > a2) std::swap(a1, a2);
    lo = std::max(lo, a1);
    hi = std::min(hi, a2);
  }
  if (lo > hi) return 0.0;  // above the limit curve: neither speed up nor slow down
  return sign > 0 ? std::max(0.0, hi) : std::min(0.0, lo);
}

// Our planned speed at path length s into a segment (from its trapezoid).
double planned_speed(const Trapezoid& p, double s) {
  if (s < p.s_acc) return std::sqrt(p.v0 * p.v0 + 2.0 * p.accel * s);
  if (s < p.s_acc + p.s_cruise) return p.vc;
  return std::sqrt(std::max(0.0, p.vc * p.vc - 2.0 * p.decel * (s - p.s_acc - p.s_cruise)));
}

// Time-optimal traversal time; with `csv`, also writes s, v_optimal, v_ours
// every `csv_every` grid cells.
double optimal_time(const std::vector<PlannedSegment>& path, double ds_target, std::FILE* csv = nullptr,
                    int csv_every = 20) {
  std::vector<GridPoint> grid;
  std::vector<double> ours;  // our speed at each cell
  for (const PlannedSegment& p : path) {
    if (p.seg.kind == MotionKind::Rapid || p.seg.kind == MotionKind::Dwell) continue;
    const double L = p.geo.length();
    if (L <= 0.0) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(L / ds_target)));
    const double feed = p.programmed_speed > 0 ? p.seg.feed_mm_s : kVmax;
    for (int j = 0; j < n; ++j) {
      const double s = L * (j + 0.5) / n;  // cell midpoints
      GridPoint g;
      g.t = p.geo.tangent(s).head<3>();
      g.k = p.geo.curvature(s).head<3>();
      g.ds = L / n;
      double v = feed;
      for (int i = 0; i < 3; ++i) {
        if (std::abs(g.t[i]) > 1e-12) v = std::min(v, kVmax / std::abs(g.t[i]));
        if (std::abs(g.k[i]) > 1e-12) v = std::min(v, std::sqrt(kAmax / std::abs(g.k[i])));
      }
      g.v_lim = v;
      grid.push_back(g);
      if (csv != nullptr) ours.push_back(planned_speed(p.profile, s));
    }
  }
  const std::size_t n = grid.size();
  std::vector<double> fwd(n + 1), bwd(n + 1);
  fwd[0] = 0.0;  // v² at the boundaries of the cells: rest at both ends
  for (std::size_t k = 0; k < n; ++k) {
    const double v2 = std::min(fwd[k], grid[k].v_lim * grid[k].v_lim);
    fwd[k + 1] = std::min(v2 + 2.0 * a_bound(grid[k], v2, +1) * grid[k].ds, grid[k].v_lim * grid[k].v_lim);
  }
  bwd[n] = 0.0;
  for (std::size_t k = n; k-- > 0;) {
    const double v2 = std::min(bwd[k + 1], grid[k].v_lim * grid[k].v_lim);
    bwd[k] = std::min(v2 - 2.0 * a_bound(grid[k], v2, -1) * grid[k].ds, grid[k].v_lim * grid[k].v_lim);
  }
  double t = 0.0, s = 0.0;
  if (csv != nullptr) std::fprintf(csv, "s_mm,v_optimal,v_ours,v_limit\n");
  for (std::size_t k = 0; k < n; ++k) {
    const double v0 = std::sqrt(std::max(0.0, std::min(fwd[k], bwd[k])));
    const double v1 = std::sqrt(std::max(0.0, std::min(fwd[k + 1], bwd[k + 1])));
    t += 2.0 * grid[k].ds / std::max(v0 + v1, 1e-12);
    s += grid[k].ds;
    if (csv != nullptr && k % csv_every == 0)
      std::fprintf(csv, "%.5f,%.4f,%.4f,%.4f\n", s, 0.5 * (v0 + v1), ours[k], grid[k].v_lim);
  }
  return t;
}

long peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

// The program's reader, or nullptr after saying why it cannot be read.
std::unique_ptr<ProgramReader> open_program(const std::string& file, const MachineConfig& m) {
  auto reader = ProgramReader::open(file, m);
  if (!reader) {
    std::fprintf(stderr, "%s\n", reader.error().to_string().c_str());
    return nullptr;
  }
  return std::move(*reader);
}

// Planner throughput: the goal's four stages (parse + blend + look-ahead +
// coarse interpolation: one pose per period) and, in runs alternating with
// those, the same made into the position buffer's entries by the chain
// production runs (plan/entry_stream.h: steps, ramp room, guard). False
// when the program cannot be read.
bool throughput(const std::string& file, const MachineConfig& m, int runs) {
  std::vector<double> rates[2];
  for (int r = 0; r < runs; ++r) {
    for (int steps = 0; steps < 2; ++steps) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::unique_ptr<ProgramReader> reader = open_program(file, m);
      if (!reader) return false;
      const SegmentSource source = reader_source(*reader);
      std::uint64_t segs = 0;
      Planner ci(m, [&](Segment& s) {
        const SourceStatus st = source(s);
        if (st == SourceStatus::Item) ++segs;
        return st;
      });
      PeriodSample s;
      std::int64_t checksum = 0;
      double last_x = 0.0;
      if (steps == 1) {
        EntryStream stream(m, ci, Pose::Zero());
        PeriodIncrement inc;
        while (stream.next(inc) == EntryStream::Next::Entry) checksum += inc.steps[0];
      } else {
        while (ci.next(s) == SourceStatus::Item) last_x = s.pose[0];
      }
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      rates[steps].push_back(segs / sec);
      std::printf(
          "  run %d%s: %llu segments, %llu periods (%.0f s of motion) in %.3f s = %.0f "
          "segments/s (window max %zu, %s %lld)\n",
          r + 1, steps == 1 ? " with steps" : "", static_cast<unsigned long long>(segs),
          static_cast<unsigned long long>(ci.periods()), ci.periods() * m.period_s(), sec, segs / sec,
          ci.max_window(), steps == 1 ? "checksum" : "last X [µm]",
          steps == 1 ? static_cast<long long>(checksum)
                     : static_cast<long long>(std::llround(last_x * 1000.0)));
    }
  }
  for (auto& v : rates) std::sort(v.begin(), v.end());
  std::printf(
      "  median: %.0f segments/s through coarse interpolation; as RT entries (steps, ramp room, guard) "
      "%.0f segments/s; peak memory (max RSS) %ld MB\n",
      rates[0][rates[0].size() / 2], rates[1][rates[1].size() / 2], peak_rss_mb());
  return true;
}

// Where the throughput goes: the pipeline run whole up to each stage and cut
// there (parse; + corner blends; + look-ahead; + coarse interpolation; +
// the RT entries: steps, ramp room, guard), the median of `runs` for each; a stage costs the
// difference to the one before.
volatile std::int64_t g_sink = 0;

bool stages(const std::string& file, const MachineConfig& m, int runs) {
  static const char* const kNames[] = {"parse (reader)", "+ corner blends", "+ look-ahead",
                                       "+ coarse interpolation", "+ entries (steps, guard)"};
  double before = 0.0;
  std::printf("%-24s %10s %12s %10s\n", "pipeline up to", "items", "median [s]", "stage [s]");
  for (int stage = 0; stage < 5; ++stage) {
    std::vector<double> secs;
    std::uint64_t items = 0;
    for (int r = 0; r < runs; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::unique_ptr<ProgramReader> reader = open_program(file, m);
      if (!reader) return false;
      const SegmentSource source = reader_source(*reader);
      std::uint64_t n = 0;
      std::int64_t checksum = 0;
      if (stage == 0) {
        Segment s;
        while (source(s) == SourceStatus::Item) ++n;
      } else if (stage <= 2) {
        PathBlender blender(m, source);
        const IndexedSegment* s = nullptr;
        if (stage == 1) {
          while (blender.next(s) == SourceStatus::Item) ++n;
        } else {
          Lookahead la(m, [&](const IndexedSegment*& in) { return blender.next(in); });
          const PlannedSegment* p = nullptr;
          while (la.next(p) == SourceStatus::Item) ++n;
        }
      } else {
        Planner planner(m, source);
        if (stage == 4) {
          EntryStream stream(m, planner, Pose::Zero());
          PeriodIncrement inc;
          for (; stream.next(inc) == EntryStream::Next::Entry; ++n) checksum += inc.steps[0];
        } else {
          PeriodSample s;
          while (planner.next(s) == SourceStatus::Item) ++n;
        }
      }
      secs.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      items = n;
      g_sink = checksum;  // the entries' work is kept
    }
    std::sort(secs.begin(), secs.end());
    const double med = secs[secs.size() / 2];
    std::printf("%-24s %10llu %12.3f %10.3f\n", kNames[stage], static_cast<unsigned long long>(items), med,
                med - before);
    before = med;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const MachineConfig m = bench_machine();
  const char* csv_dir = nullptr;  // --csv DIR: speed profiles per case
  if (argc >= 3 && std::strcmp(argv[1], "--csv") == 0) {
    csv_dir = argv[2];
    argc -= 2;
    argv += 2;
  }
  if (argc >= 3 && std::strcmp(argv[1], "--throughput-only") == 0) {
    return throughput(argv[2], m, argc >= 4 ? std::max(1, std::atoi(argv[3])) : 3) ? 0 : 1;
  }
  if (argc >= 3 && std::strcmp(argv[1], "--stages") == 0) {
    return stages(argv[2], m, argc >= 4 ? std::max(1, std::atoi(argv[3])) : 5) ? 0 : 1;
  }
  struct Case {
    const char* name;
    const char* key;  // file name of its CSV
    std::string program;
    Pose start;  // the contour starts where the machine stands: no rapid
  };
  auto at = [](double x, double y) {
    Pose p = Pose::Zero();
    p << x, y, 5, 0, 0, 0;
    return p;
  };
  const Case cases[] = {
      {"square 50 mm, sharp corners, 3 laps, F6000", "square", square_program(), at(100, 100)},
      {"circle R40 of 2000 chords, F6000", "circle", circle_program(), at(240, 200)},
      {"zig-zag 60 deg, 200 strokes of 10 mm, F3000", "zigzag", zigzag_program(), at(100, 100)},
      {"gear outline, 0.05 mm CAM chords, F6000", "gear", gear_program(), at(230, 200)},
  };
  std::printf("vmax %.0f mm/s, amax %.0f mm/s^2 per axis, P %.3f mm, period 75 us\n", kVmax, kAmax,
              kTolerance);
  std::printf("%-46s %10s %10s %7s %10s\n", "case", "ours [s]", "optimum", "ratio", "dev [mm]");
  for (const Case& c : cases) {
    const PlannerRun r = run_planner(c.program, c.start, m);
    std::FILE* csv = nullptr;
    if (csv_dir != nullptr) csv = std::fopen((std::string(csv_dir) + "/" + c.key + ".csv").c_str(), "w");
    const double opt = optimal_time(r.planned, 0.0005, csv);
    if (csv != nullptr) std::fclose(csv);
    std::printf("%-46s %10.4f %10.4f %7.4f %10.5f\n", c.name, r.cycle_s, opt, r.cycle_s / opt, r.max_dev_mm);
  }
  // The shipped machine at 100 %: share/machines/default.toml (its feed
  // override up to 150 %, its startup modes, its P) with the limits above
  // and room to move, the programs without their G64 line — as a CAM file
  // that never writes one runs on it.
  {
    Result<MachineConfig> shipped = load_machine_config(share_path("machines/default.toml"));
    if (!shipped) {
      std::fprintf(stderr, "%s\n", shipped.error().to_string().c_str());
      return 1;
    }
    MachineConfig ms = *shipped;
    for (int i = 0; i < 3; ++i) {
      ms.axes[i].min = 0.0;
      ms.axes[i].max = 1000.0;
      ms.axes[i].max_velocity = kVmax;
      ms.axes[i].max_acceleration = kAmax;
    }
    std::printf(
        "\nshipped machine at 100 %% (default.toml: startup \"%s\", P %.3f mm, override up "
        "to %.0f %%), programs without G64\n",
        ms.startup_code.c_str(), ms.path_tolerance_mm, 100 * ms.max_feed_override);
    std::printf("%-46s %10s %10s %7s %10s\n", "case", "ours [s]", "optimum", "ratio", "dev [mm]");
    for (const Case& c : cases) {
      std::string program = c.program;
      const std::string g64 = " G64 P0.01";
      program.erase(program.find(g64), g64.size());
      const PlannerRun r = run_planner(program, c.start, ms);
      const double opt = optimal_time(r.planned, 0.0005, nullptr);
      std::printf("%-46s %10.4f %10.4f %7.4f %10.5f\n", c.name, r.cycle_s, opt, r.cycle_s / opt,
                  r.max_dev_mm);
    }
  }
  // Jerk limit (machine.max_jerk, plan/jerk_filter.h): the same programs at
  // J = 50 and 500 m/s³, against the plan without it.
  std::printf("\njerk limit: cycle time against the same plan without it\n");
  std::printf("%-46s %6s %5s %7s %9s %8s %9s %7s %9s %10s\n", "case", "J m/s3", "taps", "tau ms", "a mm/s2",
              "e_f mm", "ours [s]", "ratio", "dev [mm]", "jerk m/s3");
  for (const Case& c : cases) {
    if (std::strcmp(c.key, "square") != 0 && std::strcmp(c.key, "gear") != 0) continue;
    const PlannerRun plain = run_planner(c.program, c.start, m);
    for (const double jerk_m_s3 : {50.0, 500.0}) {
      MachineConfig mj = m;
      mj.max_jerk = jerk_m_s3 * 1000.0;
      const PlannerRun r = run_planner(c.program, c.start, mj);
      std::printf("%-46s %6.0f %5u %7.2f %9.1f %8.5f %9.4f %7.3f %9.5f %10.2f\n", c.name, jerk_m_s3,
                  r.jerk.taps, r.jerk.taps * m.period_s() * 1e3, r.jerk.accel_scale * kAmax, r.jerk.error_mm,
                  r.cycle_s, r.cycle_s / plain.cycle_s, r.max_dev_mm, r.peak_jerk / 1000.0);
    }
  }
  if (argc >= 2) {
    std::printf("throughput on %s\n", argv[1]);
    if (!throughput(argv[1], m, 3)) return 1;
  }
  return 0;
}
