// A G-code program as the planner reads it (docs/design.md §2): the ProgramReader's
// segments, through the tool-centre-point expander when the machine config
// has [kinematics] tcp = true (kinematics/tcp_program.h). `start` is always
// in joints (where the machine stands); under TCP the program starts at the
// tip there. The planner thread, the pre-run check and the report's
// reference reading all open the program this way, so they see the same
// motion.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "common/result.h"
#include "gcode/program_reader.h"
#include "kinematics/tcp_program.h"
#include "machine/machine_config.h"
#include "plan/planned_segment.h"

namespace lcnc {

// A ProgramReader as a pull source (the reader must outlive it).
[[nodiscard]] SegmentSource reader_source(ProgramReader& reader);

class ProgramSource {
 public:
  [[nodiscard]] static Result<std::unique_ptr<ProgramSource>> open(const std::string& path,
                                                                   const MachineConfig& machine,
                                                                   ReaderOptions options);
  [[nodiscard]] SourceStatus next(Segment& out);
  // After Error: the reader's or the expander's diagnostic, with the file.
  [[nodiscard]] Diagnostic error() const;
  // The reader's warnings so far (lines after the end; after End, a
  // parameter file that could not be written).
  [[nodiscard]] const std::vector<Diagnostic>& warnings() const { return reader_->warnings(); }
  // A pull source over this object (which must outlive it).
  [[nodiscard]] SegmentSource source() {
    return [this](Segment& out) { return next(out); };
  }

 private:
  ProgramSource() = default;
  std::string path_;
  std::unique_ptr<ProgramReader> reader_;
  std::optional<TcpExpander> tcp_;
};

// check_program, and under TCP the joint motion too: every position the
// joints reach within the travel (the reader checks the tip's coordinates,
// which under TCP are not the joints'); the summary's lengths are then the
// joints'.
[[nodiscard]] Result<ProgramSummary> check_job_program(const std::string& path, const MachineConfig& machine,
                                                       const ReaderOptions& options = {});

// Under tool-centre-point control, the program as written: the tool tip's
// path, read from joints options.start. A run measures the executed tip
// (forward kinematics of the joints) against it.
[[nodiscard]] Result<std::unique_ptr<ProgramReader>> open_tip_program(const std::string& path,
                                                                      const MachineConfig& machine,
                                                                      ReaderOptions options = {});

// How far a point may be off the programmed path from its rounding to steps
// alone: half a step on each of X Y Z.
[[nodiscard]] double xyz_rounding_mm(const MachineConfig& machine);
// The same for the tool tip: X Y Z's, plus half a step of A and of C turning
// the tip about their axes (tip_lever_mm).
[[nodiscard]] double tip_rounding_mm(const MachineConfig& machine);

}  // namespace lcnc
