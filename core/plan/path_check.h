// The executed path held to the programmed one, as a run's own check holds
// it (`lasercnc run`, `drill`, the daemon's jobs): the joints' X Y Z against
// the segments the planner was given (DeviationMeter, by segment), and under
// tool-centre-point control the tool tip — forward kinematics of the
// executed joints — against the program as written (by program line),
// within P plus the TCP tip tolerance and the rounding of A and C to steps.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/result.h"
#include "gcode/program_reader.h"
#include "kinematics/five_axis.h"
#include "machine/machine_config.h"
#include "path/deviation_meter.h"
#include "plan/program_source.h"

namespace lcnc {

class PathCheck {
 public:
  // A G-code program, read again from joints options.start (the run's own
  // reading is the planner's).
  [[nodiscard]] static Result<std::unique_ptr<PathCheck>> for_program(const std::string& path,
                                                                      const MachineConfig& machine,
                                                                      const ReaderOptions& options);
  // Joint segments as given (a drilling job): the joints only.
  [[nodiscard]] static std::unique_ptr<PathCheck> for_segments(
      std::shared_ptr<const std::vector<Segment>> segments, const MachineConfig& machine);

  // One executed pose (joints, mm and deg) of the segment and line the RT
  // was running.
  void add(const Pose& joints, std::uint32_t segment, std::uint32_t line);

  // Where the segment of the last pose added ends (joints X Y Z, mm): the
  // distance to go is that less the position. Nothing before a pose.
  [[nodiscard]] std::optional<Vec3> segment_end(std::uint32_t segment) const {
    return joints_->end_of(segment);
  }

  // The largest deviation: the tool tip's under TCP, else the joints'.
  [[nodiscard]] double max_mm() const noexcept;
  // One line per tolerance exceeded, e.g. "path deviation 0.0712 mm, beyond
  // its tolerance 0.0500 mm at line 12" ("tool tip deviation" for the tip).
  [[nodiscard]] std::vector<std::string> breaches() const;

 private:
  PathCheck() = default;

  std::unique_ptr<ProgramSource> joints_source_;          // a program's
  std::shared_ptr<const std::vector<Segment>> segments_;  // or a job's segments
  std::size_t next_segment_ = 0;
  std::unique_ptr<ProgramReader> tip_reader_;  // under TCP
  std::optional<FiveAxisKinematics> kin_;
  std::optional<DeviationMeter> joints_;
  std::optional<DeviationMeter> tip_;
};

}  // namespace lcnc
