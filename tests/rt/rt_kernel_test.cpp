#include "rt/rt_kernel.h"

#include <gtest/gtest.h>

#include <dlfcn.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <ucontext.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <mutex>
#include <new>
#include <random>
#include <thread>
#include <vector>

#include "drivers/sim_machine.h"

#include "support/rt_rig.h"
#include "support/rt_watch.h"

namespace lcnc::rt {
namespace {

using test::drain_log;

// The random walks stay well inside the soft limits.
MachineConfig machine() { return test::rt_machine(-1000.0, 1000.0); }

// The rig with the rings the test's to read.
struct Rig : test::KernelRig {
  Rig() : KernelRig({}, machine()) {}
};

// Fills the buffer with random increments; returns their per-axis sum.
std::array<std::int64_t, kAxisCount> fill(PositionBuffer& buf, std::size_t n, std::uint32_t seed,
                                          float k_plan = 1.0f) {
  std::mt19937 rng(seed);
  std::array<std::int64_t, kAxisCount> sum{};
  for (std::size_t k = 0; k < n; ++k) {
    PeriodIncrement inc;
    for (int a = 0; a < 3; ++a) {
      inc.steps[a] = static_cast<std::int32_t>(rng() % 101) - 50;
      sum[a] += inc.steps[a];
    }
    inc.power_pct = 50.0f;
    inc.k_plan = k_plan;
    inc.segment = static_cast<std::uint32_t>(k);
    inc.end_of_program = k + 1 == n;
    EXPECT_TRUE(buf.try_push(inc));
  }
  return sum;
}

// Changes the feed override from another thread until the kernel finishes:
// a fixed opening (a full hold and resume, a ramp to 150 %), then random
// targets from a fixed seed — holds, the slowest (below K_min: raised to
// it), 150 %, anything between — each for 2–25 ms.
class OverrideChanger {
 public:
  OverrideChanger(RtKernel& kernel, std::uint32_t seed)
      : thread_([this, &kernel, seed] { run(kernel, seed); }) {}
  ~OverrideChanger() {
    done_ = true;
    thread_.join();
  }
  OverrideChanger(const OverrideChanger&) = delete;
  OverrideChanger& operator=(const OverrideChanger&) = delete;
  [[nodiscard]] int changes() const { return changes_.load(); }

 private:
  void run(RtKernel& kernel, std::uint32_t seed) {
    std::mt19937 rng(seed);
    const double opening[][2] = {{1.0, 5}, {0.0, 40}, {1.0, 10}, {1.5, 30}, {0.4, 10}};
    std::size_t n = 0;
    while (!done_ && !kernel.finished()) {
      double k = 0.0, ms = 0.0;
      if (n < std::size(opening)) {
        k = opening[n][0];
        ms = opening[n][1];
      } else {
        const double choices[] = {0.0, 1e-3, 0.3, 1.0, 1.5, std::uniform_real_distribution<>(0, 1.5)(rng)};
        k = choices[rng() % std::size(choices)];
        ms = 2 + static_cast<double>(rng() % 24);
      }
      ++n;
      kernel.set_feed_override(k);
      changes_.fetch_add(1);
      const auto until =
          std::chrono::steady_clock::now() + std::chrono::microseconds(static_cast<int>(ms * 1000));
      while (!done_ && !kernel.finished() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }

  std::atomic<bool> done_{false};
  std::atomic<int> changes_{0};
  std::thread thread_;
};

TEST(RtKernel, ExecutesEveryEntryAndSumOfPulsesEqualsCommandedSteps) {
  Rig r;
  const auto sum = fill(*r.buffer, 4000, 1);
  r.kernel->start(RtOptions{false, 0, {}, {}});
  r.kernel->join();
  EXPECT_EQ(r.kernel->motion_periods(), 4000u);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(r.sim->position_steps(a), sum[a]);
    EXPECT_EQ(r.kernel->position_steps(a), sum[a]);
  }
  EXPECT_EQ(r.sim->bad_frames(), 0u);
  // every period either woke from its sleep or was already due (catching up)
  EXPECT_EQ(r.kernel->latency().total() + r.kernel->catch_up_periods(), r.kernel->periods());
  EXPECT_GT(r.kernel->latency().total(), r.kernel->periods() / 2);
  // every period left a trace record, in order
  TraceRecord rec;
  std::uint64_t expect = 0;
  while (r.trace->try_pop(rec)) EXPECT_EQ(rec.period, expect++);
  EXPECT_EQ(expect, r.kernel->periods());
}

// Two kernels given one epoch (two axis groups on one time base): neither
// runs a period before it, and though started 60 ms apart they run their
// periods together and end together.
TEST(RtKernel, KernelsGivenOneEpochStartOnItTogether) {
  Rig a, b;
  (void)fill(*a.buffer, 2000, 1);
  (void)fill(*b.buffer, 2000, 1);
  const auto mono_ns = [] {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
  };
  RtOptions o{false, 0, {}, {}};
  o.epoch_ns = mono_ns() + 200'000'000;  // 200 ms from now
  a.kernel->start(o);
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  b.kernel->start(o);
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  EXPECT_EQ(a.kernel->periods(), 0u);  // not before the epoch
  EXPECT_EQ(b.kernel->periods(), 0u);
  std::int64_t a_end = 0, b_end = 0;
  while (a_end == 0 || b_end == 0) {
    if (a_end == 0 && a.kernel->finished()) a_end = mono_ns();
    if (b_end == 0 && b.kernel->finished()) b_end = mono_ns();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  a.kernel->join();
  b.kernel->join();
  // the first period runs at the epoch, the 2000th 1999 periods after it:
  // neither ends before that
  EXPECT_GE(std::min(a_end, b_end) - o.epoch_ns, 1999 * 75'000);
  EXPECT_LT(std::abs(a_end - b_end), 30'000'000);  // not 60 ms apart
}

TEST(RtKernel, EmptyBufferWhileRunningIsAnUnderrunThatHoldsPosition) {
  Rig r;
  PeriodIncrement inc;
  inc.steps[0] = 10;
  ASSERT_TRUE(r.buffer->try_push(inc));
  r.kernel->start(RtOptions{false, 0, {}, {}});
  // let the buffer run dry for a while, then finish the job
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  PeriodIncrement last;
  last.steps[0] = 5;
  last.end_of_program = true;
  while (!r.buffer->try_push(last)) {
  }
  r.kernel->join();
  EXPECT_GT(r.kernel->underruns(), 10u);
  EXPECT_EQ(r.sim->position_steps(0), 15);  // held, no jump, nothing lost
  TraceRecord rec;
  std::int64_t prev = 0;
  while (r.trace->try_pop(rec)) {
    if (rec.underrun) {
      EXPECT_EQ(rec.pos_steps[0], prev);  // position held
    }
    prev = rec.pos_steps[0];
  }
}

TEST(RtKernel, UnderrunsAndHoldsAreLoggedThroughTheRing) {
  Rig r;
  PeriodIncrement inc;
  inc.steps[0] = 3;
  ASSERT_TRUE(r.buffer->try_push(inc));
  r.kernel->start(RtOptions{false, 0, {}, {}});
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // runs dry
  inc.end_of_program = true;
  while (!r.buffer->try_push(inc)) {
  }
  r.kernel->join();
  const auto log = drain_log(*r.log);
  std::size_t begins = 0, ends = 0;
  std::int64_t lasted = 0;
  for (const RtLogRecord& rec : log) {
    if (rec.code == RtLogCode::UnderrunBegin) ++begins;
    if (rec.code == RtLogCode::UnderrunEnd) {
      ++ends;
      lasted += rec.value;
    }
  }
  EXPECT_EQ(begins, 1u);
  EXPECT_EQ(ends, 1u);
  EXPECT_EQ(static_cast<std::uint64_t>(lasted), r.kernel->underruns());  // the whole streak
  EXPECT_EQ(r.kernel->log_drops(), 0u);
  EXPECT_STREQ(rt_log_text(RtLogCode::UnderrunBegin), "position buffer underrun: holding position");
}

TEST(RtKernel, FeedHoldIsLoggedWhereItBeginsAndEnds) {
  Rig r;
  fill(*r.buffer, 500, 9);
  r.kernel->set_feed_override(0.0);  // held from the start
  r.kernel->start(RtOptions{false, 0, {}, {}});
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  r.kernel->set_feed_override(1.0);
  r.kernel->join();
  const auto log = drain_log(*r.log);
  ASSERT_GE(log.size(), 2u);
  EXPECT_EQ(log[0].code, RtLogCode::HoldBegin);
  EXPECT_EQ(log[0].period, 0u);
  bool ended = false;
  for (const RtLogRecord& rec : log) ended = ended || rec.code == RtLogCode::HoldEnd;
  EXPECT_TRUE(ended);
}

TEST(RtKernel, StopEndsTheLoopWithinAFewPeriods) {
  Rig r;
  r.kernel->start(RtOptions{false, 0, {}, {}});  // empty buffer: holds forever
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  r.kernel->shutdown();
  r.kernel->join();
  EXPECT_TRUE(r.kernel->finished());
  EXPECT_EQ(r.sim->position_steps(0), 0);
}

std::vector<TraceRecord> drain(TraceRing& trace) {
  std::vector<TraceRecord> out;
  TraceRecord rec;
  while (trace.try_pop(rec)) out.push_back(rec);
  return out;
}

// The override's invariants, period by period from the trace: held exactly
// when K < K_min (position held, laser off, not an underrun); each period
// lasts T/K (T while held) and t is the machine time at its end; K never
// changes by more than ρ times the length of the period before — a linear
// ramp, never a jump. Returns the number of periods in which K was ramping.
int check_override_trace(const std::vector<TraceRecord>& recs, const RtKernel& kernel,
                         std::uint32_t period_ns) {
  const FeedOverrideRamp& ramp = kernel.override_ramp();
  const double T = period_ns;
  std::int64_t t_prev = 0;
  double len_prev = T;
  double k_prev = recs.empty() ? 1.0 : recs.front().feed_override;
  std::array<std::int64_t, kAxisCount> pos_prev{};
  double sum_len = 0.0;
  int ramping = 0;
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const TraceRecord& r = recs[i];
    EXPECT_EQ(r.period, i);
    const double k = r.feed_override;
    EXPECT_EQ(r.held, k < ramp.k_min()) << "period " << i << " K " << k;
    const double len = r.held ? T : T / k;
    sum_len += len;
    EXPECT_NEAR(static_cast<double>(r.t_ns - t_prev), len, 1.0) << "period " << i << " K " << k;
    const double dk = std::abs(k - k_prev);
    EXPECT_LE(dk, ramp.rate_per_s() * len_prev * 1e-9 * (1 + 1e-9)) << "period " << i;
    if (dk > 0.0) ++ramping;
    if (r.held) {
      EXPECT_EQ(r.pos_steps, pos_prev) << "period " << i;
      EXPECT_EQ(r.power_pct, 0.0f) << "period " << i;
      EXPECT_FALSE(r.underrun) << "period " << i;
    }
    t_prev = r.t_ns;
    len_prev = len;
    k_prev = k;
    pos_prev = r.pos_steps;
    if (::testing::Test::HasFailure()) break;  // one report, not thousands
  }
  if (!recs.empty()) {
    EXPECT_EQ(kernel.machine_time_ns(), recs.back().t_ns);
  }
  EXPECT_NEAR(static_cast<double>(kernel.machine_time_ns()), sum_len, 1.0);
  return ramping;
}

TEST(RtKernel, RandomOverrideChangesAndHoldsLoseNoStep) {
  Rig r;
  const auto sum = fill(*r.buffer, 8000, 21);
  r.kernel->start(RtOptions{false, 0, {}, {}});
  {
    OverrideChanger changer(*r.kernel, 22);
    r.kernel->join();
    EXPECT_GT(changer.changes(), 10);
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(r.sim->position_steps(a), sum[a]) << "axis " << a;
    EXPECT_EQ(r.kernel->position_steps(a), sum[a]) << "axis " << a;
  }
  EXPECT_EQ(r.kernel->motion_periods(), 8000u);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  EXPECT_EQ(r.sim->bad_frames(), 0u);
  EXPECT_EQ(r.kernel->trace_drops(), 0u);
  EXPECT_EQ(r.kernel->periods(), r.kernel->motion_periods() + r.kernel->held_periods());
  const std::vector<TraceRecord> recs = drain(*r.trace);
  ASSERT_EQ(recs.size(), r.kernel->periods());
  const int ramping = check_override_trace(recs, *r.kernel, r.m.period_ns);
  EXPECT_GT(ramping, 100);
  // the opening's hold and its 150 % were reached
  std::size_t held = 0;
  double k_top = 0.0;
  for (const TraceRecord& rec : recs) {
    held += rec.held;
    k_top = std::max(k_top, rec.feed_override);
  }
  EXPECT_EQ(held, r.kernel->held_periods());
  EXPECT_GT(held, 100u);
  EXPECT_EQ(k_top, 1.0);  // 150 % over entries planned at 100 %: as planned, no faster
  // the laser is on exactly in the moving periods (every entry has power)
  const double moving_ns =
      static_cast<double>(r.kernel->machine_time_ns()) - static_cast<double>(held) * r.m.period_ns;
  EXPECT_NEAR(static_cast<double>(r.kernel->laser_on_ns()), moving_ns, 2.0);
}

TEST(RtKernel, FeedHoldAtStartPopsNothingThenResumesWithARamp) {
  Rig r;
  const auto sum = fill(*r.buffer, 2000, 31);
  r.kernel->set_feed_override(0.0);  // before start: the run begins held
  r.kernel->start(RtOptions{false, 0, {}, {}});
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(r.kernel->motion_periods(), 0u);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  EXPECT_GT(r.kernel->held_periods(), 20u);
  EXPECT_EQ(r.buffer->size(), 2000u);
  EXPECT_EQ(r.sim->position_steps(0), 0);
  EXPECT_EQ(r.sim->power_pct(), 0.0f);
  EXPECT_EQ(r.kernel->feed_override(), 0.0);
  r.kernel->set_feed_override(1.0);
  r.kernel->join();
  for (int a = 0; a < 3; ++a) EXPECT_EQ(r.sim->position_steps(a), sum[a]);
  EXPECT_EQ(r.kernel->motion_periods(), 2000u);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  const std::vector<TraceRecord> recs = drain(*r.trace);
  check_override_trace(recs, *r.kernel, r.m.period_ns);
  // held first, then K rises monotonically from K_min to 1: no jump to 100 %
  std::size_t i = 0;
  while (i < recs.size() && recs[i].held) ++i;
  ASSERT_LT(i, recs.size());
  EXPECT_GE(i, 20u);
  const FeedOverrideRamp& ramp = r.kernel->override_ramp();
  EXPECT_GE(recs[i].feed_override, ramp.k_min());
  EXPECT_LT(recs[i].feed_override, ramp.k_min() + ramp.rate_per_s() * r.m.period_s());
  for (++i; i < recs.size() && recs[i].feed_override < 1.0; ++i)
    ASSERT_GT(recs[i].feed_override, recs[i - 1].feed_override);
  ASSERT_LT(i, recs.size());
  EXPECT_EQ(recs[i].feed_override, 1.0);
}

TEST(RtKernel, HoldMidRunDeceleratesHoldsAndResumesFromTheHeldPosition) {
  Rig r;
  const auto sum = fill(*r.buffer, 8000, 41);
  r.kernel->start(RtOptions{false, 0, {}, {}});
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  r.kernel->set_feed_override(0.0);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (r.kernel->feed_override() > 0.0 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(r.kernel->feed_override(), 0.0);
  ASSERT_FALSE(r.kernel->finished());
  const std::uint64_t popped = r.kernel->motion_periods();
  const std::size_t left = r.buffer->size();
  const std::int64_t x = r.sim->position_steps(0);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(r.kernel->motion_periods(), popped);  // nothing popped while held
  EXPECT_EQ(r.buffer->size(), left);
  EXPECT_EQ(r.sim->position_steps(0), x);
  EXPECT_EQ(r.sim->power_pct(), 0.0f);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  r.kernel->set_feed_override(1.0);
  r.kernel->join();
  for (int a = 0; a < 3; ++a) EXPECT_EQ(r.sim->position_steps(a), sum[a]);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  const std::vector<TraceRecord> recs = drain(*r.trace);
  check_override_trace(recs, *r.kernel, r.m.period_ns);
  // the way down: from 1 to K_min in steps, the last moving period at K_min
  std::size_t first_held = 0;
  while (first_held < recs.size() && !recs[first_held].held) ++first_held;
  ASSERT_LT(first_held, recs.size());
  EXPECT_EQ(recs[first_held - 1].feed_override, r.kernel->override_ramp().k_min());
  std::size_t down = first_held - 1;
  while (down > 0 && recs[down - 1].feed_override < 1.0) --down;
  EXPECT_GT(first_held - down, 10u) << "a ramp, not a step";
}

// A dwell (a pierce) lasts its programmed time whatever the override, and M4
// power follows the actual speed: K times the planned power, up to S. The
// moves are planned at 150 % (their M4 power up to 1.5·S), run at 120 %:
// K = 1.2/1.5 = 0.8.
TEST(RtKernel, OverrideLeavesDwellsAloneAndScalesDynamicPower) {
  Rig r;
  const std::size_t n_move = 400, n_dwell = 400;
  for (std::size_t k = 0; k < n_move + n_dwell; ++k) {
    PeriodIncrement inc;
    if (k < n_move) {
      inc.steps[0] = 10;
      inc.power_pct = k < n_move / 2 ? 40.0f : 75.0f;  // M4 at 80 / 150 % of S
      inc.power_cap_pct = 50.0f;                       // S = 50 %
      inc.k_plan = 1.5f;
    } else {
      inc.kind = MotionKind::Dwell;
      inc.power_pct = 30.0f;  // M3 percussion: not scaled
    }
    inc.end_of_program = k + 1 == n_move + n_dwell;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.kernel->set_feed_override(1.2);
  r.kernel->start(RtOptions{false, 0, {}, {}});
  r.kernel->join();
  const std::vector<TraceRecord> recs = drain(*r.trace);
  ASSERT_EQ(recs.size(), n_move + n_dwell);
  const double T = r.m.period_ns;
  std::int64_t prev_t = 0;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    const double len = static_cast<double>(recs[k].t_ns - prev_t);
    prev_t = recs[k].t_ns;
    if (k < n_move) {
      EXPECT_NEAR(len, T / 0.8, 1.0) << k;
      // 40 % · 0.8 = 32 %; 75 % · 0.8 = 60 % → capped at S = 50 %
      EXPECT_FLOAT_EQ(recs[k].power_pct, k < n_move / 2 ? 32.0f : 50.0f) << k;
    } else {
      EXPECT_NEAR(len, T, 1.0) << k;  // the dwell keeps its time
      EXPECT_FLOAT_EQ(recs[k].power_pct, 30.0f) << k;
    }
  }
  EXPECT_NEAR(static_cast<double>(r.kernel->machine_time_ns()), n_move * T / 0.8 + n_dwell * T, 2.0);
}

// A sink that keeps each period's outputs (room reserved before the run:
// the RT thread never allocates).
class OutputsSink final : public PulseSink {
 public:
  explicit OutputsSink(std::size_t n) {
    words.reserve(n);
    analog.reserve(n);
  }
  void send(const PulseFrame& f) noexcept override {
    if (words.size() == words.capacity()) return;
    words.push_back(f.outputs);
    analog.push_back(f.analog[1]);
  }
  std::vector<std::uint16_t> words;
  std::vector<float> analog;
};

// The program's outputs (M62 … M68, the gas) switch with the entry that
// carries them: in its own period, not one early or late.
TEST(RtKernel, OutputsSwitchInThePeriodOfTheEntryThatCarriesThem) {
  const MachineConfig m = machine();
  auto buffer = std::make_unique<PositionBuffer>();
  const std::size_t n = 300;
  for (std::size_t k = 0; k < n; ++k) {
    PeriodIncrement inc;
    inc.steps[0] = 5;
    if (k >= 100 && k < 200) {
      inc.outputs = static_cast<std::uint16_t>(0b101u | kOutputMist);
      inc.analog[1] = 2.5f;
    }
    inc.end_of_program = k + 1 == n;
    ASSERT_TRUE(buffer->try_push(inc));
  }
  OutputsSink sink(n + 16);
  RtKernel kernel(m, *buffer, sink, nullptr, {});
  kernel.start(RtOptions{false, 0, {}, {}});
  kernel.join();
  ASSERT_GE(sink.words.size(), n);
  for (std::size_t k = 0; k < n; ++k) {
    const bool on = k >= 100 && k < 200;
    EXPECT_EQ(sink.words[k], on ? (0b101u | kOutputMist) : 0u) << "period " << k;
    EXPECT_EQ(sink.analog[k], on ? 2.5f : 0.0f) << "period " << k;
  }
}

// Each entry runs at K = min(1, override / the override it is planned at):
// 150 % over entries planned at 100 % runs them as planned (the planner, not
// the RT, makes a raise), 120 % over entries planned at 150 % at K = 0.8.
TEST(RtKernel, ConstantOverrideRunsEveryEntryInTOverK) {
  struct Case {
    double override_k;
    float k_plan;
    double k;
  };
  for (const Case c : {Case{1.5, 1.0f, 1.0}, Case{1.2, 1.5f, 0.8}, Case{0.5, 1.0f, 0.5}}) {
    Rig r;
    const double k = c.k;
    const std::size_t n = 2000;
    const auto sum = fill(*r.buffer, n, 51, c.k_plan);
    r.kernel->set_feed_override(c.override_k);  // before start: no ramp
    const auto t0 = std::chrono::steady_clock::now();
    r.kernel->start(RtOptions{false, 0, {}, {}});
    r.kernel->join();
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (int a = 0; a < 3; ++a) EXPECT_EQ(r.sim->position_steps(a), sum[a]);
    EXPECT_NEAR(r.kernel->feed_override(), k * c.k_plan, 1e-6);  // what the machine runs at
    EXPECT_EQ(r.kernel->held_periods(), 0u);
    const double machine_s = static_cast<double>(n) * r.m.period_s() / k;
    EXPECT_NEAR(static_cast<double>(r.kernel->machine_time_ns()), machine_s * 1e9, 1.0) << k;
    const std::vector<TraceRecord> recs = drain(*r.trace);
    ASSERT_EQ(recs.size(), n);
    for (const TraceRecord& rec : recs) ASSERT_NEAR(rec.feed_override, k, 1e-9);
    EXPECT_EQ(check_override_trace(recs, *r.kernel, r.m.period_ns), 0);
    // wall time follows machine time (absolute deadlines): loosely, as the
    // machine is shared — but well apart from the n·T the run takes at 100 %
    EXPECT_GE(wall_s, machine_s - r.m.period_s() / k) << k;
    EXPECT_LT(wall_s, machine_s + 0.15) << k;
  }
}

// The RT loop allocates nothing: the RT thread's own allocations counted over
// the whole loop, from the enter hook to the exit hook.
TEST(RtKernel, LoopNeverAllocates) {
  Rig r;
  fill(*r.buffer, 3000, 2);
  std::atomic<std::uint64_t> at_enter{0}, at_exit{0};
  RtOptions opt{false, 0,
                [&] {
                  at_enter = g_allocations.load();
                  t_count_allocations = true;
                },
                [&] {
                  t_count_allocations = false;
                  at_exit = g_allocations.load();
                }};
  r.kernel->start(opt);
  {
    OverrideChanger changer(*r.kernel, 12);  // ramps and holds while the loop runs
    r.kernel->join();
    EXPECT_GT(changer.changes(), 3);
  }
  EXPECT_GT(r.kernel->held_periods(), 0u);
  EXPECT_EQ(r.kernel->motion_periods(), 3000u);
  EXPECT_EQ(at_exit.load() - at_enter.load(), 0u);
}

// A million periods of a daemon-style kernel (1 µs periods: the loop runs as
// fast as it can, every deadline already past) with a streaming producer,
// feed-override changes, a hold, a stop and a second job: no allocation and
// no lock on the RT thread, from the first period to the last.
TEST(RtKernel, MillionPeriodsWithoutAllocationOrLock) {
  MachineConfig m = machine();
  m.period_ns = 1'000;
  std::unique_ptr<PositionBuffer> buffer = std::make_unique<PositionBuffer>();
  std::array<std::int64_t, kAxisCount> start{};
  drivers::SimMachine sim{start};
  std::unique_ptr<RtLogRing> log = std::make_unique<RtLogRing>();
  std::unique_ptr<TraceRing> trace = std::make_unique<TraceRing>();
  std::unique_ptr<shm::ShmBlock> block = std::make_unique<shm::ShmBlock>();
  RtKernel kernel{m, *buffer, sim, trace.get(), start};
  kernel.set_log(log.get());
  kernel.set_status(&block->status);
  kernel.set_estop_word(&block->estop.requests);  // polled every period
  std::atomic<std::uint64_t> allocs_enter{0}, allocs_exit{0}, locks_enter{0}, locks_exit{0};
  RtOptions opt{false, 0,
                [&] {
                  allocs_enter = g_allocations.load();
                  locks_enter = g_locks.load();
                  t_count_allocations = true;
                },
                [&] {
                  t_count_allocations = false;
                  allocs_exit = g_allocations.load();
                  locks_exit = g_locks.load();
                }};
  opt.exit_at_end = false;
  opt.start_running = false;
  kernel.stream_begin();
  kernel.start(opt);
  std::atomic<bool> done{false};
  std::thread drainer([&] {  // the normal threads that read the rings
    TraceRecord t;
    RtLogRecord l;
    while (!done) {
      while (trace->try_pop(t)) {
      }
      while (log->try_pop(l)) {
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  std::mt19937 rng(5);
  auto push_job = [&](std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      PeriodIncrement inc;
      for (int a = 0; a < 3; ++a) inc.steps[a] = static_cast<std::int32_t>(rng() % 21) - 10;
      inc.power_pct = 40.0f;
      inc.end_of_program = k + 1 == n;
      while (!buffer->try_push(inc)) std::this_thread::yield();
    }
  };
  kernel.command({RtCommandType::StartJob, 0, 0.0});
  std::thread producer([&] { push_job(600'000); });
  for (double k : {1.5, 0.3, 1.0}) {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    kernel.set_feed_override(k);
  }
  kernel.command({RtCommandType::Hold, 0, 0.0});
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kernel.command({RtCommandType::Resume, 0, 0.0});
  producer.join();
  kernel.stream_end();
  while (kernel.jobs_ended() < 1) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  while (kernel.state() != MachineState::Idle) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  kernel.command({RtCommandType::Jog, 0, 2.0});
  while (kernel.periods() < 1'000'000) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kernel.shutdown();
  kernel.join();
  done = true;
  drainer.join();
  EXPECT_GE(kernel.periods(), 1'000'000u);
  EXPECT_EQ(kernel.motion_periods(), 600'000u);
  // 1 µs periods are mostly due before the last one ends: catch-up periods,
  // started at once, not counted as wake-ups
  EXPECT_GT(kernel.catch_up_periods(), 500'000u);
  EXPECT_EQ(kernel.latency().total() + kernel.catch_up_periods(), kernel.periods());
  EXPECT_EQ(allocs_exit.load() - allocs_enter.load(), 0u);
  EXPECT_EQ(locks_exit.load() - locks_enter.load(), 0u);
}

// The lock counter works: a mutex locked on a watched thread is seen.
TEST(RtKernel, LockCounterSeesLocks) {
  const std::uint64_t before = g_locks.load();
  std::thread([] {
    std::mutex mu;
    t_count_allocations = true;
    mu.lock();
    mu.unlock();
    t_count_allocations = false;
  }).join();
  EXPECT_GE(g_locks.load() - before, 1u);
}

// The counter works: an allocation on a counting thread is seen.
TEST(RtKernel, AllocationCounterSeesAllocations) {
  const std::uint64_t before = g_allocations.load();
  std::thread([] {
    t_count_allocations = true;
    auto p = std::make_unique<int>(7);
    t_count_allocations = false;
    EXPECT_EQ(*p, 7);
  }).join();
  EXPECT_EQ(g_allocations.load() - before, 1u);
}

// The RT loop makes no syscall but its clock sleep: a seccomp filter on the RT
// thread traps every other syscall from the first period to the last, and the
// SIGSYS handler records it. (Not under the sanitizers, whose runtimes make
// syscalls of their own.)
#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
std::atomic<int> g_bad_syscalls{0};
std::atomic<long> g_first_bad_syscall{-1};

void on_sigsys(int, siginfo_t* info, void* ctx) {
  g_bad_syscalls.fetch_add(1);
  long expected = -1;
  g_first_bad_syscall.compare_exchange_strong(expected, info->si_syscall);
  // the trapped syscall did not run; make it return -ENOSYS
  static_cast<ucontext_t*>(ctx)->uc_mcontext.gregs[REG_RAX] = -ENOSYS;
}

void install_syscall_filter() {
  // Allowed: the clock sleep and clock read; the return from the SIGSYS
  // handler itself; then what the thread's own exit
  // needs (after the loop): exit, madvise (stack release), rt_sigprocmask, munmap.
  sock_filter code[] = {
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, nr)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_clock_nanosleep, 7, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_clock_gettime, 6, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_rt_sigreturn, 5, 0),  // leaving the SIGSYS handler
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_exit, 4, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_madvise, 3, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_rt_sigprocmask, 2, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_munmap, 1, 0),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_TRAP),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
  };
  sock_fprog prog{static_cast<unsigned short>(sizeof code / sizeof code[0]), code};
  prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0);
  prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog);
}

TEST(RtKernel, LoopMakesNoSyscallButTheClockSleep) {
  struct sigaction sa {};
  sa.sa_sigaction = on_sigsys;
  sa.sa_flags = SA_SIGINFO;
  ASSERT_EQ(sigaction(SIGSYS, &sa, nullptr), 0);
  Rig r;
  fill(*r.buffer, 3000, 3);
  std::atomic<std::uint32_t> estop_word{0};  // polled every period: an atomic load, no syscall
  r.kernel->set_estop_word(&estop_word);
  std::atomic<bool> filtered{false};
  std::atomic<int> bad_at_exit{-1};
  RtOptions opt{false, 0,
                [&] {
                  install_syscall_filter();
                  filtered = true;
                },
                [&] { bad_at_exit = g_bad_syscalls.load(); }};
  r.kernel->start(opt);
  {
    OverrideChanger changer(*r.kernel, 13);  // ramps and holds while the loop runs
    r.kernel->join();
    EXPECT_GT(changer.changes(), 3);
  }
  EXPECT_GT(r.kernel->held_periods(), 0u);
  ASSERT_TRUE(filtered.load());
  EXPECT_EQ(r.kernel->motion_periods(), 3000u);
  EXPECT_EQ(bad_at_exit.load(), 0) << "first forbidden syscall: " << g_first_bad_syscall.load();
  signal(SIGSYS, SIG_DFL);
}
#endif

}  // namespace
}  // namespace lcnc::rt
