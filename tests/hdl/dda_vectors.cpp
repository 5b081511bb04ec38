// Co-verification of hdl/ with the C++ DDA (docs/design.md §5.4, §9).
//
//   dda_vectors expect VECTORS.inc EXPECTED     the pulse trains rt::Dda makes
//   dda_vectors compare EXPECTED ACTUAL         identical, or exit 1 naming the differences
//   dda_vectors generate KIND VECTORS.inc       writes a shared vector file (seeded)
//
// `expect` runs the increments of a vector file (tests/vectors/README.md)
// through rt::Dda::run_period — the closed form the RT kernel uses — and,
// axis by axis, through the tick loop rt::Dda::reference_period; the two must
// agree (exit 2 otherwise: a C++ DDA bug). It writes, per period, "P p D"
// and then one line "p t a s" per pulse (period, tick 0 … N−1, axis, + or −),
// ordered by tick, then axis: the format the VHDL testbench writes from the
// pins (hdl/tb/tb_microstep_interpolator.vhd), so the two files must be
// byte-identical.
//
// `generate` writes the committed vector files; the same KIND always gives
// the same file (std::mt19937 with a fixed seed, reduced with %, which is
// the same on every standard library).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "rt/dda.h"
#include "vector_file.h"

namespace {

using lcnc::kAxisCount;
using lcnc::hdl_test::VectorFile;

int expect(const std::string& in_path, const std::string& out_path) {
  VectorFile vf;
  if (!lcnc::hdl_test::read_vector_file(in_path, vf)) return 1;
  const auto axes = static_cast<int>(vf.axes);
  if (axes < 1 || axes > kAxisCount) {
    std::fprintf(stderr, "%s: axes=%d; rt::Dda has %d\n", in_path.c_str(), axes, kAxisCount);
    return 1;
  }
  lcnc::DdaConfig cfg;
  cfg.magnitude_bits = static_cast<std::uint32_t>(vf.mag_width);
  cfg.capacity = static_cast<std::uint32_t>(vf.capacity);
  if (cfg.magnitude_bits < 1 || cfg.magnitude_bits > 16 || cfg.capacity < cfg.max_pulses()) {
    std::fprintf(stderr, "%s: mag_width=%u capacity=%u is not a DDA preset\n", in_path.c_str(),
                 cfg.magnitude_bits, cfg.capacity);
    return 1;
  }

  std::FILE* out = std::fopen(out_path.c_str(), "w");
  if (out == nullptr) {
    std::fprintf(stderr, "%s: cannot write\n", out_path.c_str());
    return 1;
  }
  lcnc::rt::Dda dda(cfg);
  std::array<std::uint32_t, kAxisCount> ref_acc{};
  ref_acc.fill(cfg.capacity / 2);
  lcnc::PulseFrame frame;
  std::vector<std::uint32_t> ref;
  struct Pulse {
    std::uint32_t tick;
    int axis;
    bool negative;
  };
  std::vector<Pulse> pulses;
  std::uint64_t total = 0;
  for (std::size_t p = 0; p < vf.periods.size(); ++p) {
    const auto& period = vf.periods[p];
    std::array<std::int32_t, kAxisCount> steps{};
    for (std::size_t i = 0; i < period.steps.size(); ++i)
      steps[i] = static_cast<std::int32_t>(period.steps[i]);
    dda.run_period(steps, frame);
    pulses.clear();
    for (int a = 0; a < kAxisCount; ++a) {
      const lcnc::AxisPulses& ax = frame.axes[a];
      ref.clear();
      lcnc::rt::Dda::reference_period(cfg.capacity, ref_acc[a],
                                      static_cast<std::uint32_t>(std::abs(steps[a])), ref);
      const bool same = ref.size() == ax.count && std::equal(ref.begin(), ref.end(), ax.ticks);
      if (!same || dda.accumulator() != ref_acc[a]) {
        std::fprintf(stderr,
                     "%s:%d: axis %d: rt::Dda::run_period and Dda::reference_period disagree "
                     "(%u vs %zu pulses) — a bug in the C++ DDA\n",
                     in_path.c_str(), period.line, a, ax.count, ref.size());
        std::fclose(out);
        return 2;
      }
      if (a >= axes) continue;
      for (std::uint32_t j = 0; j < ax.count; ++j) pulses.push_back({ax.ticks[j], a, ax.negative});
    }
    std::stable_sort(pulses.begin(), pulses.end(),
                     [](const Pulse& x, const Pulse& y) { return x.tick < y.tick; });
    std::fprintf(out, "P %zu %lld\n", p, static_cast<long long>(period.divider));
    for (const Pulse& q : pulses)
      std::fprintf(out, "%zu %u %d %c\n", p, q.tick, q.axis, q.negative ? '-' : '+');
    total += pulses.size();
  }
  if (std::fclose(out) != 0) {
    std::fprintf(stderr, "%s: write failed\n", out_path.c_str());
    return 1;
  }
  std::printf("%s: %zu periods, %llu pulses, N = %u, %u bits, %d axes\n", out_path.c_str(), vf.periods.size(),
              static_cast<unsigned long long>(total), cfg.capacity, cfg.magnitude_bits, axes);
  return 0;
}

bool read_lines(const std::string& path, std::vector<std::string>& lines) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "%s: cannot read\n", path.c_str());
    return false;
  }
  std::string s;
  while (std::getline(in, s)) lines.push_back(s);
  return true;
}

int compare(const std::string& expected_path, const std::string& actual_path) {
  std::vector<std::string> exp, act;
  if (!read_lines(expected_path, exp) || !read_lines(actual_path, act)) return 1;
  constexpr int kShown = 10;
  std::size_t differ = 0;
  std::string period_line = "(before the first period)";
  const std::size_t n = std::max(exp.size(), act.size());
  for (std::size_t i = 0; i < n; ++i) {
    const std::string* e = i < exp.size() ? &exp[i] : nullptr;
    const std::string* a = i < act.size() ? &act[i] : nullptr;
    if (e != nullptr && e->rfind("P ", 0) == 0) period_line = *e;
    if (e != nullptr && a != nullptr && *e == *a) continue;
    if (differ < kShown) {
      std::fprintf(stderr, "line %zu (in %s): expected '%s', actual '%s'\n", i + 1, period_line.c_str(),
                   e != nullptr ? e->c_str() : "<end of file>", a != nullptr ? a->c_str() : "<end of file>");
    }
    ++differ;
  }
  if (differ > 0) {
    std::fprintf(stderr,
                 "MISMATCH: %zu of %zu lines differ between %s (expected, C++) and %s (actual, "
                 "VHDL); lines are 'P period divider' or 'period tick axis sign'\n",
                 differ, n, expected_path.c_str(), actual_path.c_str());
    return 1;
  }
  std::printf("identical: %zu lines (%s, %s)\n", n, expected_path.c_str(), actual_path.c_str());
  return 0;
}

// --- generate ------------------------------------------------------------------

class VectorWriter {
 public:
  VectorWriter(std::FILE* f, int axes, int mag_width, std::uint32_t seed)
      : f_(f), axes_(axes), max_(static_cast<int>((1u << mag_width) - 1u)), rng_(seed) {}

  int max() const { return max_; }
  int axes() const { return axes_; }
  // uniform in lo … hi
  int uniform(int lo, int hi) {
    return lo + static_cast<int>(rng_() % static_cast<std::uint32_t>(hi - lo + 1));
  }
  // 0, the maximum or anything, either sign
  int random_step(int zero_pct, int max_pct) {
    const int r = uniform(0, 99);
    int n = r < zero_pct ? 0 : (r < zero_pct + max_pct ? max_ : uniform(0, max_));
    return uniform(0, 1) == 1 ? -n : n;
  }
  void period(int divider, const std::vector<int>& steps) {
    std::fprintf(f_, "%d", divider);
    for (int s : steps) std::fprintf(f_, " %d", s);
    std::fputc('\n', f_);
  }
  void same(int count, int divider, int step) {
    for (int k = 0; k < count; ++k) period(divider, std::vector<int>(axes_, step));
  }
  void comment(const char* text) { std::fprintf(f_, "# %s\n", text); }

 private:
  std::FILE* f_;
  int axes_;
  int max_;
  std::mt19937 rng_;
};

// D for feed override K from the 100 % divider: D = round(D100 / K).
int divider_for(int d100, double k) { return static_cast<int>(std::lround(d100 / k)); }

// Segments common to every preset: standstill, full speed both ways, a
// reversal every period, override ramps with increment ramps, random.
void common_segments(VectorWriter& w, int d100, int d_min, int d_max, int random_periods) {
  const int m = w.max();
  const int a = w.axes();
  w.comment("standstill");
  w.same(5, d100, 0);
  w.comment("the largest increment, positive, then negative (a reversal at full speed)");
  w.same(8, d100, m);
  w.same(8, d100, -m);
  w.comment("a reversal every period; axes at max, max-1, half, 1, 0, ...");
  for (int k = 0; k < 10; ++k) {
    std::vector<int> s(a);
    const int mags[] = {m, m - 1, m / 2, 1, 0, (m + 1) / 2};
    for (int i = 0; i < a; ++i) s[i] = (k % 2 == 0 ? 1 : -1) * mags[i % 6];
    w.period(d100, s);
  }
  w.comment("feed override up to the fastest divider while axis 0 ramps 0 -> max, axis 1 max -> 0");
  const int ramp = 16;
  for (int k = 0; k <= ramp; ++k) {
    std::vector<int> s(a, 0);
    s[0] = m * k / ramp;
    if (a > 1) s[1] = -(m * (ramp - k) / ramp);
    if (a > 2) s[2] = m / 2;
    if (a > 3) s[3] = 1;
    // K ramps linearly from 100 % to the override that reaches d_min (docs/design.md §5.5)
    const double k_max = static_cast<double>(d100) / d_min;
    w.period(divider_for(d100, 1.0 + (k_max - 1.0) * k / ramp), s);
  }
  w.comment("feed override down to the slowest divider, random increments");
  for (int k = 0; k <= ramp; ++k) {
    std::vector<int> s(a);
    for (int& v : s) v = w.random_step(10, 10);
    const double k_min = static_cast<double>(d100) / d_max;
    const double k_top = static_cast<double>(d100) / d_min;
    w.period(divider_for(d100, k_top + (k_min - k_top) * k / ramp), s);
  }
  w.comment("random: 10 % zero, 10 % the maximum, random signs; a new divider every 10 periods");
  int d = d100;
  for (int k = 0; k < random_periods; ++k) {
    if (k % 10 == 0) d = w.uniform(d_min, d_max);
    std::vector<int> s(a);
    for (int& v : s) v = w.random_step(10, 10);
    w.period(d, s);
  }
  w.comment("smooth motion: each axis's increment a random walk (steps of +-3)");
  std::vector<int> s(a, 0);
  for (int k = 0; k < random_periods / 2; ++k) {
    for (int& v : s) v = std::clamp(v + w.uniform(-3, 3), -m, m);
    w.period(d100, s);
  }
  w.comment("standstill");
  w.same(3, d100, 0);
}

int generate(const std::string& kind, const std::string& out_path) {
  struct Preset {
    const char* kind;
    const char* about;
    int axes, mag_width, capacity, d100, d_min, d_max;
    int pulse_width, dir_setup, dir_hold;
    const char* software;  // output mode and the software timing of the testbench run
    int random_periods;
    std::uint32_t seed;
  };
  // d_min is the interpolator's min_divider (pulse_width + dir_setup +
  // dir_hold, at least pulse_width + 1) so that no divider here is clamped;
  // the paper's software timing (15 us response, 5 us of port writes) where
  // the shortest period leaves room for it.
  const Preset presets[] = {
      {"seed", "the paper's preset: 4 axes, 4 bits, N = 30, 400 kHz at 50 MHz (D = 125), 75 us", 4, 4, 30,
       125, 80, 250, 40, 20, 20, "response_ns=15000 port_ns=5000", 150, 1},
      {"fast", "the fast preset: 6 axes, 8 bits, N = 255, D >= 9 at 50 MHz: one pulse per tick at n = 255", 6,
       8, 255, 12, 9, 30, 4, 3, 2, "step_dir=true response_ns=15000 port_ns=5000", 60, 2},
      {"default", "the default machine's preset (share/machines/default.toml): 6 axes, 8 bits, N = 300", 6, 8,
       300, 12, 2, 24, 1, 0, 0, "step_dir=true response_ns=2000 port_ns=1000", 60, 3},
      {"odd", "a small odd preset: 3 axes, 3 bits, N = 7 (odd: preset N/2 rounds down)", 3, 3, 7, 4, 2, 9, 1,
       0, 0, "response_ns=0 port_ns=0", 400, 4},
  };
  for (const Preset& p : presets) {
    if (kind != p.kind) continue;
    std::FILE* f = std::fopen(out_path.c_str(), "w");
    if (f == nullptr) {
      std::fprintf(stderr, "%s: cannot write\n", out_path.c_str());
      return 1;
    }
    std::fprintf(f,
                 "# Shared DDA increment vectors, C++ <-> VHDL (tests/vectors/README.md).\n"
                 "# %s.\n"
                 "# Written by: build/tests/hdl/dda_vectors generate %s tests/vectors/%s.inc\n"
                 "# One period per line: clock divider D, then the signed increment per axis.\n",
                 p.about, p.kind, p.kind);
    std::fprintf(f,
                 "#! axes=%d mag_width=%d capacity=%d reset_divider=%d min_divider=%d "
                 "pulse_width=%d dir_setup=%d dir_hold=%d %s\n",
                 p.axes, p.mag_width, p.capacity, p.d100, p.d_min, p.pulse_width, p.dir_setup, p.dir_hold,
                 p.software);
    VectorWriter w(f, p.axes, p.mag_width, p.seed);
    common_segments(w, p.d100, p.d_min, p.d_max, p.random_periods);
    if (std::fclose(f) != 0) return 1;
    return 0;
  }
  std::fprintf(stderr, "generate: unknown kind '%s' (seed, fast, default, odd)\n", kind.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::strcmp(argv[1], "expect") == 0) return expect(argv[2], argv[3]);
  if (argc == 4 && std::strcmp(argv[1], "compare") == 0) return compare(argv[2], argv[3]);
  if (argc == 4 && std::strcmp(argv[1], "generate") == 0) return generate(argv[2], argv[3]);
  std::fprintf(stderr,
               "usage: dda_vectors expect VECTORS.inc EXPECTED\n"
               "       dda_vectors compare EXPECTED ACTUAL\n"
               "       dda_vectors generate seed|fast|default|odd VECTORS.inc\n");
  return 2;
}
