// Property: whatever a program says, the motion it gets keeps every limit.
// Random programs with extreme but possibly accepted values — feeds from
// 1e-6 to 1e6 mm/min (and G93 times), arcs from microns to metres of
// radius, helices, C moves that wrap, blend tolerances from none to huge,
// tool-centre-point moves with A near 0 on both of its sides — are each
// either refused by the check with a located error, or planned, sampled
// every period and quantized to steps as the RT gets them; then
//   * every period's increment passes the IncrementGuard (travel, velocity,
//     acceleration with the rounding allowed),
//   * the step positions, measured as an outsider would (MotionCheck's
//     windows), keep every axis' velocity and acceleration limit,
//   * the executed X Y Z stay within the tolerance in effect of the
//     programmed path (DeviationMeter); under TCP the joints' X Y Z keep
//     the joint segments', and the tool tip the program's (see check_one).
// The number of programs is LCNC_PROPERTY_PROGRAMS (default 10,000), the
// seed fixed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "core/plan/test_machine.h"
#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "path/deviation_meter.h"
#include "plan/entry_stream.h"
#include "plan/motion_check.h"
#include "plan/planner.h"
#include "plan/program_source.h"

namespace lcnc {
namespace {

namespace fs = std::filesystem;

int program_count() {
  const char* env = std::getenv("LCNC_PROPERTY_PROGRAMS");
  return env != nullptr ? std::max(1, std::atoi(env)) : 10'000;
}

// Longest a program may run, periods: the generator keeps programs far
// shorter; one that is not is itself a finding (a feed that never ends).
constexpr std::uint64_t kMaxPeriods = 2'000'000;

class Generator {
 public:
  // rotary: A and C words on the moves (C on the first rapid either way).
  Generator(std::uint32_t seed, bool rotary) : rng_(seed), rotary_(rotary) {}

  std::string program(bool tcp) {
    std::ostringstream g;
    g.precision(12);
    g << "G21 G90 G94 G17\n";
    const int mode = pick(0, 3);
    if (mode == 0) g << "G61\n";
    if (mode == 1) g << "G64\n";
    if (mode == 2) g << "G64 P" << feed(log_uniform(1e-6, 1e3), tcp) << "\n";
    if (mode == 3) {
      const double p = log_uniform(1e-4, 1.0);
      g << "G64 P" << feed(p, tcp) << " Q" << feed(log_uniform(1e-5, 0.1), tcp) << "\n";
    }
    x_ = uniform(150, 250);
    y_ = uniform(150, 250);
    z_ = uniform(100, 150);
    a_ = tcp ? uniform(-1, 1) : 0.0;
    c_ = uniform(0, 359);
    g << "G0 X" << x_ << " Y" << y_ << " Z" << z_ << (tcp ? " A" + num(a_) : "") << " C" << c_ << "\n";
    g << "M3 S" << uniform(0, 100) << "\n";
    const int moves = pick(2, 12);
    bool inverse_time = false;
    for (int k = 0; k < moves; ++k) {
      const double f = log_uniform(tcp ? 1e-3 : 1e-6, 1e6);  // mm/min (under TCP: all accepted)
      // short enough at its feed that no program runs long: ≤ 0.03 s
      const double reach = std::min(log_uniform(1e-4, 30.0), f / 60.0 * 0.03);
      const int kind = pick(0, tcp ? 3 : 6);
      if (kind <= 2) {  // G1, some with rotary axes, some in inverse time
        const bool g93 = pick(0, 5) == 0;
        if (g93 != inverse_time) g << (g93 ? "G93\n" : "G94\n");
        inverse_time = g93;
        step(reach, tcp);
        g << "G1 X" << x_ << " Y" << y_ << " Z" << z_;
        if (tcp || (rotary_ && pick(0, 2) == 0)) g << " A" << a_;
        if (rotary_ && pick(0, 1) == 0) g << " C" << c_;
        // G93: F = 1 / minutes; a time of 1e-6 … 0.03 s
        g << " F" << feed(g93 ? 60.0 / log_uniform(1e-6, 0.03) : f, tcp) << "\n";
      } else if (kind == 3) {  // a rapid
        step(std::min(reach, 5.0), tcp);
        g << "G0 X" << x_ << " Y" << y_ << " Z" << z_ << (tcp ? " A" + num(a_) : "");
        if (rotary_) g << " C" << c_;
        g << "\n";
      } else {  // an arc (IJ) or helix in XY, a radius from microns to metres
        if (inverse_time) g << "G94\n";
        inverse_time = false;
        const double sweep = uniform(0.01, 6.0);
        const double r = std::min(log_uniform(1e-3, 2000.0), reach / sweep);
        if (r < 1e-4) continue;  // no arc fits the time at this feed
        const double phi = uniform(0, 2 * M_PI);
        const double cx = x_ - r * std::cos(phi), cy = y_ - r * std::sin(phi);
        const bool cw = pick(0, 1) == 0;
        const double end = phi + (cw ? -sweep : sweep);
        const double ex = cx + r * std::cos(end), ey = cy + r * std::sin(end);
        if (ex < 1 || ex > 999 || ey < 1 || ey > 449) continue;  // off the table
        const double dz = kind == 6 ? uniform(-1, 1) * std::min(2.0, reach) : 0.0;
        if (z_ + dz < 1 || z_ + dz > 499) continue;
        g << (cw ? "G2" : "G3") << " X" << ex << " Y" << ey << " Z" << z_ + dz << " I" << cx - x_ << " J"
          << cy - y_;
        if (kind == 6 && pick(0, 3) == 0 && 2 * M_PI * r * 4 < reach) g << " P" << pick(2, 4);
        g << " F" << f << "\n";
        x_ = ex;
        y_ = ey;
        z_ += dz;
      }
    }
    g << "M5\nM2\n";
    return g.str();
  }

 private:
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  // Under TCP without exponents, so most programs are read and planned (the
  // other runs keep their programs as they were; their refusals are checked too).
  static std::string feed(double v, bool tcp) {
    if (!tcp) {
      std::ostringstream o;
      o.precision(12);
      o << v;
      return o.str();
    }
    char b[64];
    std::snprintf(b, sizeof b, "%.9f", v);
    return b;
  }
  static std::string num(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
  }
  void step(double reach, bool tcp) {
    const double d = reach / std::sqrt(3.0);
    x_ = std::clamp(x_ + uniform(-d, d), 100.0, 300.0);
    y_ = std::clamp(y_ + uniform(-d, d), 100.0, 300.0);
    z_ = std::clamp(z_ + uniform(-d, d), 50.0, 200.0);
    // A near the pole from either side; C turning on past 360 and back
    a_ = tcp ? std::clamp(a_ + uniform(-2, 2), -3.0, 3.0) : std::clamp(a_ + uniform(-10, 10), -60.0, 60.0);
    c_ += uniform(-200, 200) * std::min(1.0, reach);
  }

  std::mt19937 rng_;
  bool rotary_;
  double x_ = 0, y_ = 0, z_ = 0, a_ = 0, c_ = 0;
};

struct Tally {
  int planned = 0, refused = 0;
  std::uint64_t periods = 0;
};

// Plans `path` on `m`; a failure of any property is an assertion with the
// program shown.
void check_one(const std::string& path, const std::string& text, const MachineConfig& m, bool tcp,
               Tally& tally) {
  Result<ProgramSummary> summary = check_job_program(path, m);
  if (!summary) {  // a clear refusal: located and said
    const Diagnostic& e = summary.error();
    ASSERT_GT(e.line, 0u) << e.to_string() << "\n" << text;
    ASSERT_FALSE(e.message.empty()) << text;
    if (std::getenv("LCNC_PROPERTY_SHOW")) std::printf("refused: %s\n", e.to_string().c_str());
    ++tally.refused;
    return;
  }
  ++tally.planned;
  Result<std::unique_ptr<ProgramSource>> src = ProgramSource::open(path, m, {});
  ASSERT_TRUE(static_cast<bool>(src)) << src.error().to_string();
  Result<std::unique_ptr<ProgramSource>> ref = ProgramSource::open(path, m, {});
  ASSERT_TRUE(static_cast<bool>(ref));
  Planner planner(m, (*src)->source());
  EntryStream stream(m, planner, Pose::Zero());  // what `lasercnc run` pushes: guarded entries
  std::array<std::int64_t, kAxisCount> at{};
  for (int i = 0; i < kAxisCount; ++i) at[i] = stream.start_steps(i);
  MotionCheck motion(m, at);
  DeviationMeter deviation((*ref)->source(), m.path_tolerance_mm, xyz_rounding_mm(m));
  // under TCP the tool tip, held to the program as written
  Result<std::unique_ptr<ProgramReader>> tips = open_tip_program(path, m);
  ASSERT_TRUE(static_cast<bool>(tips));
  DeviationMeter tip((reader_source(**tips)), m.path_tolerance_mm, tip_rounding_mm(m),
                     m.tcp.tip_tolerance_mm);
  const FiveAxisKinematics kin = kinematics_from(m);
  std::uint64_t k = 0;
  auto take = [&](const PeriodIncrement& inc) {
    ++k;
    for (int i = 0; i < kAxisCount; ++i) at[i] += inc.steps[i];
    motion.add(static_cast<std::int64_t>(k) * m.period_ns, at, inc.line);
    Pose p = Pose::Zero();
    for (int i = 0; i < kAxisCount; ++i) {
      if (m.axes[i].present) p[i] = static_cast<double>(at[i]) / m.axes[i].steps_per_unit;
    }
    deviation.add(p.head<3>(), inc.segment);
    if (tcp) tip.add_at_line(kin.forward(p).tip_mm, inc.line);
  };
  PeriodIncrement inc;
  EntryStream::Next got;
  while ((got = stream.next(inc)) == EntryStream::Next::Entry) {
    take(inc);
    if (::testing::Test::HasFatalFailure()) return;
    ASSERT_LT(k, kMaxPeriods) << "a program that does not end\n" << text;
  }
  ASSERT_NE(got, EntryStream::Next::Limit) << stream.limit_error().to_string() << "\n" << text;
  ASSERT_EQ(got, EntryStream::Next::End) << text;
  motion.finish();
  ASSERT_TRUE(motion.ok()) << motion.breaches().front() << "\n" << text;
  ASSERT_EQ(deviation.excess_mm(), 0.0)
      << "deviation beyond " << deviation.excess_tolerance_mm() << " by " << deviation.excess_mm()
      << " at line " << deviation.excess_line() << "\n"
      << text;
  ASSERT_EQ(tip.excess_mm(), 0.0) << "tool tip deviation beyond " << tip.excess_tolerance_mm() << " by "
                                  << tip.excess_mm() << " at line " << tip.excess_line() << "\n"
                                  << text;
  tally.periods += k;
}

void run_property(bool tcp, bool rotary, std::uint32_t seed, int programs) {
  const MachineConfig m = testing::shipped_machine(tcp);
  const fs::path dir = fs::temp_directory_path() / ("lcnc_property_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "p.ngc").string();
  Generator gen(seed, rotary);
  Tally tally;
  for (int n = 0; n < programs; ++n) {
    const std::string text = gen.program(tcp);
    std::ofstream(path, std::ios::trunc) << text;
    check_one(path, text, m, tcp, tally);
    if (::testing::Test::HasFatalFailure()) {
      ADD_FAILURE() << "program " << n << " of seed " << seed;
      break;
    }
  }
  fs::remove_all(dir);
  std::printf("%d programs: %d planned (%llu periods), %d refused by the check\n", programs, tally.planned,
              static_cast<unsigned long long>(tally.periods), tally.refused);
  EXPECT_GT(tally.planned, programs / 4);  // the property is about motion: most must run
}

TEST(RandomProgramProperty, EveryAcceptedProgramKeepsEveryLimitAndItsTolerance) {
  run_property(false, false, 19, program_count());
}

TEST(RandomProgramProperty, WithRotaryAxesMovingAlong) { run_property(false, true, 21, program_count()); }

// Under TCP the tool tip (forward kinematics of the executed joints) is
// held to the program as written, too. This run once planned its first
// program for over 150 s (a rapid's pieces became feed moves of feed 0) and
// later swung the tip 1–6 mm off the path where a move began on the other
// A/C branch than the machine stood on, and up to 21 µm past P where a blend
// ran the rotary axes linearly across a corner.
TEST(RandomProgramProperty, UnderToolCentrePointControlToo) {
  run_property(true, true, 20, std::max(1, program_count() / 8));
}

}  // namespace
}  // namespace lcnc
