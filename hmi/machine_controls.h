// The machine screen's logic, Qt-free: which controls the machine's state
// allows (a cycle start while running, a jog during a hold: never offered),
// the alarm log (severity, wall-clock time, repeats counted on one row,
// acknowledged by the operator), the time a job has left, and the G-code the
// touch-off and work-system buttons send as MDI.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "rt/shm_interface.h"

namespace lcnc::hmi {

// What the screen knows of the controller.
struct ControlView {
  bool linked = false;
  shm::MachineState state = shm::MachineState::Idle;
  bool job_active = false;  // a job (program, MDI, framing) is planned or running
  bool program_loaded = false;
  bool program_pause = false;  // held at M0/M1/M60 or a single-block stop
};

// The controls the state allows. E-stop is always allowed.
struct ControlsEnabled {
  bool start = false, hold = false, resume = false, stop = false, reset = false;
  bool jog = false, home = false, mdi = false, touch_off = false, frame = false;
  bool override_feed = false;
};
[[nodiscard]] ControlsEnabled controls_enabled(const ControlView& v) noexcept;

// The alarm and event list: newest first. An event like the newest row of
// the same key (its code and its text with the numbers left out: "RT
// thread woke late by 2.9 ms" and "… 3.1 ms" are one) and not yet
// acknowledged adds to that row's count instead of a row of its own, so a
// repeated warning never floods the list nor pushes an e-stop out of it.
class AlarmLog {
 public:
  using Clock = std::chrono::system_clock;
  struct Row {
    Clock::time_point first, last;  // wall clock
    std::uint16_t code = 0;
    shm::Severity severity = shm::Severity::Info;
    std::uint32_t line = 0;
    std::string text;  // the latest's
    std::uint32_t count = 1;
    bool acknowledged = false;
    std::string key;
  };
  static constexpr std::size_t kMaxRows = 500;

  // Adds `e` (or counts it on its row); true when a row was added.
  bool add(const shm::Event& e, Clock::time_point now);
  void acknowledge_all() noexcept;
  void clear() noexcept { rows_.clear(); }
  [[nodiscard]] const std::deque<Row>& rows() const noexcept { return rows_; }
  // Errors and warnings not yet acknowledged.
  [[nodiscard]] std::size_t unacknowledged() const noexcept;

 private:
  std::deque<Row> rows_;
};

// A job's time left from its progress (0 … 1) and the time it has run;
// nothing until there is progress to tell it from.
[[nodiscard]] std::optional<double> time_left_s(double progress, double elapsed_s) noexcept;

// Touch-off: the current work system's origin set so that here reads
// `value` on `axis` (G10 L20 P0), in the units MDI is in (G20/G21).
[[nodiscard]] std::string touch_off_gcode(int axis, double value);
// Selects work system `index` (0 = G54 … 8 = G59.3: kWorkOffsetNames).
[[nodiscard]] std::string work_system_gcode(int index);
[[nodiscard]] const char* work_system_name(int index) noexcept;

}  // namespace lcnc::hmi
