#include "plan/path_check.h"

#include <cstdio>
#include <utility>

namespace lcnc {

Result<std::unique_ptr<PathCheck>> PathCheck::for_program(const std::string& path,
                                                          const MachineConfig& machine,
                                                          const ReaderOptions& options) {
  std::unique_ptr<PathCheck> c(new PathCheck());
  Result<std::unique_ptr<ProgramSource>> joints = ProgramSource::open(path, machine, options);
  if (!joints) return joints.error();
  c->joints_source_ = std::move(joints).value();
  c->joints_.emplace(c->joints_source_->source(), machine.path_tolerance_mm, xyz_rounding_mm(machine));
  if (machine.tcp.enabled) {
    Result<std::unique_ptr<ProgramReader>> tips = open_tip_program(path, machine, options);
    if (!tips) return tips.error();
    c->tip_reader_ = std::move(tips).value();
    c->tip_.emplace(reader_source(*c->tip_reader_), machine.path_tolerance_mm, tip_rounding_mm(machine),
                    machine.tcp.tip_tolerance_mm);
    c->kin_.emplace(kinematics_from(machine));
  }
  return c;
}

std::unique_ptr<PathCheck> PathCheck::for_segments(std::shared_ptr<const std::vector<Segment>> segments,
                                                   const MachineConfig& machine) {
  std::unique_ptr<PathCheck> c(new PathCheck());
  c->segments_ = std::move(segments);
  PathCheck* self = c.get();
  c->joints_.emplace(
      [self](Segment& out) {
        if (self->next_segment_ == self->segments_->size()) return SourceStatus::End;
        out = (*self->segments_)[self->next_segment_++];
        return SourceStatus::Item;
      },
      machine.path_tolerance_mm, xyz_rounding_mm(machine));
  return c;
}

void PathCheck::add(const Pose& joints, std::uint32_t segment, std::uint32_t line) {
  joints_->add(joints.head<3>(), segment);
  if (tip_) tip_->add_at_line(kin_->forward(joints).tip_mm, line);
}

double PathCheck::max_mm() const noexcept { return tip_ ? tip_->max_mm() : joints_->max_mm(); }

std::vector<std::string> PathCheck::breaches() const {
  std::vector<std::string> out;
  const auto say = [&](const DeviationMeter& m, const char* what) {
    if (m.excess_mm() <= 0.0) return;
    char msg[200];
    std::snprintf(msg, sizeof msg, "%s %.4f mm, beyond its tolerance %.4f mm at line %u", what,
                  m.excess_tolerance_mm() + m.excess_mm(), m.excess_tolerance_mm(), m.excess_line());
    out.emplace_back(msg);
  };
  say(*joints_, "path deviation");
  if (tip_) say(*tip_, "tool tip deviation");
  return out;
}

}  // namespace lcnc
