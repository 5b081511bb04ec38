#include "holes/drill_job.h"

#include <cmath>

#include "holes/hole_placement.h"
#include "holes/hole_table.h"
#include "path/travel_check.h"

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
    Result<HoleProgram> placed = place_hole(prog, kin);
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
  TravelCheck check(machine, name, "hole");
  for (const Segment& s : job.segments)
    if (Status st = check.add(s); !st) return st.error();
  ProgramSummary sum(check.summary());
  sum.lines = static_cast<std::uint32_t>(job.holes.size());
  return sum;
}

Result<PreparedDrill> prepare_drill_job(const std::string& table, const MachineConfig& machine,
                                        const Pose& start, const DrillOptions& options) {
  PreparedDrill p;
  Result<std::vector<HoleProcessParams>> rows = read_hole_table(table, &p.row_lines);
  if (!rows) return rows.error();
  p.rows = std::move(rows).value();
  Result<DrillJob> job = build_drill_job(p.rows, kinematics_from(machine), start, options);
  if (!job) {
    Diagnostic d = job.error();
    if (d.file.empty()) d.file = table;
    return d;
  }
  p.job = std::move(job).value();
  Result<ProgramSummary> summary = check_drill_job(p.job, machine, table);
  if (!summary) {
    // the job names the hole (its number as the line): point at its row
    Diagnostic d = summary.error();
    for (std::size_t k = 0; k < p.rows.size(); ++k)
      if (p.rows[k].hole_number == d.line) {
        d.line = p.row_lines[k];
        d.col = 1;
        break;
      }
    return d;
  }
  p.summary = *summary;
  p.summary.files = {table};
  return p;
}

std::vector<DrillMoment> DrillProgress::advance(std::size_t segment) {
  std::vector<DrillMoment> out;
  for (;;) {
    if (has_current_ && !head_done_ && segment >= holes_[current_].head_segment) {
      head_done_ = true;
      out.push_back({DrillMoment::Kind::Head, current_});
    }
    if (next_ >= holes_.size() || segment < holes_[next_].first_segment) return out;
    close_current(out);
    current_ = next_++;
    has_current_ = true;
    head_done_ = false;
    out.push_back({DrillMoment::Kind::Start, current_});
  }
}

std::vector<DrillMoment> DrillProgress::finish() {
  std::vector<DrillMoment> out;
  close_current(out);
  return out;
}

void DrillProgress::close_current(std::vector<DrillMoment>& out) {
  if (!has_current_) return;
  if (!head_done_) out.push_back({DrillMoment::Kind::Head, current_});
  out.push_back({DrillMoment::Kind::End, current_});
  has_current_ = false;
  head_done_ = true;
}

}  // namespace lcnc
