// Framing: the loaded program's X Y extents — of its cuts, else of all its
// moves — traced at the Z where the machine stands, with the beam off, at
// half the slower of X's and Y's top speed; then back to where it began. The
// operator sees where the job will cut on the sheet before it does.
#pragma once

#include <string>

#include "gcode/program_reader.h"
#include "machine/machine_config.h"

namespace lcnc::app {

struct Framing {
  std::string program;     // the G-code the daemon runs, in machine coordinates (G53)
  Pose lo = Pose::Zero();  // the rectangle traced: X, Y of lo and hi
  Pose hi = Pose::Zero();
};

// The framing of the program `name` summarized as `sum`, from `here`.
[[nodiscard]] Framing framing_program(const ProgramSummary& sum, const std::string& name, const Pose& here,
                                      const MachineConfig& machine);

}  // namespace lcnc::app
