#include "kinematics/tcp_program.h"

#include <algorithm>
#include <cmath>

#include "kinematics/kinematics_tolerances.h"
#include "kinematics/orientation_interpolation.h"
#include "kinematics/tcp_path.h"
#include "path/segment_geometry.h"

namespace lcnc {
namespace {

// A rotation this close to the identity is a translation (rounding only).
constexpr double kIdentity = 1e-12;

bool rotary_moves(const Segment& s) {
  return s.start[index(Axis::A)] != s.end[index(Axis::A)] || s.start[index(Axis::C)] != s.end[index(Axis::C)];
}

}  // namespace

TcpExpander::TcpExpander(const FiveAxisKinematics& kin, const TcpConfig& config, SegmentSource source,
                         const Pose& start_joints)
    : kin_(kin), config_(config), source_(std::move(source)), at_(start_joints) {}

Pose TcpExpander::tip_start(const FiveAxisKinematics& kin, const Pose& joints) {
  Pose p = joints;
  p.head<3>() = kin.forward(joints).tip_mm;
  return p;
}

void TcpExpander::queue_joint_move(Segment q) {
  q.start = at_;
  at_ = q.end;
  queue_.push_back(q);
}

Status TcpExpander::expand(const Segment& s) {
  const auto fail = [&](const std::string& why) {
    return Status(
        make_error(ErrorCode::GcodeUnsupported, "line " + std::to_string(s.line) + ": " + why, {}, s.line));
  };
  if (s.kind == MotionKind::Dwell) {
    Segment q = s;
    q.end = at_;
    queue_joint_move(q);
    return {};
  }
  // The tool orientation is the program's, the joints that give it are the
  // machine's: (A, C) and (−A, C + 180°) point the tool alike, and the
  // machine stays on the branch (and the turn of C) it stands on. Joint
  // lines between branches would swing the tip off the path.
  const RotaryJoints from = rotary_of(at_);
  if (!rotary_moves(s)) {
    const Eigen::Isometry3d t = kin_.tip_to_joints(from);
    const auto joints = [&](const Pose& tip) {
      Pose j = transformed(t, tip);
      j[index(Axis::A)] = from.a_deg;
      j[index(Axis::C)] = from.c_deg;
      return j;
    };
    const bool translation = (t.linear() - Eigen::Matrix3d::Identity()).norm() <= kIdentity;
    if (s.kind != MotionKind::Arc || translation) {
      Segment q = s;
      q.end = joints(s.end);
      if (s.kind == MotionKind::Arc) q.center = t * s.center;
      queue_joint_move(q);
      return {};
    }
    // a rotated arc: chords within the tip tolerance
    for (const Pose& p : arc_chord_ends(s, config_.tip_tolerance_mm)) {
      Segment q = s;
      q.kind = MotionKind::Linear;
      q.extra_turns = 0;
      q.end = joints(p);
      queue_joint_move(q);
    }
    return {};
  }
  if (s.kind == MotionKind::Arc)
    return fail(
        "an arc along which A or C moves cannot be run under tool-centre-point control; "
        "split it into lines");
  const RotaryJoints written = rotary_of(s.start);
  const double turns = std::round((from.c_deg - written.c_deg) / 360.0);
  Result<OrientationMove> move =
      (from.a_deg == written.a_deg &&
       std::abs(from.c_deg - written.c_deg - 360.0 * turns) <= kin::kSameJointDeg)
          ? OrientationMove::between_joints(
                config_.orientation, from,
                RotaryJoints{s.end[index(Axis::A)], s.end[index(Axis::C)] + 360.0 * turns}, kin_.limits(),
                config_.orientation_tolerance_deg)
          : OrientationMove::to_axis(config_.orientation, from, tool_axis(rotary_of(s.end)), kin_.limits(),
                                     config_.orientation_tolerance_deg);
  if (!move) return fail(move.error().message);
  Result<std::vector<Segment>> pieces =
      tcp_line_segments(kin_, s.start.head<3>(), s.end.head<3>(), *move, s, config_.tip_tolerance_mm,
                        config_.orientation_tolerance_deg);
  if (!pieces) return fail(pieces.error().message);
  // The orientation path may start at another C than the machine's (a move
  // leaving the pole): turn C there first — the orientation does not change.
  if (!pieces->empty() && (pieces->front().start - at_).norm() > 1e-9) {
    Segment turn = pieces->front();
    turn.kind = MotionKind::Rapid;
    turn.laser = LaserMode::Off;
    turn.end = pieces->front().start;
    queue_joint_move(turn);
  }
  for (const Segment& q : *pieces) queue_joint_move(q);
  return {};
}

SourceStatus TcpExpander::next(Segment& out) {
  while (queue_.empty()) {
    if (done_) return end_status_;
    Segment s;
    const SourceStatus st = source_(s);
    if (st != SourceStatus::Item) {
      done_ = true;
      end_status_ = st;
      continue;
    }
    if (Status e = expand(s); !e) {
      error_ = e.error();
      done_ = true;
      end_status_ = SourceStatus::Error;
    }
  }
  out = queue_.front();
  queue_.pop_front();
  return SourceStatus::Item;
}

}  // namespace lcnc
