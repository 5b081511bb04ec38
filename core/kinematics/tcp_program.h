// Tool-centre-point control of G-code programs (docs/design.md §5.6, Shao (2022) §4):
// with the machine config's [kinematics] tcp = true, a program's X Y Z are
// the tool tip in the workpiece frame and A C the rotary joints, and this
// stage of the planner's input turns each programmed move into joint moves:
//
// * a line (G0 or G1): the tip runs the programmed line while the tool axis
//   follows the configured orientation interpolator (joint-linear, vector,
//   or pole-smoothed through A = 0) — or keeps its orientation when A and C
//   are not moved — as one smooth joint path, its curve pieces within
//   tip_tolerance_mm and orientation_tolerance_deg (tcp_path.h). Where two
//   feed lines meet in G64, the corner is rounded in joint space: the end of
//   the one and the start of the next are replaced by one curve piece,
//   tangent to both, whose tip stays within half the corner's P (G64 P, or
//   the machine's path_tolerance_mm) of the programmed corner, the tool
//   axis turning smoothly from the one's orientation to the next's over it;
//   the look-ahead then carries the speed through. (Not where P leaves
//   nothing after what rounding to steps and the jerk filter may add, nor
//   where the joint path reverses: such a corner is run with a stop.) Elsewhere (G61, rapids,
//   a feed change to or from a rapid) the corner stays a corner;
// * an arc at constant A and C: the rigid map tip → joints at that
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
#include <optional>

#include "common/result.h"
#include "kinematics/five_axis.h"
#include "kinematics/five_axis_geometry.h"
#include "kinematics/tcp_path.h"
#include "path/segment.h"
#include "plan/planned_segment.h"

namespace lcnc {

class TcpExpander {
 public:
  // `source` reads the program from tip_start(kin, start_joints);
  // default_corner_mm: a corner's P where G64 gives none (the machine's
  // path_tolerance_mm); corner_margin_mm: what of P the executed path may
  // add to a rounded corner's own deviation (steps, the jerk filter).
  TcpExpander(const FiveAxisKinematics& kin, const TcpConfig& config, SegmentSource source,
              const Pose& start_joints, double default_corner_mm = 0.0, double corner_margin_mm = 0.0);

  // The next joint-space segment.
  [[nodiscard]] SourceStatus next(Segment& out);
  // Why next() said Error: this stage's own error, or none (then ask the
  // source).
  [[nodiscard]] const std::optional<Diagnostic>& error() const noexcept { return error_; }

  // The tip pose (X Y Z tip, A B C joints) of the machine at these joints:
  // where a TCP program starts.
  [[nodiscard]] static Pose tip_start(const FiveAxisKinematics& kin, const Pose& joints);

 private:
  // A programmed line whose end is held back: the next may round its corner.
  struct Held {
    Segment programmed;
    TcpMove move;
    double u_from = 0.0;     // what the last corner left of it
    bool smooth_in = false;  // its first piece continues that corner's
  };

  [[nodiscard]] Status expand(const Segment& s);
  [[nodiscard]] Status expand_line(const Segment& s);
  // Queues the held line's pieces up to u_to and lets it go.
  [[nodiscard]] Status release(double u_to = 1.0);
  // The corner of the held line and `next` rounded (one curve piece queued,
  // the held line's pieces before it), or false when it cannot be within
  // tolerance; *u_next is where `next` goes on from.
  [[nodiscard]] Result<bool> round_corner(const Segment& s, const TcpMove& next, double* u_next);
  void queue_joint_move(Segment q);

  FiveAxisKinematics kin_;
  TcpConfig config_;
  SegmentSource source_;
  double default_corner_mm_;
  double corner_margin_mm_;
  Pose at_;      // joints where the last programmed move ends
  Pose queued_;  // joints after the last queued segment
  std::optional<Held> held_;
  std::deque<Segment> queue_;
  std::optional<Diagnostic> error_;
  bool done_ = false;
  SourceStatus end_status_ = SourceStatus::End;
};

}  // namespace lcnc
