#include "holes/drill_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "holes/hole_placement.h"
#include "path/segment_geometry.h"

namespace lcnc {
namespace {

Segment rapid(const Pose& from, const Pose& to, std::uint32_t line) {
  Segment s;
  s.kind = MotionKind::Rapid;
  s.start = from;
  s.end = to;
  s.line = line;
  return s;
}

}  // namespace

Result<DrillJob> build_drill_job(const std::vector<HoleProcessParams>& rows, const FiveAxisKinematics& kin,
                                 const Pose& start, const DrillOptions& options) {
  if (!(options.clearance_mm >= 0.0 && std::isfinite(options.clearance_mm)) ||
      !(options.head_settle_s >= 0.0 && std::isfinite(options.head_settle_s)))
    return make_error(ErrorCode::Usage, "drill: clearance and head settle time must be ≥ 0");
  DrillJob job;
  Pose at = start;
  for (const HoleProcessParams& row : rows) {
    Result<HoleProgram> local = generate_hole(row);
    if (!local) return local.error();
    HoleProgram& prog = *local;
    const std::uint32_t line = row.hole_number;
    // approach from the clearance point, retract to it: in the hole frame,
    // along its axis (+z out of the material)
    Pose above = prog.segments.front().start;
    above[2] = options.clearance_mm;
    Pose retracted = prog.segments.back().end;
    retracted[2] = options.clearance_mm;
    prog.segments.insert(prog.segments.begin(), rapid(above, prog.segments.front().start, line));
    prog.segments.push_back(rapid(prog.segments.back().end, retracted, line));
    for (HoleEvent& e : prog.events) ++e.before_segment;
    Result<HoleProgram> placed = place_hole(prog, kin, options.chord_tolerance_mm);
    if (!placed) return placed.error();

    DrillStep step;
    step.hole_number = line;
    step.head = row.head;
    step.power_pct = row.power_pct;
    step.first_segment = job.segments.size();
    const Pose clearance = placed->segments.front().start;
    job.segments.push_back(rapid(at, clearance, line));
    Segment settle;
    settle.kind = MotionKind::Dwell;
    settle.start = settle.end = clearance;
    settle.dwell_s = options.head_settle_s;
    settle.line = line;
    step.head_segment = job.segments.size();
    job.segments.push_back(settle);
    for (const Segment& s : placed->segments) job.segments.push_back(s);
    step.end_segment = job.segments.size();
    at = job.segments.back().end;
    job.holes.push_back(step);
  }
  return job;
}

Result<ProgramSummary> check_drill_job(const DrillJob& job, const MachineConfig& machine,
                                       const std::string& name) {
  ProgramSummary sum;
  sum.lines = static_cast<std::uint32_t>(job.holes.size());
  sum.segments = job.segments.size();
  bool first = true;
  const auto reach = [&](const Pose& p, std::uint32_t hole) -> Status {
    for (int i = 0; i < kAxisCount; ++i) {
      const AxisConfig& ax = machine.axes[i];
      if (!ax.present) {
        if (std::abs(p[i]) > 1e-9) {
          return make_error(ErrorCode::GcodeNoSuchAxis,
                            "hole " + std::to_string(hole) + " needs axis " + kAxisLetters[i] +
                                ", which the machine lacks",
                            name, hole);
        }
        continue;
      }
      if (!ax.wrap && (p[i] < ax.min - 1e-9 || p[i] > ax.max + 1e-9)) {
        char msg[200];
        std::snprintf(msg, sizeof msg, "hole %u: axis %c would reach %.4f, outside its travel %g … %g",
                      hole, kAxisLetters[i], p[i], ax.min, ax.max);
        return make_error(ErrorCode::GcodeBeyondTravel, msg, name, hole);
      }
    }
    sum.min = first ? p : sum.min.cwiseMin(p);
    sum.max = first ? p : sum.max.cwiseMax(p);
    first = false;
    return {};
  };
  for (const Segment& s : job.segments) {
    if (Status st = reach(s.start, s.line); !st) return st.error();
    if (s.kind == MotionKind::Dwell) continue;
    const SegmentGeometry geo(s);
    const double len = geo.length();
    sum.path_length_mm += len;
    if (s.kind != MotionKind::Rapid) sum.feed_length_mm += len;
    if (s.kind == MotionKind::Arc) {
      // a scan circle is small: 64 samples per turn find its extremes
      const int n = 64 * static_cast<int>(1 + s.extra_turns);
      for (int k = 1; k < n; ++k)
        if (Status st = reach(geo.at(len * k / n), s.line); !st) return st.error();
    }
    if (Status st = reach(s.end, s.line); !st) return st.error();
  }
  return sum;
}

}  // namespace lcnc
