// The job pipeline lasercnc run and lasercncd share (app/planner_feed.h):
// the planner thread streaming into the RT kernel on the simulated machine,
// with real threads — random programs under random feed-override changes,
// and a job stopped short of a soft limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/planner_feed.h"
#include "app/run_job.h"
#include "drivers/sim_machine.h"
#include "plan/motion_check.h"
#include "rt/rt_kernel.h"
#include "rt/rt_log.h"

namespace lcnc::app {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

MachineConfig machine() {
  RunOptions o;
  Result<MachineConfig> m = load_machine(o);
  EXPECT_TRUE(static_cast<bool>(m));
  return *m;
}

fs::path write_job_pipeline(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("lcnc_pipeline_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

// A random program within X 10–90, Y 10–90: lines and arcs, feeds, laser on
// and off, G64 P and G61 stretches.
std::string random_program(std::uint32_t seed, int moves = 25) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(10.0, 40.0), feed(6000.0, 18000.0), bow(-0.8, 0.8);
  std::string p = "G21 G90 G17\nG0 X25 Y25 Z5\nM3 S70\n";
  double x = 25, y = 25;
  char buf[160];
  for (int i = 0; i < moves; ++i) {
    const int kind = static_cast<int>(rng() % 10);
    if (kind == 0) p += (rng() % 2) ? "G61\n" : "G64 P0.01\n";
    if (kind == 1) p += (rng() % 2) ? "M5\n" : "M4 S50\n";
    const double nx = xy(rng), ny = xy(rng);
    if (kind < 7) {
      std::snprintf(buf, sizeof buf, "G1 X%.3f Y%.3f F%.0f\n", nx, ny, feed(rng));
    } else {
      // an arc: the centre on the chord's bisector, so both radii are equal
      const double t = bow(rng);
      const double ccx = (x + nx) / 2 - t * (ny - y), ccy = (y + ny) / 2 + t * (nx - x);
      std::snprintf(buf, sizeof buf, "G%d X%.4f Y%.4f I%.4f J%.4f F%.0f\n", rng() % 2 ? 2 : 3, nx, ny,
                    ccx - x, ccy - y, feed(rng));
    }
    p += buf;
    x = nx;
    y = ny;
  }
  p += "M5\nM2\n";
  return p;
}

struct Job {
  MachineConfig m = machine();
  std::array<std::int64_t, kAxisCount> start{};
  std::unique_ptr<rt::PositionBuffer> buffer = std::make_unique<rt::PositionBuffer>();
  std::unique_ptr<drivers::SimMachine> sim;
  std::unique_ptr<rt::RtKernel> kernel;
  std::unique_ptr<PlannerFeed> feed;
  explicit Job(rt::TraceRing* trace = nullptr) {
    sim = std::make_unique<drivers::SimMachine>(start);
    kernel = std::make_unique<rt::RtKernel>(m, *buffer, *sim, trace, start);
    feed = std::make_unique<PlannerFeed>(m, *buffer, *kernel);
  }
  void run(const fs::path& program, rt::RtClock clock = rt::RtClock::Wall) {
    feed->start(program.string(), ReaderOptions{});
    feed->wait_prefilled();
    rt::RtOptions o;
    o.try_realtime = false;
    o.clock = clock;
    kernel->start(o);
  }
};

// Per period, whether X changed speed faster than its acceleration allows
// (steps at 1 µm; a period's length is T/K, or T when held; one step of
// quantization either side). Returns the worst excess, 0 if none.
double worst_accel_excess(const std::vector<rt::TraceRecord>& recs, const MachineConfig& m) {
  const double T = m.period_s();
  const double amax_steps = m.axes[0].max_acceleration * 1000.0;
  double worst = 0.0;
  std::int64_t prev_pos = 0, prev_d = 0;
  double prev_len = T;
  std::uint64_t prev_period = 0;
  int chain = 0;  // consecutive records up to the one before (a dropped record breaks it)
  for (const rt::TraceRecord& r : recs) {
    const bool consecutive = chain > 0 && r.period == prev_period + 1;
    const double len = r.held ? T : T / r.feed_override;
    const std::int64_t d = r.pos_steps[0] - prev_pos;
    if (consecutive && chain >= 2) {
      const double dv = std::abs(static_cast<double>(d) / len - static_cast<double>(prev_d) / prev_len);
      worst = std::max(worst, dv / (0.5 * (len + prev_len)) - (amax_steps + 2.0 / (T * T)));
    }
    chain = consecutive ? chain + 1 : 1;
    prev_period = r.period;
    prev_pos = r.pos_steps[0];
    prev_d = d;
    prev_len = len;
  }
  return worst;
}

TEST(JobPipeline, RandomProgramsUnderRandomOverrideChangesLoseNoStep) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const fs::path prog = write_job_pipeline("random_" + std::to_string(seed) + ".ngc", random_program(seed));
    ASSERT_TRUE(static_cast<bool>(check_program(prog.string(), machine()))) << seed;
    Job job;
    job.run(prog);
    std::mt19937 rng(seed * 77);
    int changes = 0;
    while (!job.kernel->finished()) {
      const double choices[] = {0.0, 0.2, 0.7, 1.0, 1.2, 1.5};
      job.kernel->set_feed_override(choices[rng() % 6]);
      ++changes;
      std::this_thread::sleep_for(std::chrono::milliseconds(5 + rng() % 40));
    }
    job.kernel->join();
    job.feed->join();
    const PlannedJob& planned = job.feed->result();
    ASSERT_FALSE(planned.failed) << planned.error.to_string();
    EXPECT_GT(changes, 3) << seed;
    for (int a = 0; a < kAxisCount; ++a)
      EXPECT_EQ(job.sim->position_steps(a), planned.commanded[a]) << "seed " << seed << " axis " << a;
    EXPECT_EQ(job.kernel->underruns(), 0u) << seed;
    EXPECT_FALSE(job.kernel->fault().active) << seed;
  }
}

// A program that cannot be read on mid-way while the machine moves (here a
// move beyond the travel, run without the check that refuses it before
// anything moves — as when the file changes after it was checked): the
// motion before the bad line is planned to rest like a program's end, so the
// machine stops gradually exactly where the last good line ends, never dead
// and never past it, and the error names the line and the axis.
TEST(JobPipeline, AProgramFailingMidWayStopsAtRestAtItsLastGoodLine) {
  const fs::path prog =
      write_job_pipeline("past_limit.ngc", "G21 G90\nG0 X900 Y100\nM3 S50\nG1 X990 F30000\nG1 X1200\nM2\n");
  const Result<ProgramSummary> checked = check_program(prog.string(), machine());
  ASSERT_FALSE(static_cast<bool>(checked));  // what lasercnc run says before running
  EXPECT_EQ(checked.error().code, ErrorCode::GcodeBeyondTravel);
  std::unique_ptr<rt::TraceRing> trace = std::make_unique<rt::TraceRing>();
  Job job(trace.get());
  job.run(prog);
  std::vector<rt::TraceRecord> recs;
  rt::TraceRecord rec;
  const auto deadline = std::chrono::steady_clock::now() + 60s;  // the job takes ~2 s
  while (!job.kernel->finished()) {
    EXPECT_FALSE(job.feed->stopped_short());  // no stop is needed
    while (trace->try_pop(rec)) recs.push_back(rec);
    if (std::chrono::steady_clock::now() > deadline) {
      job.kernel->shutdown();
      job.kernel->join();
      FAIL() << "the job never ended";
    }
    std::this_thread::sleep_for(1ms);
  }
  job.kernel->join();
  while (trace->try_pop(rec)) recs.push_back(rec);
  job.feed->join();
  const PlannedJob& planned = job.feed->result();
  ASSERT_TRUE(planned.failed);
  EXPECT_EQ(planned.error.code, ErrorCode::GcodeBeyondTravel);
  EXPECT_EQ(planned.error.line, 5u);
  EXPECT_NE(planned.error.message.find('X'), std::string::npos) << planned.error.message;
  EXPECT_FALSE(job.kernel->fault().active);
  EXPECT_EQ(job.kernel->jobs_ended(), 1u);  // ended as a job ends: no stop, no e-stop
  EXPECT_EQ(job.kernel->underruns(), 0u);
  EXPECT_EQ(job.sim->position_steps(0), 990'000);  // the end of line 4, exactly
  EXPECT_EQ(job.sim->position_steps(0), planned.commanded[0]);
  ASSERT_FALSE(recs.empty());
  EXPECT_EQ(recs.back().power_pct, 0.0f);  // the laser is off at rest
  // it came to rest gradually: no period moved X more than the axis's
  // acceleration allows after the one before
  EXPECT_LE(worst_accel_excess(recs, job.m), 0.0);
}

// A stop mid-way ends the planning too. The kernel discards a stopped job's
// entries as fast as they come, so the buffer never fills: the planner must
// see the abort itself, not only when it waits for room — else it plans on to
// the program's end (here 90 s of motion) before the job counts as over.
TEST(JobPipeline, AnAbortedFeedPlansNoFurtherWhileItsEntriesAreDiscarded) {
  const fs::path prog = write_job_pipeline("long_line.ngc", "G21 G90\nM3 S50\nG1 X900 F600\nM5\nM2\n");
  Job job;  // the kernel not started
  job.feed->start(prog.string(), ReaderOptions{});
  // This thread discards as the kernel's flush does, and asks for the abort
  // from inside the drain after 30,000 entries: when the flag is raised at
  // most a buffer's worth more waits, whatever the scheduling.
  std::uint64_t discarded = 0;
  PeriodIncrement inc;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (!job.feed->done() && std::chrono::steady_clock::now() < deadline)
    if (job.buffer->try_pop(inc) && ++discarded == 30'000) job.feed->request_abort();
  ASSERT_TRUE(job.feed->done());
  job.feed->join();
  const double total_periods = 90.0 / job.m.period_s();  // 1.2 million
  EXPECT_LE(job.feed->result().increments,
            30'000u + rt::kPositionBufferCapacity + 1u);  // +1: the entry in hand
  EXPECT_GT(total_periods, 1e6);
}

// The planner thread stalled on purpose at full speed (as if starved of the
// CPU): the kernel brakes along the path on its buffer's reserve within the
// axis's acceleration — no underrun, no jump — logs that the buffer ran
// low, waits at rest, and runs on when the planner comes back: the job ends
// with every step.
TEST(JobPipeline, APlannerStalledAtFullSpeedBrakesAlongThePathAndRunsOn) {
  const fs::path prog = write_job_pipeline("stall.ngc", "G21 G90\nM3 S50\nG1 X250 F6000\nM5\nM2\n");
  std::unique_ptr<rt::TraceRing> trace = std::make_unique<rt::TraceRing>();
  std::unique_ptr<rt::RtLogRing> log = std::make_unique<rt::RtLogRing>();
  Job job(trace.get());
  job.kernel->set_log(log.get());
  // at cruise, 100 mm/s: X ≈ 80 mm after 12,000 periods (0.9 s) — the
  // planner stops there whatever the threads' timing
  job.feed->inject_stall_after(12'000);
  job.run(prog);
  std::vector<rt::TraceRecord> recs;
  std::vector<rt::RtLogRecord> logged;
  auto drain = [&] {
    rt::TraceRecord rec;
    while (trace->try_pop(rec)) recs.push_back(rec);
    rt::RtLogRecord l;
    while (log->try_pop(l)) logged.push_back(l);
  };
  auto wait = [&](auto done) {
    const auto until = std::chrono::steady_clock::now() + 30s;
    while (!done() && std::chrono::steady_clock::now() < until) {
      drain();
      std::this_thread::sleep_for(1ms);
    }
    return done();
  };
  ASSERT_TRUE(wait([&] { return job.kernel->starvations() > 0; }));
  // at rest: X still for 100 ms
  std::int64_t x = -1;
  ASSERT_TRUE(wait([&] {
    const std::int64_t now = job.sim->position_steps(0);
    if (now != x) {
      x = now;
      return false;
    }
    std::this_thread::sleep_for(100ms);
    return job.sim->position_steps(0) == x;
  }));
  EXPECT_GT(x, 50'000);
  EXPECT_LT(x, 100'000);
  EXPECT_EQ(job.kernel->state(), shm::MachineState::Running);  // waiting, not faulted
  EXPECT_FALSE(job.kernel->fault().active);
  drain();  // the records of the rest just seen
  const std::size_t stalled_at = recs.size();
  job.feed->inject_stall(false);
  ASSERT_TRUE(wait([&] { return job.kernel->finished(); }));
  job.kernel->join();
  job.feed->join();
  drain();
  const PlannedJob& planned = job.feed->result();
  ASSERT_FALSE(planned.failed) << planned.error.to_string();
  EXPECT_EQ(job.sim->position_steps(0), 250'000);
  EXPECT_EQ(job.sim->position_steps(0), planned.commanded[0]);
  EXPECT_EQ(job.kernel->underruns(), 0u);
  EXPECT_EQ(job.kernel->trace_drops(), 0u);
  EXPECT_LE(worst_accel_excess(recs, job.m), 0.0);
  // dark while it stood (M3 is constant power, but a held period is dark)
  std::size_t held = 0, held_lit = 0;
  for (std::size_t i = 0; i < stalled_at; ++i) {
    held += recs[i].held;
    held_lit += recs[i].held && recs[i].power_pct != 0.0f;
  }
  EXPECT_GT(held, 100u);
  EXPECT_EQ(held_lit, 0u);
  bool began = false, ended = false;
  for (const rt::RtLogRecord& l : logged) {
    began |= l.code == rt::RtLogCode::StarveBegin;
    ended |= began && l.code == rt::RtLogCode::StarveEnd;
  }
  EXPECT_TRUE(began && ended);
}

// The override above 100 % comes through the planner, below it through the
// RT's period scaling; both at once, mid-job, never take an axis past its
// limits. Three laps of an R40 circle of 2000 chords at F12000 (200 mm/s)
// in real time, the override set from this thread at given periods: 100 %, then
// 150 % — planned from the entry the planner is at (the kernel's period plus
// what is queued) — then 40 % and back to 100 %, each acting in the RT at
// once. Measured from the trace as an outsider would (MotionCheck: velocity
// and acceleration over the windows it states).
TEST(JobPipeline, OverrideRaisedTo150AndLoweredTo40MidJobKeepsEveryLimitAndStep) {
  std::string text = "G21 G90 G64 P0.01\nG0 X90 Y50 Z5\nM3 S60\nG1 F12000\n";
  char buf[96];
  for (int lap = 0; lap < 3; ++lap)
    for (int i = 1; i <= 2000; ++i) {
      const double phi = 2 * M_PI * i / 2000.0;
      std::snprintf(buf, sizeof buf, "X%.4f Y%.4f\n", 50 + 40 * std::cos(phi), 50 + 40 * std::sin(phi));
      text += buf;
    }
  text += "M5\nM2\n";
  const fs::path prog = write_job_pipeline("override_circle.ngc", text);
  ASSERT_TRUE(static_cast<bool>(check_program(prog.string(), machine())));
  std::unique_ptr<rt::TraceRing> trace = std::make_unique<rt::TraceRing>();
  Job job(trace.get());
  job.run(prog);
  std::vector<rt::TraceRecord> recs;
  rt::TraceRecord rec;
  // waits for the kernel's period `at`, reading the trace; false if the job ended first
  auto reach = [&](std::uint64_t at) {
    while (!job.kernel->finished() && job.kernel->periods() < at) {
      while (trace->try_pop(rec)) recs.push_back(rec);
      std::this_thread::yield();
    }
    return !job.kernel->finished();
  };
  ASSERT_TRUE(reach(8'000));
  job.kernel->set_feed_override(1.5);
  // the planner plans for it from about the entry it is at
  const std::uint64_t raised = job.kernel->periods() + job.buffer->size();
  ASSERT_TRUE(reach(raised + 6'000));
  job.kernel->set_feed_override(0.4);
  const std::uint64_t lowered = job.kernel->periods();
  ASSERT_TRUE(reach(lowered + 5'000));
  job.kernel->set_feed_override(1.0);
  const std::uint64_t back = job.kernel->periods();
  reach(std::numeric_limits<std::uint64_t>::max());
  job.kernel->join();
  job.feed->join();
  while (trace->try_pop(rec)) recs.push_back(rec);
  const PlannedJob& planned = job.feed->result();
  ASSERT_FALSE(planned.failed) << planned.error.to_string();
  // steps exact, no underrun, no fault, the whole trace
  for (int a = 0; a < kAxisCount; ++a) EXPECT_EQ(job.sim->position_steps(a), planned.commanded[a]) << a;
  EXPECT_EQ(job.kernel->underruns(), 0u);
  EXPECT_FALSE(job.kernel->fault().active);
  ASSERT_EQ(job.kernel->trace_drops(), 0u);
  ASSERT_EQ(recs.size(), job.kernel->periods());
  // every axis within its velocity and acceleration limits
  MotionCheck check(job.m, job.start);
  for (const rt::TraceRecord& r : recs) check.add(r.t_ns, r.pos_steps, r.line);
  check.finish();
  EXPECT_TRUE(check.ok()) << check.breaches().front();
  // A planner that fell behind (a sanitizer build on a loaded machine) had
  // the RT slow the path for it: then the phases' speeds are not the
  // override's alone. The rest above holds whatever the timing.
  if (job.kernel->starvations() > 0) GTEST_SKIP() << "the planner fell behind: phase speeds not checked";
  // the path speed per phase, over windows of 40 periods: 100 % (200 mm/s);
  // 150 % once the re-planned entries run (the look-ahead's window and
  // 100 → 150 mm/s at 5000 mm/s²: a few hundred periods); 40 % once the
  // ramp is over (0.15 s of machine time, some 1,300 periods); 100 %
  auto speed = [&](std::size_t k) {
    const rt::TraceRecord &a = recs[k - 40], &b = recs[k];
    const double dx = static_cast<double>(b.pos_steps[0] - a.pos_steps[0]) / 1000.0;
    const double dy = static_cast<double>(b.pos_steps[1] - a.pos_steps[1]) / 1000.0;
    return std::hypot(dx, dy) / (static_cast<double>(b.t_ns - a.t_ns) * 1e-9);
  };
  auto range = [&](std::uint64_t from, std::uint64_t to) {
    double lo = 1e300, hi = 0.0;
    for (std::size_t k = std::max<std::uint64_t>(from, 40); k < std::min<std::uint64_t>(to, recs.size());
         ++k) {
      lo = std::min(lo, speed(k));
      hi = std::max(hi, speed(k));
    }
    return std::pair{lo, hi};
  };
  ASSERT_GT(raised, 10'000u);
  const auto [lo100, hi100] = range(raised - 4'000, raised);
  EXPECT_NEAR(lo100, 200.0, 2.0);
  EXPECT_NEAR(hi100, 200.0, 2.0);
  const auto [lo150, hi150] = range(raised + 1'500, lowered);
  EXPECT_NEAR(lo150, 300.0, 3.0);
  EXPECT_NEAR(hi150, 300.0, 3.0);
  const auto [lo40, hi40] = range(lowered + 2'500, back);
  EXPECT_NEAR(lo40, 80.0, 1.0);
  EXPECT_NEAR(hi40, 80.0, 1.0);
  const auto [lo_back, hi_back] = range(back + 2'500, back + 4'000);
  EXPECT_NEAR(lo_back, 200.0, 2.0);
  EXPECT_NEAR(hi_back, 200.0, 2.0);
}

// The soak: random jobs one after another on the simulated clock (the kernel runs
// each period as soon as the planner has the buffer filled: a planner never
// late) until LCNC_SOAK_PERIODS periods have run (CI: 2,000,000;
// RELIABILITY.md: 100,000,000), under random feed-override changes (0 … 150 %),
// holds and resumes from another thread. Every job ends with Σ pulses =
// commanded steps on every axis, no underrun, no fault.
TEST(JobPipeline, SoakOfRandomJobsUnderOverrideHoldsAndResumesLosesNoStep) {
  const char* env = std::getenv("LCNC_SOAK_PERIODS");
  const double target = env != nullptr ? std::atof(env) : 2e6;
  std::uint64_t periods = 0, held = 0, jobs = 0, changes = 0, holds = 0;
  double machine_s = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  std::mt19937 rng(4242);
  for (std::uint32_t seed = 100; static_cast<double>(periods) < target; ++seed) {
    const fs::path prog = write_job_pipeline("soak.ngc", random_program(seed, 400));
    if (!check_program(prog.string(), machine())) continue;  // an arc beyond the travel
    Job job;
    job.run(prog, rt::RtClock::Simulated);
    bool holding = false;
    while (!job.kernel->finished()) {
      // a plan the guard refused stops short and waits for a stop: in
      // the simulated clock the kernel waits for the planner, so end it and fail
      if (job.feed->stopped_short()) {
        job.kernel->command({rt::RtCommandType::Stop, 0, 0.0});
        job.feed->abort();
        job.kernel->shutdown();
        job.kernel->join();
        job.feed->join();
        FAIL() << "seed " << seed << ": " << job.feed->result().limit_error.to_string();
      }
      const unsigned r = rng() % 10;
      if (r < 6) {
        const double choices[] = {0.0, 0.1, 0.5, 0.8, 1.0, 1.2, 1.5};
        job.kernel->set_feed_override(choices[rng() % 7]);
        ++changes;
      } else if (!holding && r < 8) {
        job.kernel->command({rt::RtCommandType::Hold, 0, 0.0});
        holding = true;
        ++holds;
      } else if (holding) {
        job.kernel->command({rt::RtCommandType::Resume, 0, 0.0});
        holding = false;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200 + rng() % 1800));
      if (holding && rng() % 3 == 0) {  // a hold never outlasts a few turns
        job.kernel->command({rt::RtCommandType::Resume, 0, 0.0});
        holding = false;
      }
    }
    job.kernel->join();
    job.feed->join();
    const PlannedJob& planned = job.feed->result();
    ASSERT_FALSE(planned.failed) << seed << ": " << planned.error.to_string();
    for (int a = 0; a < kAxisCount; ++a)
      ASSERT_EQ(job.sim->position_steps(a), planned.commanded[a]) << "seed " << seed << " axis " << a;
    ASSERT_EQ(job.kernel->underruns(), 0u) << seed;
    ASSERT_FALSE(job.kernel->fault().active) << seed;
    periods += job.kernel->periods();
    held += job.kernel->held_periods();
    machine_s += static_cast<double>(job.kernel->machine_time_ns()) * 1e-9;
    ++jobs;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "rt soak: %llu periods (%llu held) in %llu random jobs, %.0f s of machine time in %.0f s; "
      "%llu override changes, %llu holds; every step exact, 0 underruns, 0 faults\n",
      static_cast<unsigned long long>(periods), static_cast<unsigned long long>(held),
      static_cast<unsigned long long>(jobs), machine_s, wall, static_cast<unsigned long long>(changes),
      static_cast<unsigned long long>(holds));
  EXPECT_GT(holds, 0u);
  EXPECT_GT(held, 0u);
}

}  // namespace
}  // namespace lcnc::app
