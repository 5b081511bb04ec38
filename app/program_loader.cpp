#include "app/program_loader.h"

#include <filesystem>

#include "holes/drill_job.h"
#include "plan/program_source.h"

namespace lcnc::app {

bool is_hole_table(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
}

ReaderOptions reading_of(const ProgramSnapshot& p, ReaderOptions ropt) {
  ropt.program_dir = std::filesystem::path(p.name()).parent_path().string();  // not the copy's
  ropt.file_policy = [access = p.access()](const std::string& path) { return may_read(path, access); };
  return ropt;
}

Result<CheckedJob> check_job(const ProgramSnapshot& p, const MachineConfig& machine, ReaderOptions ropt) {
  ropt = reading_of(p, std::move(ropt));
  CheckedJob out;
  if (!is_hole_table(p.name())) {
    Result<ProgramSummary> s = check_job_program(p.path(), machine, ropt);
    if (!s) return p.rename(s.error());
    out.summary = *s;
    return out;
  }
  Result<PreparedDrill> d = prepare_drill_job(p.path(), machine, ropt.start);
  if (!d) return p.rename(d.error());
  out.summary = d->summary;
  out.drill_segments = std::make_shared<const std::vector<Segment>>(std::move(d->job.segments));
  return out;
}

ProgramLoad::ProgramLoad(const shm::Command& c, const MachineConfig& machine, const Pose& start,
                         std::uint64_t params_gen, FileAccess access)
    : cmd_(c), start_(start), params_gen_(params_gen) {
  SnapshotRequest req;
  req.path = c.text;
  req.access = std::move(access);
  req.hole_table = is_hole_table(req.path);
  req.cancel = &cancel_;
  thread_ = std::thread([this, &machine, req = std::move(req)] {
    Result<std::shared_ptr<const ProgramSnapshot>> snap = ProgramSnapshot::take(req);
    if (!snap) {
      checked_.emplace(snap.error());
    } else {
      snapshot_ = *snap;
      ReaderOptions ropt;
      ropt.start = start_;
      ropt.cancel = &cancel_;
      checked_.emplace(check_job(*snapshot_, machine, ropt));
    }
    done_.store(true, std::memory_order_release);
  });
}

ProgramLoad::~ProgramLoad() {
  cancel();
  join();
}

void ProgramLoad::join() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace lcnc::app
