#include "plan/program_source.h"

#include "path/travel_check.h"
#include "plan/tolerance_budget.h"

#include <cmath>
#include <numbers>

namespace lcnc {

SegmentSource reader_source(ProgramReader& reader) {
  return [&reader](Segment& out) {
    switch (reader.next(out)) {
      case ProgramReader::Next::Segment: return SourceStatus::Item;
      case ProgramReader::Next::End: return SourceStatus::End;
      case ProgramReader::Next::Error: return SourceStatus::Error;
    }
    return SourceStatus::Error;
  };
}

Result<std::unique_ptr<ProgramSource>> ProgramSource::open(const std::string& path,
                                                           const MachineConfig& machine,
                                                           ReaderOptions options) {
  std::unique_ptr<ProgramSource> ps(new ProgramSource());
  ps->path_ = path;
  const Pose joints = options.start;
  std::optional<FiveAxisKinematics> kin;
  if (machine.tcp.enabled) {
    kin = kinematics_from(machine);
    options.start = TcpExpander::tip_start(*kin, joints);
  }
  Result<std::unique_ptr<ProgramReader>> reader = ProgramReader::open(path, machine, options);
  if (!reader) return reader.error();
  ps->reader_ = std::move(reader).value();
  if (kin) {
    // a rounded corner keeps within P what rounding to steps and the jerk
    // filter add (plan/tolerance_budget.h)
    const ToleranceBudget budget =
        tolerance_budget(machine, machine.max_jerk > 0.0 ? jerk_filter_budget_mm(machine) : 0.0);
    ps->tcp_.emplace(*kin, machine.tcp, reader_source(*ps->reader_), joints, machine.path_tolerance_mm,
                     budget.quantization_mm + budget.jerk_filter_mm);
  }
  return ps;
}

SourceStatus ProgramSource::next(Segment& out) {
  if (tcp_) return tcp_->next(out);
  switch (reader_->next(out)) {
    case ProgramReader::Next::Segment: return SourceStatus::Item;
    case ProgramReader::Next::End: return SourceStatus::End;
    case ProgramReader::Next::Error: return SourceStatus::Error;
  }
  return SourceStatus::Error;
}

Diagnostic ProgramSource::error() const {
  if (tcp_ && tcp_->error()) {
    Diagnostic d = *tcp_->error();
    d.file = path_;
    return d;
  }
  return reader_->error();
}

Result<ProgramSummary> check_job_program(const std::string& path, const MachineConfig& machine,
                                         const ReaderOptions& options) {
  if (!machine.tcp.enabled) return check_program(path, machine, options);
  ReaderOptions tip = options;
  tip.start = TcpExpander::tip_start(kinematics_from(machine), options.start);
  Result<ProgramSummary> read = check_program(path, machine, tip);
  if (!read) return read;
  Result<std::unique_ptr<ProgramSource>> src = ProgramSource::open(path, machine, options);
  if (!src) return src.error();
  TravelCheck check(machine, path, "line");
  Segment s;
  SourceStatus st;
  while ((st = (*src)->next(s)) == SourceStatus::Item)
    if (Status e = check.add(s); !e) return e.error();
  if (st == SourceStatus::Error) return (*src)->error();
  ProgramSummary sum(check.summary());
  sum.lines = read->lines;
  sum.warnings = read->warnings;
  sum.end = read->end;
  sum.files = read->files;
  sum.feed_min = read->feed_min;  // of the tool tip: what framing shows
  sum.feed_max = read->feed_max;
  return sum;
}

Result<std::unique_ptr<ProgramReader>> open_tip_program(const std::string& path, const MachineConfig& machine,
                                                        ReaderOptions options) {
  if (machine.tcp.enabled) options.start = TcpExpander::tip_start(kinematics_from(machine), options.start);
  return ProgramReader::open(path, machine, options);
}

double xyz_rounding_mm(const MachineConfig& machine) {
  double sq = 0.0;
  for (Axis a : {Axis::X, Axis::Y, Axis::Z}) {
    const AxisConfig& ax = machine.axis(a);
    if (ax.present) sq += 0.25 / (ax.steps_per_unit * ax.steps_per_unit);
  }
  return std::sqrt(sq);
}

double tip_rounding_mm(const MachineConfig& machine) {
  const double lever = tip_lever_mm(machine.kinematics);
  double turn_rad = 0.0;
  for (Axis a : {Axis::A, Axis::C}) {
    const AxisConfig& ax = machine.axis(a);
    if (ax.present) turn_rad += 0.5 / ax.steps_per_unit * std::numbers::pi / 180.0;
  }
  return xyz_rounding_mm(machine) + lever * turn_rad;
}

}  // namespace lcnc
