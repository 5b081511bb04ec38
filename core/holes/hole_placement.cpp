// Hole program → machine joints; see hole_placement.h.
#include "holes/hole_placement.h"

#include <algorithm>
#include <vector>

namespace lcnc {

namespace {

// T·ẑ this close to ẑ keeps G17 arcs (a rounding allowance, not a tolerance).
constexpr double kAxisParallel = 1e-12;

}  // namespace

Result<HoleProgram> place_hole(const HoleProgram& program, const FiveAxisKinematics& kin) {
  HoleProgram out;
  out.frame = program.frame;
  out.segments.reserve(program.segments.size());
  std::vector<std::size_t> first_of(program.segments.size() + 1, 0);
  for (std::size_t i = 0; i < program.segments.size(); ++i) {
    const Segment& s = program.segments[i];
    first_of[i] = out.segments.size();
    const Eigen::Isometry3d t = kin.tip_to_joints(rotary_of(s.start)) * program.frame;
    Segment q = s;
    q.start = transformed(t, s.start);
    q.end = transformed(t, s.end);
    if (s.kind == MotionKind::Arc) {
      if (s.plane != Plane::XY)
        return make_error(ErrorCode::Internal, "hole placement: only G17 arcs are generated");
      // the centre in the start's plane (a helix rises from there)
      q.center = t * Vec3(s.center.x(), s.center.y(), s.start[2]);
      const Vec3 axis = t.linear() * Vec3::UnitZ();
      if ((axis - Vec3::UnitZ()).norm() > kAxisParallel) {
        q.plane = Plane::Free;
        q.normal = s.clockwise ? Vec3(-axis) : axis;  // Free: counter-clockwise about normal
        q.clockwise = false;
      }
    }
    out.segments.push_back(q);
  }
  first_of[program.segments.size()] = out.segments.size();
  out.events = program.events;
  for (HoleEvent& e : out.events)
    e.before_segment = first_of[std::min(e.before_segment, program.segments.size())];
  return out;
}

}  // namespace lcnc
