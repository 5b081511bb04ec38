// 5-axis tool-centre-point programs against the time-optimal bound of the
// joint path they followed: five programs on the head-head and the
// table-table variant of share/machines/default.toml ([kinematics] tcp on).
//
//   build/bench/tcp_bench                  # the table
//   build/bench/tcp_bench PROGRAM [hh|tt]  # one program
//
// Each program is planned as `lasercnc run --fast` plans it (the same
// program source, expander and planner, the machine starting at the
// reader's default position); its cycle time is the planner's periods.
// The bound (phase-plane, docs/design.md §5.6 "Time-optimal bound"): the
// executed joint path (the planned pose of every period) is resampled by
// its arc length in X Y Z A C (mm and degrees alike) at kGridStep, q' and
// q'' are read over ±kStencil of path, and the time-optimal traversal of
// that path is found under
//   |q_i'·s̈ + q_i''·ṡ²| ≤ amax_i,  |q_i'|·ṡ ≤ vmax_i   (every joint),
//   tip speed ≤ F on feed moves (F, deg/s, of A and C on moves where the
//   tip stands still: RS274NGC's feed of a rotary move),
// by the forward/backward passes on x = ṡ² (Bobrow; Pham's TOPP): the
// path rests where the run rests for a dwell (the dwell's time added), and
// nowhere else unless the path itself has a corner. The same run's motion is
// checked against the joint limits as the run's own check does
// (plan/motion_check.h) on the steps it would send.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "kinematics/five_axis.h"
#include "machine/machine_config.h"
#include "plan/coarse_interpolator.h"
#include "plan/motion_check.h"
#include "plan/planner.h"
#include "plan/program_source.h"

namespace {

using namespace lcnc;

constexpr double kGridStep = 0.01;  // resampling step of the path (mm or deg)
constexpr int kStencil = 10;        // derivatives over ±kStencil grid steps (±0.1 mm)
constexpr int kBisections = 50;

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  std::string s = b;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

struct Program {
  std::string name;
  std::string text;
};

// The five programs, their tip coordinates about (cx, cy) at Z20.
std::vector<Program> programs(double cx, double cy) {
  std::vector<Program> out;
  const auto x = [&](double d) { return " X" + num(cx + d); };
  const auto y = [&](double d) { return " Y" + num(cy + d); };
  // share/examples/tcp_bevel.ngc, moved to (cx, cy)
  out.push_back({"tcp_bevel", "G21 G90 G64 P0.01\nG0" + x(-30) + y(-20) + " Z20 A0 C0\nM3 S80\nG1" + x(30) +
                                  " A20 F1200\nG1" + y(20) + " C90\nG1" + x(-30) + " C180\nG1" + y(-20) +
                                  " A0\nM5\nG0 Z40\nM2\n"});
  {
    std::string p = "G21 G90 G64 P0.01\nG0" + x(-50) + y(-50) + " Z20 A30 C0\nM3 S80\n";
    const double cs[4][2] = {{50, -50}, {50, 50}, {-50, 50}, {-50, -50}};
    for (int e = 0; e < 4; ++e) {
      p += "G1" + x(cs[e][0]) + y(cs[e][1]) + (e == 0 ? " F2400" : "") + "\n";
      p += "G1 C" + num(90.0 * (e + 1)) + "\n";
    }
    out.push_back({"bevel square", p + "M5\nM2\n"});
  }
  {
    constexpr double kR = 30.0;
    std::string p = "G21 G90 G64 P0.01\nG0" + x(0) + y(-kR) + " Z20 A20 C0\nM3 S80\n";
    for (int k = 1; k <= 360; ++k) {
      const double phi = (k - 90.0) * std::numbers::pi / 180.0;
      p += "G1" + x(kR * std::cos(phi)) + y(kR * std::sin(phi)) + " C" + std::to_string(k) +
           (k == 1 ? " F3000" : "") + "\n";
    }
    out.push_back({"tilted circle", p + "M5\nM2\n"});
  }
  {
    std::string p = "G21 G90 G64 P0.01\n";
    for (int k = 0; k < 20; ++k)
      p += "G0" + x(-95.0 + 10.0 * k) + y(0) + " Z20 A" + (k % 2 == 0 ? "30" : "-30") + " C" + num(18.0 * k) +
           "\nM3 S80\nG4 P0.05\nM5\n";
    out.push_back({"tilted holes", p + "M2\n"});
  }
  out.push_back({"sweep through A = 0", "G21 G90 G64 P0.01\nG0" + x(-50) + y(-25) +
                                            " Z20 A-30 C0\nM3 S80\nG1" + x(50) + " A30 F600\nG1" + y(25) +
                                            " C179.98\nM5\nM2\n"});
  return out;
}

struct Sample {
  double t = 0.0;
  Pose q = Pose::Zero();
  std::uint32_t line = 0;
  bool dwell = false;
};

// What the bound needs of a program line: its feed (mm/s, or deg/s where
// the tip stands still) and whether the tip moves; rapids have none.
struct LineFeed {
  double feed = 0.0;
  bool tip_moves = true;
};

struct Run {
  double cycle_s = 0.0;
  std::vector<Sample> samples;
  bool limits_ok = false;
  std::string breach;
  std::size_t segments = 0;
};

Result<Run> plan(const std::string& path, const MachineConfig& m) {
  Result<std::unique_ptr<ProgramSource>> src = ProgramSource::open(path, m, ReaderOptions{});
  if (!src) return src.error();
  Planner planner(m, (*src)->source());
  Run run;
  planner.on_planned([&](const PlannedSegment&) { ++run.segments; });
  StepQuantizer q(m, ReaderOptions{}.start);
  std::array<std::int64_t, kAxisCount> start{};
  for (int i = 0; i < kAxisCount; ++i) start[i] = q.commanded(i);
  MotionCheck check(m, start);
  PeriodSample s;
  SourceStatus st;
  while ((st = planner.next(s)) == SourceStatus::Item) {
    run.samples.push_back({s.t_s, s.pose, s.line, s.kind == MotionKind::Dwell});
    std::array<std::int64_t, kAxisCount> steps{};
    for (int i = 0; i < kAxisCount; ++i) steps[i] = m.axes[i].present ? q.to_steps(i, s.pose[i]) : 0;
    check.add(static_cast<std::int64_t>(std::llround(s.t_s * 1e9)), steps, s.line);
  }
  if (st == SourceStatus::Error) return (*src)->error();
  check.finish();
  run.limits_ok = check.ok();
  if (!run.limits_ok) run.breach = check.breaches().front();
  run.cycle_s = run.samples.empty() ? 0.0 : run.samples.back().t;
  return run;
}

std::map<std::uint32_t, LineFeed> line_feeds(const std::string& path, const MachineConfig& m) {
  std::map<std::uint32_t, LineFeed> out;
  Result<std::unique_ptr<ProgramReader>> r = open_tip_program(path, m, ReaderOptions{});
  if (!r) return out;
  Segment s;
  while ((*r)->next(s) == ProgramReader::Next::Segment) {
    if (s.kind == MotionKind::Dwell) continue;
    LineFeed f;
    f.feed = s.kind == MotionKind::Rapid ? 0.0 : s.feed_mm_s;
    f.tip_moves = (s.end.head<3>() - s.start.head<3>()).norm() > 1e-9;
    out[s.line] = f;
  }
  return out;
}

// One stretch of path between rests, resampled: q, the tip and the feed
// bound at each grid point.
struct Grid {
  std::vector<Pose> q;
  std::vector<double> feed;  // 0: none
  std::vector<bool> tip_moves;
};

// Time-optimal traversal (rest to rest) of the grid.
double optimum(const Grid& g, const MachineConfig& m, const FiveAxisKinematics& kin) {
  const int n = static_cast<int>(g.q.size());
  if (n < 3) return 0.0;
  const double h = kGridStep;
  std::vector<Pose> d1(n), d2(n);
  std::vector<double> feed_cap(n, std::numeric_limits<double>::infinity());
  std::vector<Vec3> tip(n);
  for (int i = 0; i < n; ++i) tip[i] = kin.forward(g.q[i]).tip_mm;
  for (int i = 0; i < n; ++i) {
    const int k = std::min({kStencil, i, n - 1 - i});
    if (k == 0) {
      const int j = i == 0 ? 1 : n - 2;
      d1[i] = (g.q[std::max(i, j)] - g.q[std::min(i, j)]) / h;
      d2[i] = Pose::Zero();
    } else {
      d1[i] = (g.q[i + k] - g.q[i - k]) / (2.0 * k * h);
      d2[i] = (g.q[i + k] - 2.0 * g.q[i] + g.q[i - k]) / (k * h * k * h);
    }
    if (g.feed[i] > 0.0) {
      const int a = std::max(0, i - 1), b = std::min(n - 1, i + 1);
      const double ds = (b - a) * h;
      const double rate =
          g.tip_moves[i] ? (tip[b] - tip[a]).norm() / ds : (g.q[b].tail<3>() - g.q[a].tail<3>()).norm() / ds;
      if (rate > 1e-12) feed_cap[i] = std::pow(g.feed[i] / rate, 2);
    }
  }
  // s̈ range at grid i and x = ṡ²: [lo, hi]; empty (lo > hi) when x is too fast
  auto range = [&](int i, double x, double& lo, double& hi) {
    lo = -std::numeric_limits<double>::infinity();
    hi = std::numeric_limits<double>::infinity();
    for (int j = 0; j < kAxisCount; ++j) {
      const AxisConfig& ax = m.axes[j];
      if (!ax.present) continue;
      const double a = ax.max_acceleration, k1 = d1[i][j], k2 = d2[i][j] * x;
      if (std::abs(k1) < 1e-12) {
        if (std::abs(k2) > a) lo = 1, hi = 0;
        continue;
      }
      double u0 = (-a - k2) / k1, u1 = (a - k2) / k1;
      if (u0 > u1) std::swap(u0, u1);
      lo = std::max(lo, u0);
      hi = std::min(hi, u1);
    }
  };
  std::vector<double> mvc(n);
  for (int i = 0; i < n; ++i) {
    double cap = feed_cap[i];
    for (int j = 0; j < kAxisCount; ++j) {
      const AxisConfig& ax = m.axes[j];
      if (ax.present && std::abs(d1[i][j]) > 1e-12)
        cap = std::min(cap, std::pow(ax.max_velocity / d1[i][j], 2));
    }
    double lo, hi;
    range(i, cap, lo, hi);
    if (lo > hi) {  // the largest x with a feasible s̈
      double a = 0.0, b = cap;
      for (int it = 0; it < kBisections; ++it) {
        const double mid = 0.5 * (a + b);
        range(i, mid, lo, hi);
        (lo <= hi ? a : b) = mid;
      }
      cap = a;
    }
    mvc[i] = cap;
  }
  std::vector<double> x(n);
  x[n - 1] = 0.0;
  for (int i = n - 1; i > 0; --i) {  // backward: the most it may enter with
    double lo, hi;
    range(i, x[i], lo, hi);
    x[i - 1] = std::min(mvc[i - 1], std::max(0.0, x[i] - 2.0 * h * std::min(lo, 0.0)));
  }
  x[0] = 0.0;
  for (int i = 0; i + 1 < n; ++i) {  // forward
    double lo, hi;
    range(i, x[i], lo, hi);
    x[i + 1] = std::min(x[i + 1], x[i] + 2.0 * h * std::max(hi, 0.0));
  }
  double t = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double v = std::sqrt(x[i]) + std::sqrt(x[i + 1]);
    t += v > 0.0 ? 2.0 * h / v : 0.0;
  }
  return t;
}

// The bound of a whole run: each stretch between dwells, plus the dwells.
double optimum(const Run& run, const std::map<std::uint32_t, LineFeed>& feeds, const MachineConfig& m) {
  const FiveAxisKinematics kin(m.kinematics, rotary_limits_from(m));
  double total = 0.0;
  std::vector<Sample> stretch;
  auto flush = [&] {
    if (stretch.size() < 2) {
      stretch.clear();
      return;
    }
    // arc length in X Y Z A C
    std::vector<double> s(stretch.size(), 0.0);
    for (std::size_t k = 1; k < stretch.size(); ++k)
      s[k] = s[k - 1] + (stretch[k].q - stretch[k - 1].q).norm();
    Grid g;
    std::size_t k = 0;
    for (double at = 0.0; at <= s.back(); at += kGridStep) {
      while (k + 2 < s.size() && s[k + 1] < at) ++k;
      const double span = s[k + 1] - s[k];
      const double f = span > 0.0 ? std::clamp((at - s[k]) / span, 0.0, 1.0) : 0.0;
      g.q.push_back(stretch[k].q + f * (stretch[k + 1].q - stretch[k].q));
      const auto it = feeds.find(stretch[k + 1].line);
      g.feed.push_back(it == feeds.end() ? 0.0 : it->second.feed);
      g.tip_moves.push_back(it == feeds.end() || it->second.tip_moves);
    }
    total += optimum(g, m, kin);
    stretch.clear();
  };
  // from the start, at rest; a dwell rests (its time counted as it is) and
  // the path goes on from there
  stretch.push_back(Sample{0.0, ReaderOptions{}.start, 0, false});
  double last_t = 0.0;
  for (const Sample& p : run.samples) {
    if (p.dwell) {
      flush();
      total += p.t - last_t;
    }
    stretch.push_back(p);
    last_t = p.t;
  }
  flush();
  return total;
}

MachineConfig variant(bool table) {
  Result<MachineConfig> m = load_machine_config(std::string(LCNC_SHARE_DIR) + "/machines/default.toml");
  if (!m) {
    std::fprintf(stderr, "%s\n", m.error().to_string().c_str());
    std::exit(1);
  }
  m->tcp.enabled = true;
  if (table) m->kinematics.variant = MachineVariant::TableTable;
  return *m;
}

}  // namespace

int main(int argc, char** argv) {
  // one program of the user's: tcp_bench FILE [hh|tt]
  if (argc > 1) {
    const MachineConfig m = variant(argc > 2 && std::strcmp(argv[2], "tt") == 0);
    Result<Run> run = plan(argv[1], m);
    if (!run) {
      std::fprintf(stderr, "%s\n", run.error().to_string().c_str());
      return 1;
    }
    const double opt = optimum(*run, line_feeds(argv[1], m), m);
    std::printf("%s: %zu segments, cycle %.3f s, optimum %.3f s, ratio %.3f, limits %s\n", argv[1],
                run->segments, run->cycle_s, opt, run->cycle_s / opt,
                run->limits_ok ? "kept" : run->breach.c_str());
    return run->limits_ok ? 0 : 1;
  }
  std::printf("| program | variant | segments | cycle s | optimum s | ratio | limits |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  bool all_ok = true;
  for (const bool table : {false, true}) {
    const MachineConfig m = variant(table);
    // head-head: about X150 Y150; table-table: about the table centre
    for (const Program& p : programs(table ? 0.0 : 150.0, table ? 0.0 : 150.0)) {
      const std::string path = "/tmp/tcp_bench_" + std::to_string(::getpid()) + ".ngc";
      std::ofstream(path) << p.text;
      Result<Run> run = plan(path, m);
      if (!run) {
        std::printf("| %s | %s | error: %s |\n", p.name.c_str(), table ? "tt" : "hh",
                    run.error().to_string().c_str());
        all_ok = false;
        continue;
      }
      const double opt = optimum(*run, line_feeds(path, m), m);
      std::remove(path.c_str());
      all_ok = all_ok && run->limits_ok;
      std::printf("| %s | %s | %zu | %.2f | %.2f | %.2f | %s |\n", p.name.c_str(), table ? "tt" : "hh",
                  run->segments, run->cycle_s, opt, run->cycle_s / opt,
                  run->limits_ok ? "kept" : run->breach.c_str());
      std::fflush(stdout);
    }
  }
  return all_ok ? 0 : 1;
}
