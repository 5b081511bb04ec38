// Tool-centre-point control of G-code programs (docs/design.md §5.6, Shao (2022) §4):
// with the machine config's [kinematics] tcp = true, a program's X Y Z are
// the tool tip in the workpiece frame and A C the rotary joints, and this
// stage of the planner's input turns each programmed move into joint moves:
//
// * a line (G0 or G1) whose A or C changes: the tip runs the programmed
//   line while the tool axis follows the configured orientation
//   interpolator (joint-linear, vector, or pole-smoothed through A = 0),
//   split into joint-space lines within tip_tolerance_mm and
//   orientation_tolerance_deg (tcp_path.h);
// * a line or arc at constant A and C: the rigid map tip → joints at that
//   orientation (FiveAxisKinematics::tip_to_joints); a pure translation (a
//   head-head machine) keeps arcs as arcs in their plane, a rotation (a
//   table-table machine) turns them into chords within tip_tolerance_mm;
// * a dwell: in place. An arc along which A or C moves is an error (split it
//   into lines), as is a move no interpolator can follow within the
//   tolerances (a C jump through the pole with the vector method).
//
// The joints start where the machine stands; the program's start position is
// the tip there (tip_start()). Errors name the program line.
#pragma once

#include <deque>

#include "common/result.h"
#include "kinematics/five_axis.h"
#include "kinematics/five_axis_geometry.h"
#include "path/segment.h"
#include "plan/planned_segment.h"

namespace lcnc {

class TcpExpander {
 public:
  // `source` reads the program from tip_start(kin, start_joints).
  TcpExpander(const FiveAxisKinematics& kin, const TcpConfig& config, SegmentSource source,
              const Pose& start_joints);

  // The next joint-space segment.
  [[nodiscard]] SourceStatus next(Segment& out);
  // Why next() said Error: this stage's own error, or none (then ask the
  // source).
  [[nodiscard]] const std::optional<Diagnostic>& error() const noexcept { return error_; }

  // The tip pose (X Y Z tip, A B C joints) of the machine at these joints:
  // where a TCP program starts.
  [[nodiscard]] static Pose tip_start(const FiveAxisKinematics& kin, const Pose& joints);

 private:
  [[nodiscard]] Status expand(const Segment& s);
  void queue_joint_move(Segment q);

  FiveAxisKinematics kin_;
  TcpConfig config_;
  SegmentSource source_;
  Pose at_;  // joints after the last emitted segment
  std::deque<Segment> queue_;
  std::optional<Diagnostic> error_;
  bool done_ = false;
  SourceStatus end_status_ = SourceStatus::End;
};

}  // namespace lcnc
