// Hole program → machine joints; see hole_placement.h.
#include "holes/hole_placement.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "path/segment_geometry.h"

namespace lcnc {

namespace {

// T·ẑ this close to ẑ keeps G17 arcs (a rounding allowance, not a tolerance).
constexpr double kAxisParallel = 1e-12;

}  // namespace

Result<HoleProgram> place_hole(const HoleProgram& program, const FiveAxisKinematics& kin,
                               double chord_tol) {
  if (!(chord_tol > 0.0))
    return make_error(ErrorCode::GcodeBadValue, "hole placement: chord tolerance must be > 0 mm");
  HoleProgram out;
  out.frame = program.frame;
  std::vector<std::size_t> first_of(program.segments.size() + 1, 0);
  for (std::size_t i = 0; i < program.segments.size(); ++i) {
    const Segment& s = program.segments[i];
    first_of[i] = out.segments.size();
    const Eigen::Isometry3d t = kin.tip_to_joints(rotary_of(s.start)) * program.frame;
    const Vec3 axis = t.linear() * Vec3::UnitZ();
    if (s.kind != MotionKind::Arc) {
      Segment q = s;
      q.start = transformed(t, s.start);
      q.end = transformed(t, s.end);
      out.segments.push_back(q);
      continue;
    }
    if (s.plane != Plane::XY)
      return make_error(ErrorCode::Internal, "hole placement: only G17 arcs are generated");
    if ((axis - Vec3::UnitZ()).norm() <= kAxisParallel) {
      Segment q = s;
      q.start = transformed(t, s.start);
      q.end = transformed(t, s.end);
      q.center = t * s.center;
      out.segments.push_back(q);
    } else if (s.start[2] == s.end[2]) {
      Segment q = s;
      q.start = transformed(t, s.start);
      q.end = transformed(t, s.end);
      q.center = t * Vec3(s.center.x(), s.center.y(), s.start[2]);
      q.plane = Plane::Free;
      q.normal = s.clockwise ? Vec3(-axis) : axis;  // Free: counter-clockwise about normal
      out.segments.push_back(q);
    } else {
      // Tilted helix: chords with sag r·(1 − cos(Δφ/2)) ≤ tol.
      Pose prev = s.start;
      for (const Pose& p : arc_chord_ends(s, chord_tol)) {
        Segment q = s;
        q.kind = MotionKind::Linear;
        q.extra_turns = 0;
        q.start = transformed(t, prev);
        q.end = transformed(t, p);
        out.segments.push_back(q);
        prev = p;
      }
    }
  }
  first_of[program.segments.size()] = out.segments.size();
  out.events = program.events;
  for (HoleEvent& e : out.events)
    e.before_segment = first_of[std::min(e.before_segment, program.segments.size())];
  return out;
}

}  // namespace lcnc
