// Shared fixtures of the G-code front-end tests: the test machine (built in
// code, not loaded from TOML) and helpers that run a program held in a string.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "support/expect_mentions.h"

namespace lcnc::test {

inline Pose pose(double x, double y, double z, double a = 0, double b = 0, double c = 0) {
  Pose p;
  p << x, y, z, a, b, c;
  return p;
}

// X 0..1000, Y 0..450, Z 0..500, A -95..95, B absent, C 0..360 continuous;
// s_max 100; G55 = X+500, G56 = (100, 50, 20, A5).
inline MachineConfig test_machine() {
  MachineConfig m;
  m.name = "gcode-test";
  m.path_tolerance_mm = 0.01;
  m.laser.s_max = 100.0;
  auto set = [&](Axis a, bool present, double min, double max, bool wrap = false) {
    AxisConfig& ax = m.axis(a);
    ax.present = present;
    ax.axis = a;
    ax.min = min;
    ax.max = max;
    ax.max_velocity = 100.0;
    ax.max_acceleration = 1000.0;
    ax.wrap = wrap;
  };
  set(Axis::X, true, 0.0, 1000.0);
  set(Axis::Y, true, 0.0, 450.0);
  set(Axis::Z, true, 0.0, 500.0);
  set(Axis::A, true, -95.0, 95.0);
  set(Axis::B, false, 0.0, 0.0);
  set(Axis::C, true, 0.0, 360.0, true);
  for (auto& w : m.work_offsets) w = Pose::Zero();
  m.work_offsets[1] = pose(500, 0, 0);
  m.work_offsets[2] = pose(100, 50, 20, 5);
  return m;
}

inline ReaderOptions start_at(double x = 10, double y = 10, double z = 10) {
  ReaderOptions o;
  o.start = pose(x, y, z);
  return o;
}

struct Run {
  std::vector<Segment> segments;
  ProgramReader::Next last = ProgramReader::Next::End;
  Diagnostic error;
  std::vector<Diagnostic> warnings;
  std::uint32_t lines = 0;
};

inline Run run(const std::string& text, ReaderOptions options = start_at(),
               const MachineConfig& machine = test_machine()) {
  auto reader = ProgramReader::from_string(text, "test.ngc", machine, options);
  Run r;
  Segment s;
  for (;;) {
    r.last = reader->next(s);
    if (r.last != ProgramReader::Next::Segment) break;
    r.segments.push_back(s);
  }
  if (r.last == ProgramReader::Next::Error) r.error = reader->error();
  r.warnings = reader->warnings();
  r.lines = reader->lines_read();
  return r;
}

// Runs a program that must succeed; fails the test with the diagnostic if not.
inline std::vector<Segment> segments(const std::string& text, ReaderOptions options = start_at(),
                                     const MachineConfig& machine = test_machine()) {
  Run r = run(text, options, machine);
  EXPECT_EQ(r.last, ProgramReader::Next::End) << r.error.to_string();
  return r.segments;
}

// Runs a program that must fail; checks code, line and column.
inline Diagnostic expect_error(const std::string& text, ErrorCode code, std::uint32_t line, std::uint32_t col,
                               ReaderOptions options = start_at(),
                               const MachineConfig& machine = test_machine()) {
  Run r = run(text, options, machine);
  EXPECT_EQ(r.last, ProgramReader::Next::Error) << "program:\n" << text;
  EXPECT_EQ(r.error.code, code) << r.error.to_string();
  EXPECT_EQ(r.error.line, line) << r.error.to_string();
  EXPECT_EQ(r.error.col, col) << r.error.to_string();
  EXPECT_EQ(r.error.file, "test.ngc");
  return r.error;
}

#define EXPECT_POSE_NEAR(actual, expected, tol)                   \
  EXPECT_LT(((actual) - (expected)).cwiseAbs().maxCoeff(), (tol)) \
      << "actual   " << (actual).transpose() << "\nexpected " << (expected).transpose()

#define EXPECT_VEC3_NEAR(actual, expected, tol)                   \
  EXPECT_LT(((actual) - (expected)).cwiseAbs().maxCoeff(), (tol)) \
      << "actual   " << (actual).transpose() << "\nexpected " << (expected).transpose()

}  // namespace lcnc::test
