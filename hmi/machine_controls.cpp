#include "hmi/machine_controls.h"

#include <cctype>
#include <cstdio>

#include "geom/pose.h"
#include "machine/machine_config.h"

namespace lcnc::hmi {

ControlsEnabled controls_enabled(const ControlView& v) noexcept {
  ControlsEnabled c;
  if (!v.linked) return c;
  using S = shm::MachineState;
  const bool at_rest = v.state == S::Idle && !v.job_active;
  c.start = at_rest && v.program_loaded;
  c.frame = c.start;
  c.jog = c.home = c.mdi = c.touch_off = at_rest;
  c.hold = v.state == S::Running;
  c.resume = v.state == S::FeedHold;
  c.stop = v.job_active || v.state == S::Running || v.state == S::FeedHold || v.state == S::Jog ||
           v.state == S::Homing;
  c.reset = v.state == S::EStop;
  c.override_feed = v.state != S::EStop;
  return c;
}

namespace {

// The event's key: its code and its text with every number as '#'.
std::string key_of(const shm::Event& e) {
  std::string k = std::to_string(e.code) + ':';
  bool in_number = false;
  for (const char ch : std::string_view(e.text)) {
    const bool digit = std::isdigit(static_cast<unsigned char>(ch)) != 0 || (in_number && ch == '.');
    if (digit && !in_number) k += '#';
    if (!digit) k += ch;
    in_number = digit;
  }
  return k;
}

}  // namespace

bool AlarmLog::add(const shm::Event& e, Clock::time_point now) {
  const std::string key = key_of(e);
  if (!rows_.empty() && !rows_.front().acknowledged && rows_.front().key == key) {
    Row& r = rows_.front();
    ++r.count;
    r.last = now;
    r.line = e.line;
    r.text = e.text;
    return false;
  }
  Row r;
  r.first = r.last = now;
  r.code = e.code;
  r.severity = e.severity;
  r.line = e.line;
  r.text = e.text;
  r.key = key;
  rows_.push_front(std::move(r));
  while (rows_.size() > kMaxRows) rows_.pop_back();
  return true;
}

void AlarmLog::acknowledge_all() noexcept {
  for (Row& r : rows_) r.acknowledged = true;
}

std::size_t AlarmLog::unacknowledged() const noexcept {
  std::size_t n = 0;
  for (const Row& r : rows_)
    if (!r.acknowledged && r.severity != shm::Severity::Info) ++n;
  return n;
}

std::optional<double> time_left_s(double progress, double elapsed_s) noexcept {
  if (!(progress > 0.01) || !(elapsed_s > 0.0) || progress > 1.0) return std::nullopt;
  return elapsed_s * (1.0 - progress) / progress;
}

std::string touch_off_gcode(int axis, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "G10 L20 P0 %c%.6f", kAxisLetters[axis < 0 || axis >= kAxisCount ? 0 : axis],
                value);
  return buf;
}

const char* work_system_name(int index) noexcept {
  return kWorkOffsetNames[static_cast<std::size_t>(index >= 0 && index < kWorkOffsetCount ? index : 0)];
}

std::string work_system_gcode(int index) { return work_system_name(index); }

}  // namespace lcnc::hmi
