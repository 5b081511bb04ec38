// Checks motion built in code (a drilling job, a program under
// tool-centre-point control) against the machine's travel before it runs,
// as ProgramReader does for a program's own moves, and sums what
// check_program sums. Every position a segment reaches is checked: its ends,
// and arcs sampled along their length (64 points a turn).
#pragma once

#include <string>

#include "common/result.h"
#include "machine/machine_config.h"
#include "path/motion_summary.h"
#include "path/segment.h"

namespace lcnc {

class TravelCheck {
 public:
  // `what` names the segment's line in messages ("hole", "line"); `file` the program.
  TravelCheck(const MachineConfig& machine, std::string file, std::string what);
  // GcodeBeyondTravel (or GcodeNoSuchAxis) naming the line and the axis.
  [[nodiscard]] Status add(const Segment& s);
  [[nodiscard]] MotionSummary& summary() noexcept { return sum_; }

 private:
  [[nodiscard]] Status reach(const Pose& p, std::uint32_t line);
  const MachineConfig& machine_;
  std::string file_, what_;
  MotionSummary sum_;
  bool first_ = true;
};

}  // namespace lcnc
