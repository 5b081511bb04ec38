// The machine screen's logic without Qt: controls by state, the alarm log,
// the time left, the touch-off G-code.
#include <gtest/gtest.h>

#include <cstring>

#include "hmi/machine_controls.h"

namespace lcnc::hmi {
namespace {

using S = shm::MachineState;

ControlView view(S state, bool job_active = false, bool loaded = true) {
  ControlView v;
  v.linked = true;
  v.state = state;
  v.job_active = job_active;
  v.program_loaded = loaded;
  return v;
}

TEST(ControlsEnabled, FollowTheMachineState) {
  const ControlsEnabled idle = controls_enabled(view(S::Idle));
  EXPECT_TRUE(idle.start && idle.frame && idle.jog && idle.home && idle.mdi && idle.touch_off);
  EXPECT_FALSE(idle.hold || idle.resume || idle.reset || idle.stop);
  EXPECT_FALSE(controls_enabled(view(S::Idle, false, false)).start);  // nothing loaded
  EXPECT_FALSE(controls_enabled(view(S::Idle, false, false)).frame);

  const ControlsEnabled running = controls_enabled(view(S::Running, true));
  EXPECT_FALSE(running.start || running.jog || running.home || running.mdi || running.touch_off ||
               running.frame);
  EXPECT_TRUE(running.hold && running.stop && running.override_feed);
  EXPECT_FALSE(running.resume);

  const ControlsEnabled held = controls_enabled(view(S::FeedHold, true));
  EXPECT_TRUE(held.resume && held.stop);
  EXPECT_FALSE(held.hold || held.jog || held.start);

  // a job planned but not yet moving is no time for a jog either
  const ControlsEnabled planning = controls_enabled(view(S::Idle, true));
  EXPECT_FALSE(planning.start || planning.jog || planning.mdi);
  EXPECT_TRUE(planning.stop);

  const ControlsEnabled estop = controls_enabled(view(S::EStop));
  EXPECT_TRUE(estop.reset);
  EXPECT_FALSE(estop.start || estop.jog || estop.override_feed || estop.resume);

  ControlView lost = view(S::Idle);
  lost.linked = false;
  const ControlsEnabled none = controls_enabled(lost);
  EXPECT_FALSE(none.start || none.jog || none.reset || none.override_feed || none.stop);
}

shm::Event event(std::uint16_t code, shm::Severity sev, const char* text) {
  shm::Event e;
  e.code = code;
  e.severity = sev;
  std::strncpy(e.text, text, sizeof e.text - 1);
  return e;
}

TEST(AlarmLog, RepeatsCountOnOneRowAndNeverPushAnEStopOut) {
  AlarmLog log;
  const auto t0 = AlarmLog::Clock::now();
  EXPECT_TRUE(log.add(event(502, shm::Severity::Error, "e-stop: the operator's"), t0));
  for (int i = 0; i < 2000; ++i) {
    char text[64];
    std::snprintf(text, sizeof text, "RT thread woke late by %d.%03d ms", 1 + i % 7, i % 1000);
    log.add(event(0, shm::Severity::Warning, text), t0 + std::chrono::milliseconds(i));
  }
  ASSERT_EQ(log.rows().size(), 2u);
  EXPECT_EQ(log.rows()[0].count, 2000u);
  EXPECT_EQ(log.rows()[0].severity, shm::Severity::Warning);
  EXPECT_EQ(log.rows()[0].last, t0 + std::chrono::milliseconds(1999));
  EXPECT_EQ(log.rows()[0].first, t0);
  EXPECT_EQ(log.rows()[1].code, 502);
  EXPECT_EQ(log.unacknowledged(), 2u);
  // acknowledged: the next repeat starts a row of its own
  log.acknowledge_all();
  EXPECT_EQ(log.unacknowledged(), 0u);
  EXPECT_TRUE(log.add(event(0, shm::Severity::Warning, "RT thread woke late by 9.1 ms"), t0));
  EXPECT_EQ(log.rows().size(), 3u);
  EXPECT_EQ(log.unacknowledged(), 1u);
  // other news is a row of its own
  EXPECT_TRUE(log.add(event(0, shm::Severity::Info, "homed X"), t0));
  EXPECT_TRUE(log.add(event(0, shm::Severity::Info, "homed Y"), t0));
  EXPECT_EQ(log.rows().size(), 5u);
  EXPECT_EQ(log.unacknowledged(), 1u);  // news is not an alarm
}

TEST(AlarmLog, KeepsItsNewestRows) {
  AlarmLog log;
  for (std::size_t i = 0; i < AlarmLog::kMaxRows + 10; ++i)
    log.add(event(0, shm::Severity::Info, i % 2 ? "homed X" : "homed Y"), AlarmLog::Clock::now());
  EXPECT_EQ(log.rows().size(), AlarmLog::kMaxRows);
}

TEST(TimeLeft, FromProgressAndElapsed) {
  EXPECT_FALSE(time_left_s(0.0, 10.0));
  EXPECT_FALSE(time_left_s(0.005, 10.0));  // too early to tell
  ASSERT_TRUE(time_left_s(0.25, 10.0));
  EXPECT_DOUBLE_EQ(*time_left_s(0.25, 10.0), 30.0);
  EXPECT_DOUBLE_EQ(*time_left_s(1.0, 10.0), 0.0);
}

TEST(TouchOff, IsG10L20OfTheCurrentSystem) {
  EXPECT_EQ(touch_off_gcode(0, 0.0), "G10 L20 P0 X0.000000");
  EXPECT_EQ(touch_off_gcode(2, -1.5), "G10 L20 P0 Z-1.500000");
  EXPECT_EQ(work_system_gcode(1), "G55");
  EXPECT_EQ(work_system_gcode(8), "G59.3");
}

}  // namespace
}  // namespace lcnc::hmi
