// The kernel's states and commands: e-stop, stop, feed
// hold, the braking reserve of a streaming job, soft and hard limits, jog and
// homing — on the real RT thread driving the simulated machine.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "drivers/sim_machine.h"
#include "rt/rt_kernel.h"
#include "rt/seqlock.h"
#include "rt/shm_interface.h"
#include "support/rt_rig.h"

namespace lcnc::rt {
namespace {

using namespace std::chrono_literals;

using test::rt_machine;
using test::step_x;
using test::wait_for;

// The rig with its rings read in the background, as a daemon reads them.
struct ControlRig : test::KernelRig {
  explicit ControlRig(std::array<std::int64_t, kAxisCount> at = {}, MachineConfig config = rt_machine(),
                      std::array<std::int64_t, kAxisCount> raw = {},
                      std::array<PitchTable, kAxisCount> pitch_error = {})
      : KernelRig(at, std::move(config), raw, pitch_error) {
    read_in_background();
  }
};

TEST(RtKernelControl, EStopStopsMotionAndLaserFromTheNextPeriod) {
  ControlRig r;
  for (int i = 0; i < 12000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(20)));
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 200; }));
  const std::uint64_t before = r.kernel->periods();  // periods completed when e-stop is sent
  r.send(RtCommandType::EStop);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
  std::this_thread::sleep_for(5ms);
  r.drain();
  // the period running while the command arrived may still move; from the
  // one after it on: no pulse, laser off
  std::size_t checked = 0;
  for (const TraceRecord& rec : r.records) {
    if (rec.period < before + 1) continue;
    ++checked;
    EXPECT_EQ(rec.pos_steps[0], r.records[before].pos_steps[0]) << rec.period;
    EXPECT_EQ(rec.power_pct, 0.0f) << rec.period;
  }
  EXPECT_GT(checked, 10u);
  const RtFault f = r.kernel->fault();
  EXPECT_TRUE(f.active);
  EXPECT_EQ(f.code, ErrorCode::RtEstop);
  // the job was discarded; reset → Idle, and a new job runs
  ASSERT_TRUE(wait_for([&] { return r.buffer->empty(); }));
  r.send(RtCommandType::StartJob);  // refused in e-stop
  r.send(RtCommandType::Reset);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  EXPECT_FALSE(r.kernel->fault().active);
  bool refused = false;
  for (const RtLogRecord& l : r.logs())
    refused = refused ||
              (l.code == RtLogCode::Refused && l.value == static_cast<std::int64_t>(RtCommandType::StartJob));
  EXPECT_TRUE(refused);
  const std::int64_t at = r.kernel->position_steps(0);
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(3)));
  PeriodIncrement end = step_x(1);
  end.end_of_program = true;
  ASSERT_TRUE(r.buffer->try_push(end));
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->position_steps(0) == at + 301; }));
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  EXPECT_EQ(r.sim->position_steps(0), r.kernel->position_steps(0));
  r.kernel->shutdown();
}

// The trace says which periods took a job's entry: only their segment is
// the job's (idle and underrun periods hold a position of no segment, and a
// path check must skip them).
TEST(RtKernelControl, TraceMarksThePeriodsThatTookAJobsEntry) {
  ControlRig r;
  r.start_idle();
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 50; }));
  for (int i = 0; i < 200; ++i) {
    PeriodIncrement inc = step_x(3);
    inc.segment = 7;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.send(RtCommandType::StartJob);
  // no end of program: the buffer runs dry, an underrun
  ASSERT_TRUE(wait_for([&] { return r.kernel->underruns() > 20; }));
  r.send(RtCommandType::EStop);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
  r.drain();
  std::size_t on = 0, underrun = 0, idle = 0;
  for (const TraceRecord& rec : r.records) {
    if (rec.on_path) {
      ++on;
      EXPECT_EQ(rec.segment, 7u) << rec.period;
      EXPECT_FALSE(rec.underrun);
    } else if (rec.underrun) {
      ++underrun;
    } else {
      ++idle;
    }
  }
  EXPECT_EQ(on, 200u);
  EXPECT_GT(underrun, 20u);
  EXPECT_GT(idle, 50u);
  r.kernel->shutdown();
}

// The e-stop word (any process bumps it, no lock, no daemon in between):
// the kernel takes it in the period after the request, counted by the
// kernel itself — the StateChange log record carries its period index.
TEST(RtKernelControl, EStopWordActsInTheNextPeriod) {
  ControlRig r;
  for (int i = 0; i < 12000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(20)));
  std::atomic<std::uint32_t> word{7};  // requests before the start are not this run's
  r.kernel->set_estop_word(&word);
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 200; }));
  EXPECT_EQ(r.kernel->state(), MachineState::Running);  // the old count was no e-stop
  (void)r.logs();
  // the periods completed at the request lie between these two
  const std::uint64_t before = r.kernel->periods();
  word.fetch_add(1, std::memory_order_release);
  const std::uint64_t after = r.kernel->periods();
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
  std::uint64_t at = 0;
  for (const RtLogRecord& l : r.logs())
    if (l.code == RtLogCode::StateChange && l.value == static_cast<std::int64_t>(MachineState::EStop))
      at = l.period;
  // the period under way at the request may have read the word already; the
  // next one takes it
  EXPECT_GE(at, before);
  EXPECT_LE(at, after + 1);
  EXPECT_EQ(r.kernel->fault().code, ErrorCode::RtEstop);
  EXPECT_FALSE(r.kernel->last_job_completed());
  // reset, and the same word again: a second e-stop
  r.send(RtCommandType::Reset);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  word.fetch_add(1, std::memory_order_release);
  EXPECT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
}

// The control side knows when a command has been taken: until then the state
// is the one before it; once taken, the one the command brought (the daemon
// answers its senders only then).
TEST(RtKernelControl, ACommandIsCountedTakenWithTheStateItBrought) {
  ControlRig r;
  EXPECT_TRUE(r.kernel->commands_taken());  // none pushed
  r.send(RtCommandType::Jog, 0, 90.0);
  EXPECT_FALSE(r.kernel->commands_taken());  // no period has run
  EXPECT_EQ(r.kernel->state(), MachineState::Idle);
  r.start_idle();
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken(); }));
  EXPECT_EQ(r.kernel->state(), MachineState::Jog);  // a 90 mm jog is far from its end
  r.send(RtCommandType::Stop);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken(); }));
  r.send(RtCommandType::EStop);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken(); }));
  EXPECT_EQ(r.kernel->state(), MachineState::EStop);
}

// A job that ran to its end is told apart from a stopped one.
TEST(RtKernelControl, LastJobCompletedSaysWhetherTheJobRanToItsEnd) {
  ControlRig r;
  for (int i = 0; i < 100; ++i) {
    PeriodIncrement inc = step_x(5);
    inc.end_of_program = i == 99;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(
      wait_for([&] { return r.kernel->jobs_ended() == 1 && r.kernel->state() == MachineState::Idle; }));
  EXPECT_TRUE(r.kernel->last_job_completed());
  for (int i = 0; i < 12000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(20)));
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken(); }));  // running
  r.send(RtCommandType::Stop);
  ASSERT_TRUE(wait_for([&] { return r.kernel->jobs_ended() == 2; }));
  EXPECT_FALSE(r.kernel->last_job_completed());
}

TEST(RtKernelControl, StopRampsDownAlongThePathThenDiscardsTheJob) {
  ControlRig r;
  for (int i = 0; i < 12000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(20)));
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 300; }));
  r.send(RtCommandType::Stop);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  ASSERT_TRUE(wait_for([&] { return r.buffer->empty(); }));
  std::this_thread::sleep_for(3ms);
  r.kernel->shutdown();
  r.kernel->join();
  r.drain();
  EXPECT_LT(r.kernel->motion_periods(), 12000u);  // the rest was discarded
  EXPECT_EQ(r.kernel->underruns(), 0u);
  EXPECT_FALSE(r.kernel->fault().active);  // an operator's stop is no fault
  EXPECT_EQ(r.sim->position_steps(0), r.kernel->position_steps(0));
  // the speed falls at the ramp's acceleration, never in a jump: from
  // 20 steps/T (267 mm/s) to 0 at ρ·v = 50/s · 267 mm/s ≈ 13 m/s², well under
  // the 50 m/s² the axis has
  const std::vector<double> v = r.speeds();
  const double amax = 50000.0 * 1000.0;  // steps/s²
  double peak = 0.0;
  // from the job's first moving period on (the test's entries start at full
  // speed; a loaded computer may let idle periods run before the start)
  std::size_t first = 0;
  while (first < v.size() && v[first] == 0.0) ++first;
  for (std::size_t i = first + 1; i < v.size(); ++i) {
    const double dt = r.m.period_s() / std::max(r.records[i].feed_override, 1e-9);
    peak = std::max(peak, std::abs(v[i] - v[i - 1]) / dt);
  }
  EXPECT_LT(peak, 0.5 * amax);
  EXPECT_EQ(v.back(), 0.0);
}

TEST(RtKernelControl, FeedHoldAndResumeAreStates) {
  ControlRig r;
  std::int64_t sum = 0;
  // 1.2 s of motion: a loaded computer that lets this thread look late still
  // finds the job running when it holds it
  for (int i = 0; i < 16000; ++i) {
    PeriodIncrement inc = step_x(5);  // 80 mm in all: within the travel
    inc.end_of_program = i == 15999;
    sum += 5;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 100; }));
  r.send(RtCommandType::Hold);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::FeedHold; }));
  ASSERT_TRUE(wait_for([&] { return r.kernel->held_periods() > 50; }));
  const std::int64_t held_at = r.kernel->position_steps(0);
  std::this_thread::sleep_for(10ms);
  EXPECT_EQ(r.kernel->position_steps(0), held_at);  // holds, laser off
  r.send(RtCommandType::Resume);
  // taken: the state it brought was Running (the rest of the job may be over
  // before a loaded computer lets this thread look)
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken(); }));
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }))
      << "state " << static_cast<int>(r.kernel->state()) << " at " << r.kernel->position_steps(0) << " of "
      << sum << ", underruns " << r.kernel->underruns();
  EXPECT_EQ(r.kernel->position_steps(0), sum);
  EXPECT_EQ(r.sim->position_steps(0), sum);
  EXPECT_EQ(r.kernel->underruns(), 0u);
  r.kernel->shutdown();
}

// M0/M1/M60: the job holds after the pause's entry at once — no entry after
// it runs, not even during a ramp — until Resume, then ends where it should.
TEST(RtKernelControl, AProgramPauseHoldsAtItsEntryUntilResumed) {
  ControlRig r;
  std::int64_t sum = 0;
  for (int i = 0; i < 600; ++i) {
    PeriodIncrement inc = step_x(i < 300 ? 10 : 0, i < 300 ? 1 : 2);
    if (i >= 300 && i < 302) inc.kind = MotionKind::Dwell;  // the pause's dwell, at rest
    inc.pause = i == 300;
    if (i >= 302) inc = step_x(10, 3);
    inc.end_of_program = i == 599;
    sum += inc.steps[0];
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->program_paused(); }));
  EXPECT_EQ(r.kernel->state(), MachineState::FeedHold);
  EXPECT_EQ(r.kernel->program_pauses(), 1u);
  // at the pause: the 300 entries before it ran, none after it
  EXPECT_EQ(r.kernel->position_steps(0), 3000);
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(r.kernel->position_steps(0), 3000);
  EXPECT_EQ(r.buffer->size(), 299u);
  r.send(RtCommandType::Resume);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  EXPECT_FALSE(r.kernel->program_paused());
  EXPECT_EQ(r.kernel->position_steps(0), sum);
  EXPECT_EQ(r.sim->position_steps(0), sum);
  bool logged = false;
  for (const RtLogRecord& l : r.logs())
    if (l.code == RtLogCode::ProgramPause) logged = l.line == 2;
  EXPECT_TRUE(logged);
  r.kernel->shutdown();
}

// Unattended (`lasercnc run --pause S`): the kernel ends a program pause by
// itself after RtOptions::program_pause_periods, counted in its own periods,
// so the pause lasts the same machine time on the simulated clock as on the
// wall clock; the job then runs to its end with every step.
TEST(RtKernelControl, AnUnattendedProgramPauseEndsAfterItsPeriodsOnTheSimulatedClock) {
  ControlRig r;
  std::int64_t sum = 0;
  for (int i = 0; i < 600; ++i) {
    PeriodIncrement inc = step_x(i < 300 ? 10 : 0, i < 300 ? 1 : 2);
    if (i >= 300 && i < 302) inc.kind = MotionKind::Dwell;
    inc.pause = i == 300;
    if (i >= 302) inc = step_x(10, 3);
    inc.end_of_program = i == 599;
    sum += inc.steps[0];
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  RtOptions o;
  o.try_realtime = false;
  o.clock = RtClock::Simulated;
  o.program_pause_periods = 400;
  r.kernel->start(o);
  r.kernel->join();
  r.drain();
  EXPECT_EQ(r.kernel->program_pauses(), 1u);
  EXPECT_EQ(r.kernel->position_steps(0), sum);
  EXPECT_EQ(r.sim->position_steps(0), sum);
  std::size_t held = 0;
  for (const TraceRecord& t : r.records) held += t.held;
  // after the pause's own period, 399 held ones; then the resume ramps K up
  // from 0, its first periods below K_min held too (a few dozen at most)
  EXPECT_GE(held, 399u);
  EXPECT_LT(held, 399u + 50u);
  EXPECT_EQ(r.records.size(), 600u + held);
  EXPECT_EQ(r.kernel->periods(), 600u + held);
  EXPECT_EQ(r.kernel->latency().total(), 0u);  // the simulated clock measures none
}

// M66: the job holds at the wait's entry until the input does as asked —
// a resume does not end it — then goes on; the time up, it stops with E420.
TEST(RtKernelControl, AnInputWaitHoldsUntilTheInputComesOrStopsAtItsTimeout) {
  for (const bool comes : {true, false}) {
    SCOPED_TRACE(comes ? "the input comes" : "the time is up");
    ControlRig r;
    std::int64_t sum = 0;
    for (int i = 0; i < 600; ++i) {
      PeriodIncrement inc = step_x(i < 300 ? 10 : 0, i < 300 ? 1 : 2);
      if (i >= 300 && i < 302) inc.kind = MotionKind::Dwell;  // the wait's dwell, at rest
      if (i == 300) {
        inc.wait_input = 3;
        inc.wait_mode = 1;  // a rise
        inc.wait_timeout_s = comes ? 30.0f : 0.05f;
      }
      if (i >= 302) inc = step_x(10, 3);
      inc.end_of_program = i == 599;
      sum += inc.steps[0];
      ASSERT_TRUE(r.buffer->try_push(inc));
    }
    r.sim->set_digital_inputs(0b1000);  // high already: a rise needs it low first
    r.start_idle();
    r.send(RtCommandType::StartJob);
    ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::FeedHold; }));
    EXPECT_EQ(r.kernel->position_steps(0), 3000);
    if (comes) {
      r.send(RtCommandType::Resume);  // no: the input decides
      std::this_thread::sleep_for(20ms);
      EXPECT_EQ(r.kernel->state(), MachineState::FeedHold);
      EXPECT_EQ(r.kernel->position_steps(0), 3000);
      r.sim->set_digital_inputs(0);
      std::this_thread::sleep_for(5ms);
      EXPECT_EQ(r.kernel->state(), MachineState::FeedHold);  // low is no rise
      r.sim->set_digital_inputs(0b1000);
      ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
      EXPECT_TRUE(r.kernel->last_job_completed());
      EXPECT_EQ(r.kernel->position_steps(0), sum);
    } else {
      ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
      EXPECT_FALSE(r.kernel->last_job_completed());
      EXPECT_EQ(r.kernel->fault().code, ErrorCode::RtInputTimeout);
      EXPECT_EQ(r.kernel->fault().line, 2u);
      EXPECT_EQ(r.kernel->position_steps(0), 3000);  // nothing after the wait ran
    }
    bool logged = false;
    for (const RtLogRecord& l : r.logs())
      if (l.code == RtLogCode::InputWait) logged = l.line == 2 && l.value == 3;
    EXPECT_TRUE(logged);
    r.kernel->shutdown();
  }
}

// M50 P0 / M49: entries the program took out of the override run at
// K = 1 whatever the operator's override, reached by the override ramp
// (no jump in speed); the override acts again on the entries after them.
TEST(RtKernelControl, EntriesWithTheOverrideOffRunAtFullSpeedWhateverTheOverride) {
  ControlRig r;
  for (int i = 0; i < 9000; ++i) {
    const std::uint32_t line = i < 2000 ? 1 : i < 7000 ? 2 : 3;
    PeriodIncrement inc = step_x(10, line);
    if (line == 2) inc.feed_control = kFeedOverrideOff;
    inc.end_of_program = i == 8999;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.kernel->set_feed_override(0.5);
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(
      wait_for([&] { return r.kernel->state() == MachineState::Idle && r.kernel->periods() > 9000; }));
  r.drain();
  ASSERT_GE(r.records.size(), 9000u);
  std::map<std::uint32_t, std::vector<double>> k_by_line;
  double prev = r.records.front().feed_override;
  const double rate = r.kernel->override_ramp().rate_per_s();
  for (std::size_t i = 0; i < r.records.size(); ++i) {
    const TraceRecord& rec = r.records[i];
    if (!rec.on_path) continue;
    k_by_line[rec.line].push_back(rec.feed_override);
    // no step in K beyond the ramp's rate over the period
    const double dt = std::max(r.length(i), i > 0 ? r.length(i - 1) : 0.0);
    ASSERT_LE(std::abs(rec.feed_override - prev), rate * dt * 1.001 + 1e-12) << i;
    prev = rec.feed_override;
  }
  EXPECT_NEAR(k_by_line[1].back(), 0.5, 1e-9);
  EXPECT_EQ(k_by_line[2].back(), 1.0);          // the last of the 5000: long since at 1
  EXPECT_LT(k_by_line[2].front(), 0.51);        // it started from the override …
  EXPECT_NEAR(k_by_line[3].back(), 0.5, 1e-9);  // … and goes back to it
  EXPECT_EQ(r.kernel->position_steps(0), 90000);
  r.kernel->shutdown();
}

// M52 P1: the adaptive-feed input scales the feed of the entries the
// program put under it; M53: the feed-hold input holds the motion (at
// rest, resumed when it drops), except on entries after M53 P0.
TEST(RtKernelControl, TheFeedInputsActOnTheEntriesTheProgramPutsUnderThem) {
  ControlRig r;
  for (int i = 0; i < 12000; ++i) {
    const std::uint32_t line = i < 6000 ? 1 : 2;
    PeriodIncrement inc = step_x(5, line);  // 60 mm in all: the travel is 100
    inc.feed_control = line == 1 ? kAdaptiveFeed : kFeedHoldInputOff;
    inc.end_of_program = i == 11999;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.sim->set_adaptive_feed(0.25f);
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->position_steps(0) > 10000; }));
  r.sim->set_feed_hold_input(true);    // line 1 obeys it
  std::this_thread::sleep_for(150ms);  // the ramp to 0 takes 0.05 s of machine time
  const std::int64_t held_at = r.kernel->position_steps(0);
  std::this_thread::sleep_for(30ms);
  EXPECT_EQ(r.kernel->position_steps(0), held_at);
  EXPECT_LT(held_at, 30000);
  r.sim->set_feed_hold_input(false);
  ASSERT_TRUE(wait_for([&] { return r.kernel->position_steps(0) > 30000; }));
  r.sim->set_feed_hold_input(true);  // line 2 does not
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }))
      << static_cast<int>(r.kernel->state()) << " at " << r.kernel->position_steps(0);
  EXPECT_TRUE(r.kernel->last_job_completed());
  EXPECT_EQ(r.kernel->position_steps(0), 60000);
  r.drain();
  double k1 = 0.0, k2 = 0.0;
  bool held_seen = false;
  for (const TraceRecord& rec : r.records) {
    if (rec.held) held_seen = true;
    if (!rec.on_path) continue;
    if (rec.line == 1 && rec.pos_steps[0] < 10000) k1 = rec.feed_override;
    if (rec.line == 2) k2 = rec.feed_override;
  }
  EXPECT_TRUE(held_seen);
  EXPECT_NEAR(k1, 0.25, 1e-9);  // the input's factor, once the ramp got there
  EXPECT_EQ(k2, 1.0);           // line 2 is not under adaptive feed
  r.kernel->shutdown();
}

// A producer streaming slower than the machine runs: the kernel keeps the
// braking reserve and decelerates along the path instead of running dry.
TEST(RtKernelControl, SlowStreamDeceleratesAlongThePathAndNeverUnderruns) {
  ControlRig r;
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(20)));
  r.kernel->stream_begin();
  RtOptions o;
  o.try_realtime = false;
  r.kernel->start(o);
  // push 3000 more at about half the machine's pace, then end the stream
  std::int64_t sum = 1000 * 20;
  for (int i = 0; i < 3000; ++i) {
    PeriodIncrement inc = step_x(20);
    inc.end_of_program = i == 2999;
    while (!r.buffer->try_push(inc)) std::this_thread::sleep_for(50us);
    sum += 20;
    if (i % 4 == 0) std::this_thread::sleep_for(600us);
  }
  r.kernel->stream_end();
  std::thread drainer([&] {
    while (!r.kernel->finished()) {
      r.drain();
      std::this_thread::sleep_for(1ms);
    }
  });
  r.kernel->join();
  drainer.join();
  r.drain();
  EXPECT_EQ(r.kernel->underruns(), 0u);
  EXPECT_GT(r.kernel->starvations(), 0u);
  EXPECT_EQ(r.sim->position_steps(0), sum);
  EXPECT_EQ(r.kernel->trace_drops(), 0u);
  // the speed changes only as fast as the override ramps (ρ·v ≈ 13 m/s²) —
  // twice that where the ramp leaves or enters the hold, the step at K_min
  // it is designed for (rt/feed_override.h) — plus the steps' quantization
  const std::vector<double> v = r.speeds();
  const double ramp_accel = r.kernel->override_ramp().rate_per_s() * 20 / r.m.period_s();
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double dt = 0.5 * (r.length(i) + r.length(i - 1));
    EXPECT_LE(std::abs(v[i] - v[i - 1]) / dt, 2.0 * ramp_accel + 1.0 / (dt * dt)) << i;
  }
}

// The last line of defence: an entry that would cross a soft limit is not
// executed (the planner thread's own check stops jobs short along the path
// before that: tests/e2e).
TEST(RtKernelControl, AnEntryCrossingTheSoftLimitIsNotExecuted) {
  ControlRig r({99'000, 0, 0, 0, 0, 0});  // X at 99 mm, travel 0–100 mm
  for (int i = 0; i < 200; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(7, 7)));
  RtOptions o;
  o.try_realtime = false;
  r.kernel->start(o);  // one-shot: ends once the e-stop has settled
  r.kernel->join();
  r.drain();
  const RtFault f = r.kernel->fault();
  ASSERT_TRUE(f.active);
  EXPECT_EQ(f.code, ErrorCode::RtSoftLimit);
  EXPECT_EQ(f.axis, 0);
  EXPECT_EQ(f.line, 7u);
  EXPECT_EQ(r.kernel->state(), MachineState::EStop);
  EXPECT_EQ(r.kernel->position_steps(0), 99'000 + 142 * 7);  // the last entry that fits
  std::int64_t peak = 0;
  for (const TraceRecord& rec : r.records) peak = std::max(peak, rec.pos_steps[0]);
  EXPECT_LE(peak, 100'000);
  EXPECT_EQ(r.sim->position_steps(0), r.kernel->position_steps(0));
}

TEST(RtKernelControl, JogMovesExactlyAndStopsShortAtTheSoftLimit) {
  ControlRig r({50'000, 0, 0, 0, 0, 0});
  r.start_idle();
  r.send(RtCommandType::Jog, 0, 12.345);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Jog; }));
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  EXPECT_EQ(r.kernel->position_steps(0), 62'345);
  EXPECT_EQ(r.sim->position_steps(0), 62'345);
  r.send(RtCommandType::Jog, 1, -5.0);  // Y at 0: the soft limit — no move
  ASSERT_TRUE(
      wait_for([&] { return r.kernel->commands_taken() && r.kernel->state() == MachineState::Idle; }));
  r.send(RtCommandType::Jog, 0, 1000.0);  // far past X max
  ASSERT_TRUE(wait_for([&] { return r.kernel->position_steps(0) == 100'000; }));
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  std::this_thread::sleep_for(5ms);
  EXPECT_EQ(r.kernel->position_steps(0), 100'000);
  EXPECT_EQ(r.kernel->position_steps(1), 0);
  int short_jogs = 0;
  for (const RtLogRecord& l : r.logs()) short_jogs += l.code == RtLogCode::JogShort;
  EXPECT_EQ(short_jogs, 2);
  r.kernel->shutdown();
  r.kernel->join();
  r.drain();
  // speeds within the jog speed, changes within the axis's acceleration,
  // but for the quantization to whole steps: rounded positions make two
  // neighbouring increments differ by up to 2 steps more than the motion does
  const std::vector<double> v = r.speeds();
  const double jog = 0.25 * 500 * 1000, acc = 50000.0 * 1000;
  for (std::size_t i = 1; i < v.size(); ++i) {
    EXPECT_LE(std::abs(v[i]), jog * 1.01 + 1.0 / r.m.period_s()) << i;
    EXPECT_LE(std::abs(v[i] - v[i - 1]) / r.m.period_s(), acc + 2.0 / (r.m.period_s() * r.m.period_s())) << i;
  }
}

TEST(RtKernelControl, CommandsOutsideTheirStatesAreRefused) {
  ControlRig r;
  for (int i = 0; i < 5000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(5)));
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 10; }));
  r.send(RtCommandType::Jog, 1, 1.0);
  r.send(RtCommandType::Home, 1);
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken(); }));
  int refused = 0;
  for (const RtLogRecord& l : r.logs()) refused += l.code == RtLogCode::Refused;
  EXPECT_EQ(refused, 3);
  EXPECT_EQ(r.kernel->position_steps(1), 0);
  EXPECT_EQ(r.kernel->state(), MachineState::Running);
  r.kernel->shutdown();
}

// The commands of one period are taken in the state it began in, but none
// moves the machine after an e-stop among them: a jog after an e-stop once
// read "Idle" and moved the machine out of its e-stop.
TEST(RtKernelControl, NoCommandOfThePeriodMovesTheMachineAfterAnEStop) {
  ControlRig r;
  r.begin_stepped();
  r.send(RtCommandType::EStop);
  r.send(RtCommandType::Jog, 0, 1.0);
  r.step(200);
  EXPECT_EQ(r.kernel->state(), MachineState::EStop);
  EXPECT_EQ(r.kernel->position_steps(0), 0);
  int refused = 0;
  for (const RtLogRecord& l : r.logs()) refused += l.code == RtLogCode::Refused;
  EXPECT_EQ(refused, 1);

  // nor a start or a homing
  r.send(RtCommandType::Reset);
  r.step();
  ASSERT_EQ(r.kernel->state(), MachineState::Idle);
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(5)));
  r.send(RtCommandType::EStop);
  r.send(RtCommandType::StartJob);
  r.send(RtCommandType::Home, 1);
  r.step(200);
  EXPECT_EQ(r.kernel->state(), MachineState::EStop);
  EXPECT_EQ(r.kernel->position_steps(0), 0);
  EXPECT_EQ(r.kernel->position_steps(1), 0);
  r.kernel->end_periods();
}

// Every command but the e-stop and the stop needs the mode its period began
// in: a jog taken in the period a job started in once put the machine into
// Jog with the job's entries queued, and a hold and a resume in one period
// undid each other.
TEST(RtKernelControl, NoCommandActsOnAModeChangedEarlierInItsPeriod) {
  ControlRig r;
  r.begin_stepped();
  for (int i = 0; i < 4000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(5)));
  r.send(RtCommandType::StartJob);
  r.send(RtCommandType::Jog, 1, 1.0);
  r.step();
  EXPECT_EQ(r.kernel->state(), MachineState::Running);
  r.step(10);
  EXPECT_EQ(r.kernel->position_steps(1), 0);  // no jog of Y
  EXPECT_EQ(r.kernel->position_steps(0), 11 * 5);
  r.send(RtCommandType::Hold);
  r.send(RtCommandType::Resume);
  r.step();
  EXPECT_EQ(r.kernel->state(), MachineState::FeedHold);  // held: the resume came in the hold's period
  int refused = 0;
  for (const RtLogRecord& l : r.logs()) refused += l.code == RtLogCode::Refused;
  EXPECT_EQ(refused, 1);  // the jog
  r.send(RtCommandType::Resume);
  r.step();
  EXPECT_EQ(r.kernel->state(), MachineState::Running);
  r.kernel->end_periods();
}

// The status that first shows a program's hold (M0, M66) says why it holds
// in the same publication: the reason was once set after the state, so
// that status said "feed hold" with no pause and no input for a while.
TEST(RtKernelControl, TheStatusThatShowsAProgramHoldSaysWhy) {
  for (const bool wait : {false, true}) {
    ControlRig r;
    auto status = std::make_unique<Seqlock<shm::Status>>();
    r.kernel->set_status(status.get());
    r.begin_stepped();
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(5)));
    PeriodIncrement hold = step_x(0, 2, 0.0f);
    hold.kind = MotionKind::Dwell;
    if (wait) {
      hold.wait_input = 3;
      hold.wait_mode = 3;  // high
      hold.wait_timeout_s = 10.0f;
    } else {
      hold.pause = true;
    }
    ASSERT_TRUE(r.buffer->try_push(hold));
    for (int i = 0; i < 10; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(5)));
    r.send(RtCommandType::StartJob);
    shm::Status st;
    for (int i = 0; i < 20 && r.kernel->state() != MachineState::FeedHold; ++i) r.step();
    ASSERT_EQ(r.kernel->state(), MachineState::FeedHold) << "wait " << wait;
    ASSERT_TRUE(status->load(st));
    EXPECT_EQ(st.state, MachineState::FeedHold) << "wait " << wait;
    EXPECT_EQ(st.program_pause, !wait);
    EXPECT_EQ(st.input_wait, wait ? 3 : -1);
    r.kernel->end_periods();
  }
}

// A job whose last entry runs while it is being stopped ends there, once:
// the stop it was in once outlived it, and an e-stop in the Idle that
// followed counted the job as ended (and aborted) a second time.
TEST(RtKernelControl, AJobThatEndsWhileStoppingEndsOnce) {
  ControlRig r;
  r.begin_stepped();
  for (int i = 0; i < 100; ++i) {
    PeriodIncrement inc = step_x(5);
    inc.end_of_program = i == 99;
    ASSERT_TRUE(r.buffer->try_push(inc));
  }
  r.send(RtCommandType::StartJob);
  r.step();
  r.send(RtCommandType::Stop);  // the ramp to rest outlasts the 99 entries left
  for (int i = 0; i < 200 && r.kernel->state() != MachineState::Idle; ++i) r.step();
  ASSERT_EQ(r.kernel->state(), MachineState::Idle);
  EXPECT_EQ(r.kernel->jobs_ended(), 1u);
  EXPECT_TRUE(r.kernel->last_job_completed());
  EXPECT_EQ(r.kernel->position_steps(0), 500);
  r.send(RtCommandType::EStop);
  r.step();
  EXPECT_EQ(r.kernel->state(), MachineState::EStop);
  EXPECT_EQ(r.kernel->jobs_ended(), 1u);
  EXPECT_TRUE(r.kernel->last_job_completed());
  r.send(RtCommandType::Reset);
  r.step();
  EXPECT_EQ(r.kernel->state(), MachineState::Idle);  // nothing to flush: reset at once
  r.kernel->end_periods();
}

TEST(RtKernelControl, HomingFindsTheSwitchAndRebasesTheAxis) {
  // The kernel believes X is at 50 mm; the switches sit 3 mm lower than it
  // thinks: the home switch trips where it would count −3 mm.
  ControlRig r({50'000, 20'000, 0, 0, 0, 0}, rt_machine(), {-3'000, 0, 0, 0, 0, 0});
  r.start_idle();
  r.send(RtCommandType::Home, 0);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Homing; }));
  EXPECT_EQ(r.kernel->homed_mask() & 1u, 0u);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }, 10000ms));
  EXPECT_FALSE(r.kernel->fault().active);
  EXPECT_EQ(r.kernel->homed_mask() & 1u, 1u);
  // the switch's position (count −3000 + 1, where it releases) is now X = 0
  const std::int64_t shift = r.kernel->position_steps(0) - r.sim->position_steps(0);
  EXPECT_NEAR(static_cast<double>(shift), 3'000.0, 1.0);
  EXPECT_NEAR(static_cast<double>(r.kernel->position_steps(0)), 0.0, 200.0);  // braked past it
  EXPECT_GE(r.kernel->position_steps(0), 0);
  EXPECT_EQ(r.kernel->position_steps(1), 20'000);  // other axes untouched
  bool homed = false;
  for (const RtLogRecord& l : r.logs()) homed = homed || (l.code == RtLogCode::Homed && l.axis == 0);
  EXPECT_TRUE(homed);
  // jogs now stop at the true travel
  r.send(RtCommandType::Jog, 0, -10.0);
  ASSERT_TRUE(
      wait_for([&] { return r.kernel->state() == MachineState::Idle && r.kernel->position_steps(0) == 0; }));
  r.kernel->shutdown();
}

TEST(RtKernelControl, HardLimitSwitchIsAnEStopNamingTheAxis) {
  // The switches sit 5 mm lower than the kernel thinks: X's max hard limit
  // (2 mm beyond the 100 mm soft limit) trips where it counts 97 mm.
  ControlRig r({90'000, 0, 0, 0, 0, 0}, rt_machine(), {-5'000, 0, 0, 0, 0, 0});
  r.start_idle();
  r.send(RtCommandType::Jog, 0, 9.0);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
  const RtFault f = r.kernel->fault();
  EXPECT_EQ(f.code, ErrorCode::RtHardLimit);
  EXPECT_EQ(f.axis, 0);
  EXPECT_GE(r.sim->position_steps(0), 97'000);
  EXPECT_LT(r.sim->position_steps(0), 97'100);  // stopped the period it tripped
  // reset, then only motion away from the switch is allowed
  r.send(RtCommandType::Reset);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  r.send(RtCommandType::Jog, 0, 1.0);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
  r.send(RtCommandType::Reset);
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::Idle; }));
  const std::int64_t at = r.kernel->position_steps(0);
  r.send(RtCommandType::Jog, 0, -2.0);
  ASSERT_TRUE(wait_for([&] { return r.kernel->position_steps(0) == at - 2'000; }));
  r.kernel->shutdown();
}

TEST(RtKernelControl, EStopInputStopsTheJobInThePeriodItIsSeen) {
  ControlRig r;
  for (int i = 0; i < 12000; ++i) ASSERT_TRUE(r.buffer->try_push(step_x(20)));
  r.start_idle();
  r.send(RtCommandType::StartJob);
  ASSERT_TRUE(wait_for([&] { return r.kernel->commands_taken() && r.kernel->periods() > 200; }));
  r.sim->set_estop_input(true);
  const std::uint64_t before = r.kernel->periods();
  ASSERT_TRUE(wait_for([&] { return r.kernel->state() == MachineState::EStop; }));
  std::this_thread::sleep_for(5ms);
  r.drain();
  for (const TraceRecord& rec : r.records)
    if (rec.period >= before + 1) {
      EXPECT_EQ(rec.pos_steps[0], r.records[before].pos_steps[0]) << rec.period;
    }
  EXPECT_EQ(r.kernel->fault().code, ErrorCode::RtEstop);
  r.kernel->shutdown();
}

// A leadscrew whose carriage runs ahead by up to 30 µm (the simulated
// machine's pitch error) and the config's compensation table, its negative:
// the carriage lands where it was commanded, to the step.
TEST(RtKernelControl, PitchCompensationPutsTheCarriageWhereCommanded) {
  MachineConfig m = rt_machine();
  PitchTable comp;
  comp.start = 0.0;
  comp.interval = 25.0;
  comp.values = {0.0, -0.010, -0.030, -0.020, 0.0};  // mm
  m.axes[0].pitch_compensation = comp;
  std::array<PitchTable, kAxisCount> error{};
  error[0].start = 0.0;
  error[0].interval = 25'000.0;
  error[0].values = {0.0, 10.0, 30.0, 20.0, 0.0};  // steps (µm), at counted positions
  ControlRig r({0, 0, 0, 0, 0, 0}, m, {}, error);
  r.start_idle();
  for (const double target : {37.5, 62.0, 99.0, 12.0}) {
    r.send(RtCommandType::Jog, 0, target - r.kernel->position_steps(0) / 1000.0);
    ASSERT_TRUE(wait_for([&] {
      return r.kernel->state() == MachineState::Idle &&
             r.kernel->position_steps(0) == std::llround(target * 1000);
    }));
    std::this_thread::sleep_for(2ms);
    // counted = commanded + correction; actual = counted + error ≈ commanded
    EXPECT_NEAR(static_cast<double>(r.sim->actual_position_steps(0)), target * 1000, 1.0) << target;
    EXPECT_NE(r.sim->position_steps(0), std::llround(target * 1000)) << target;
    EXPECT_EQ(r.kernel->pulses_emitted(0), r.sim->position_steps(0));
  }
  r.kernel->shutdown();
}

}  // namespace
}  // namespace lcnc::rt
