#include "kinematics/tcp_program.h"

#include <algorithm>
#include <cmath>

#include "kinematics/kinematics_tolerances.h"
#include "kinematics/orientation_interpolation.h"
#include "kinematics/tcp_path.h"
#include "path/path_tolerances.h"
#include "path/segment_geometry.h"

namespace lcnc {
namespace {

// A rotation this close to the identity is a translation (rounding only).
constexpr double kIdentity = 1e-12;
// A rounded corner's tip stays within this share of its P: the rest is the
// pieces' own tip tolerance, the rounding to steps and the jerk filter's.
constexpr double kCornerShare = 0.5;
// A corner takes at most this share of each line (the next corner the rest).
constexpr double kCornerLineShare = 0.5;
// The rounding is tried this many times, halving its reach each time.
constexpr int kCornerHalvings = 30;
// Points of a rounded corner checked against the programmed corner.
constexpr int kCornerChecks = 8;
// Joint paths turning by more than this (cos of the angle between their
// directions at the corner) are not rounded: a curve between nearly
// opposite directions loops; such a corner is a reversal, run with a stop.
constexpr double kMinCornerCos = -0.5;

bool rotary_moves(const Segment& s) {
  return s.start[index(Axis::A)] != s.end[index(Axis::A)] || s.start[index(Axis::C)] != s.end[index(Axis::C)];
}

// Distance from p to the corner a → c → b.
double to_corner(const Vec3& p, const Vec3& a, const Vec3& c, const Vec3& b) {
  return std::min(distance_to_segment(p, a, c), distance_to_segment(p, c, b));
}

}  // namespace

TcpExpander::TcpExpander(const FiveAxisKinematics& kin, const TcpConfig& config, SegmentSource source,
                         const Pose& start_joints, double default_corner_mm, double corner_margin_mm)
    : kin_(kin),
      config_(config),
      source_(std::move(source)),
      default_corner_mm_(default_corner_mm),
      corner_margin_mm_(corner_margin_mm),
      at_(start_joints),
      queued_(start_joints) {}

Pose TcpExpander::tip_start(const FiveAxisKinematics& kin, const Pose& joints) {
  Pose p = joints;
  p.head<3>() = kin.forward(joints).tip_mm;
  return p;
}

void TcpExpander::queue_joint_move(Segment q) {
  q.start = queued_;
  queued_ = q.end;
  queue_.push_back(q);
}

Status TcpExpander::release(double u_to) {
  if (!held_) return {};
  Held h = std::move(*held_);
  held_.reset();
  Result<std::vector<Segment>> pieces = tcp_curve_segments(h.move, h.programmed, config_.tip_tolerance_mm,
                                                           config_.orientation_tolerance_deg, h.u_from, u_to);
  if (!pieces)
    return Status(make_error(ErrorCode::GcodeUnsupported,
                             "line " + std::to_string(h.programmed.line) + ": " + pieces.error().message, {},
                             h.programmed.line));
  for (std::size_t k = 0; k < pieces->size(); ++k) {
    Segment& q = (*pieces)[k];
    if (k == 0) q.smooth_in = h.smooth_in;
    queue_joint_move(q);
  }
  return {};
}

Result<bool> TcpExpander::round_corner(const Segment& s, const TcpMove& next, double* u_next) {
  const Held& h = *held_;
  const Segment& a = h.programmed;
  if (a.path_mode != PathMode::Blend || a.kind != MotionKind::Linear || s.kind != MotionKind::Linear ||
      h.move.length <= 0.0 || next.length <= 0.0)
    return false;
  const double p = a.blend_tolerance_mm > 0.0 ? a.blend_tolerance_mm : default_corner_mm_;
  const double tol = std::min(kCornerShare * p, p - corner_margin_mm_);
  if (!(tol > 0.0)) return false;
  const Pose ta = h.move.rate_at(1.0), tb = next.rate_at(0.0);
  if (ta.dot(tb) < kMinCornerCos * ta.norm() * tb.norm()) return false;
  const Vec3 corner = h.move.b;
  const Vec3 from = h.move.tip_at(h.u_from);
  const Vec3 to = next.b;
  // The reach of the rounding along each line: the same tip distance on
  // both where both tips move, else the same share of each move.
  const double len_a = (h.move.b - h.move.a).norm(), len_b = (next.b - next.a).norm();
  const bool by_tip = len_a > path::kMinSegmentLength && len_b > path::kMinSegmentLength;
  double reach = kCornerLineShare * (by_tip ? std::min((1.0 - h.u_from) * len_a, len_b) : 1.0);
  for (int k = 0; k < kCornerHalvings; ++k, reach *= 0.5) {
    const double da = by_tip ? reach / len_a : reach * (1.0 - h.u_from);
    const double db = by_tip ? reach / len_b : reach;
    const double ua = 1.0 - da;
    Segment q = s;
    q.curve = true;
    q.smooth_in = true;
    q.start = h.move.joints_at(ua);
    q.end = next.joints_at(db);
    q.curve_length = h.move.length * da + next.length * db;
    // It takes as long as the two parts it replaces, each at its own feed
    // (G94) or in its share of its time (G93).
    const auto part_s = [](const Segment& prog, const TcpMove& m, double share) {
      if (prog.duration_s > 0.0) return prog.duration_s * share;
      const double f = m.path_feed(prog.feed_mm_s);
      return f > 0.0 ? m.length * share / f : 0.0;
    };
    const double ta = part_s(a, h.move, da), tb = part_s(s, next, db);
    q.duration_s = 0.0;
    if (a.duration_s > 0.0 || s.duration_s > 0.0) {
      q.duration_s = ta + tb;
    } else if (ta > 0.0 && tb > 0.0) {
      q.feed_mm_s = q.curve_length / (ta + tb);
    }
    q.curve_d_start = h.move.rate_at(ua) * (q.curve_length / h.move.length);
    q.curve_d_end = next.rate_at(db) * (q.curve_length / next.length);
    const SegmentGeometry geo(q);
    bool ok = true;
    for (int j = 1; j < kCornerChecks && ok; ++j)
      ok =
          to_corner(kin_.forward(geo.at(q.curve_length * j / kCornerChecks)).tip_mm, from, corner, to) <= tol;
    if (!ok) continue;
    if (Status st = release(ua); !st) return st.error();
    queue_joint_move(q);
    *u_next = db;
    return true;
  }
  return false;
}

Status TcpExpander::expand_line(const Segment& s) {
  const auto fail = [&](const std::string& why) {
    return Status(
        make_error(ErrorCode::GcodeUnsupported, "line " + std::to_string(s.line) + ": " + why, {}, s.line));
  };
  // The tool orientation is the program's, the joints that give it are the
  // machine's: (A, C) and (−A, C + 180°) point the tool alike, and the
  // machine stays on the branch (and the turn of C) it stands on. Joint
  // moves between branches would swing the tip off the path.
  const RotaryJoints from = rotary_of(at_);
  const RotaryJoints written = rotary_of(s.start);
  const double turns = std::round((from.c_deg - written.c_deg) / 360.0);
  Result<OrientationMove> move =
      !rotary_moves(s) ? OrientationMove::between_joints(OrientationMethod::JointLinear, from, from,
                                                         kin_.limits(), config_.orientation_tolerance_deg)
      : (from.a_deg == written.a_deg &&
         std::abs(from.c_deg - written.c_deg - 360.0 * turns) <= kin::kSameJointDeg)
          ? OrientationMove::between_joints(
                config_.orientation, from,
                RotaryJoints{s.end[index(Axis::A)], s.end[index(Axis::C)] + 360.0 * turns}, kin_.limits(),
                config_.orientation_tolerance_deg)
          : OrientationMove::to_axis(config_.orientation, from, tool_axis(rotary_of(s.end)), kin_.limits(),
                                     config_.orientation_tolerance_deg);
  if (!move) return fail(move.error().message);
  const Vec3 a = s.start.head<3>(), b = s.end.head<3>();
  TcpMove m = TcpMove::make(kin_, a, b, *move);
  const Pose end = m.joints_at(1.0);
  if (m.length <= 0.0) {  // nothing moves (a repeated point)
    if (Status st = release(); !st) return st;
    at_ = end;
    return {};
  }
  double u_from = 0.0;
  bool smooth_in = false;
  bool rounded = false;
  if (held_) {
    Result<bool> r = round_corner(s, m, &u_from);
    if (!r) return r.error();
    rounded = *r;
    smooth_in = rounded;
  }
  if (!rounded) {
    if (Status st = release(); !st) return st;
    // The orientation path may start at another C than the machine's (a
    // move leaving the pole): turn C there first — the orientation does not
    // change.
    const Pose start = m.joints_at(0.0);
    if ((start - queued_).norm() > 1e-9) {
      Segment turn = s;
      turn.kind = MotionKind::Rapid;
      turn.laser = LaserMode::Off;
      turn.curve = false;
      turn.end = start;
      queue_joint_move(turn);
    }
  }
  held_ = Held{s, std::move(m), u_from, smooth_in};
  at_ = end;
  return {};
}

Status TcpExpander::expand(const Segment& s) {
  if (s.kind == MotionKind::Linear || s.kind == MotionKind::Rapid) return expand_line(s);
  if (Status st = release(); !st) return st;
  if (s.kind == MotionKind::Dwell) {
    Segment q = s;
    q.end = at_;
    queue_joint_move(q);
    return {};
  }
  if (rotary_moves(s))
    return Status(make_error(ErrorCode::GcodeUnsupported,
                             "line " + std::to_string(s.line) +
                                 ": an arc along which A or C moves cannot be run under tool-centre-point "
                                 "control; split it into lines",
                             {}, s.line));
  const RotaryJoints from = rotary_of(at_);
  const Eigen::Isometry3d t = kin_.tip_to_joints(from);
  const auto joints = [&](const Pose& tip) {
    Pose j = transformed(t, tip);
    j[index(Axis::A)] = from.a_deg;
    j[index(Axis::C)] = from.c_deg;
    return j;
  };
  const bool translation = (t.linear() - Eigen::Matrix3d::Identity()).norm() <= kIdentity;
  if (translation) {
    Segment q = s;
    q.end = joints(s.end);
    q.center = t * s.center;
    queue_joint_move(q);
  } else {
    // a rotated arc: chords within the tip tolerance
    for (const Pose& p : arc_chord_ends(s, config_.tip_tolerance_mm)) {
      Segment q = s;
      q.kind = MotionKind::Linear;
      q.extra_turns = 0;
      q.end = joints(p);
      queue_joint_move(q);
    }
  }
  at_ = queued_;
  return {};
}

SourceStatus TcpExpander::next(Segment& out) {
  while (queue_.empty()) {
    if (done_) return end_status_;
    Segment s;
    const SourceStatus st = source_(s);
    if (st != SourceStatus::Item) {
      if (Status e = release(); !e) {
        error_ = e.error();
        done_ = true;
        end_status_ = SourceStatus::Error;
        continue;
      }
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
