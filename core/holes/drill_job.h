// A drilling job: the rows of a hole table turned into one motion program in
// machine joints (docs/design.md §6, Shao (2022) §4) that the planner runs like G-code.
//
// Per hole, in table order:
//   travel   rapid from where the machine is to the clearance point, on the
//            hole axis clearance_mm above the surface (A and C turn to the
//            hole's on the way);
//   settle   a dwell of head_settle_s there: the four-beam head takes the
//            hole's parameter block (fields 12–17) while the machine stands
//            — the moment a run writes it (DrillStep::head_segment);
//   approach rapid down the axis to the surface;
//   the hole the process of field 18 (hole_processes.h: laser on at the
//            row's power on its cutting moves, off on rapids), placed at the
//            hole's A and C (hole_placement.h);
//   retract  rapid straight up the hole's wall, parallel to its axis, to the
//            clearance height (beside the clearance point by the pattern's
//            end radius); the next travel starts there.
// Every segment carries the hole number as its line, so errors and the
// report name holes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/result.h"
#include "gcode/program_reader.h"
#include "holes/hole_processes.h"
#include "kinematics/five_axis.h"
#include "machine/machine_config.h"

namespace lcnc {

struct DrillOptions {
  double clearance_mm = 5.0;   // above the surface, along the tool axis
  double head_settle_s = 0.2;  // dwell while the head takes its block
};

struct DrillStep {
  std::uint32_t hole_number = 0;
  std::size_t first_segment = 0;  // the travel rapid
  std::size_t head_segment = 0;   // the settle dwell
  std::size_t end_segment = 0;    // one past the retract
  ScanHeadParams head{};
  double power_pct = 0.0;
};

struct DrillJob {
  std::vector<Segment> segments;  // machine joints X Y Z A (B) C
  std::vector<DrillStep> holes;
};

// The holes' moments as the job runs, from the segment the kernel is on:
// a hole starts at its travel rapid, its head block is due at its settle
// dwell, it ends where the next starts (the last: at the job's end, finish()).
// The segment is seen when a thread looks, so segments pass unseen: every
// moment up to the one seen is handed out, in order, none twice, none
// skipped — a hole whose dwell passed unseen still gets its head block.
struct DrillMoment {
  enum class Kind : std::uint8_t { Start, Head, End };
  Kind kind;
  std::size_t hole;  // index into DrillJob::holes
};

class DrillProgress {
 public:
  explicit DrillProgress(const std::vector<DrillStep>& holes) : holes_(holes) {}
  // The moments reached by `segment` since the last call.
  [[nodiscard]] std::vector<DrillMoment> advance(std::size_t segment);
  // The job has ended: the moments still due (the last hole's head and end).
  [[nodiscard]] std::vector<DrillMoment> finish();

 private:
  void close_current(std::vector<DrillMoment>& out);
  const std::vector<DrillStep>& holes_;
  std::size_t next_ = 0;  // the hole whose start is awaited
  bool has_current_ = false, head_done_ = false;
  std::size_t current_ = 0;
};

// `start`: where the machine stands (joints). Errors name the hole.
[[nodiscard]] Result<DrillJob> build_drill_job(const std::vector<HoleProcessParams>& rows,
                                               const FiveAxisKinematics& kin, const Pose& start,
                                               const DrillOptions& options = {});

// What check_program says of a G-code program, for a drilling job: lines =
// holes, lengths, bounds; every position reached (arcs sampled along their
// length) within the machine's travel, else GcodeBeyondTravel naming the
// hole and the axis. Nothing runs before this passes.
[[nodiscard]] Result<ProgramSummary> check_drill_job(const DrillJob& job, const MachineConfig& machine,
                                                     const std::string& name);

// A hole table file made into a checked drilling job from `start`: read
// (hole_table.h: file:line:col), built, checked against the travel — an
// error about a hole points at its row (file:line). What `lasercnc drill`
// and the daemon's load of a .csv do.
struct PreparedDrill {
  std::vector<HoleProcessParams> rows;
  std::vector<std::uint32_t> row_lines;  // the file line of each row
  DrillJob job;
  ProgramSummary summary;
};
[[nodiscard]] Result<PreparedDrill> prepare_drill_job(const std::string& table, const MachineConfig& machine,
                                                      const Pose& start, const DrillOptions& options = {});

}  // namespace lcnc
