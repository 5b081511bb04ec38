#include "hmi/toolpath.h"

#include <cmath>

#include "kinematics/five_axis.h"
#include "plan/planner.h"
#include "plan/program_source.h"

namespace lcnc::hmi {
namespace {
const double kMinTurnCos = std::cos(kMinTurnDeg * 3.14159265358979323846 / 180.0);
}  // namespace

Result<Toolpath> plan_toolpath(const std::string& program, const MachineConfig& machine, const Pose& start,
                               const std::function<void(double)>& progress, const std::atomic<bool>* cancel) {
  ReaderOptions ro;
  ro.start = start;
  Result<ProgramSummary> summary = check_job_program(program, machine, ro);
  if (!summary) return summary.error();
  Result<std::unique_ptr<ProgramSource>> src = ProgramSource::open(program, machine, ro);
  if (!src) return src.error();
  Planner planner(machine, (*src)->source());
  Toolpath tp;
  tp.lines = summary->lines;
  const double vmax = std::max(1e-9, [&] {
    double v = 0;
    for (const AxisConfig& a : machine.axes)
      if (a.present && !is_rotary(a.axis)) v = std::max(v, a.max_velocity);
    return v;
  }());
  PeriodSample s;
  SourceStatus st;
  ToolpathPoint last;
  bool any = false;
  Vec3 prev = start.head<3>();
  while ((st = planner.next(s)) == SourceStatus::Item) {
    const Vec3 at = s.pose.head<3>();
    tp.length_mm += (at - prev).norm();
    prev = at;
    tp.peak_speed = std::max(tp.peak_speed, s.speed);
    tp.time_s = s.t_s;
    ++tp.periods;
    const bool laser = s.power_pct > 0.0f;
    const bool rapid = s.kind == MotionKind::Rapid;
    const Vec3 axis = tool_axis(s.pose[3], s.pose[5]);
    if (!any || (at - last.at).norm() >= kMinStepMm || std::abs(s.speed - last.speed) >= kSpeedStep * vmax ||
        laser != last.laser || rapid != last.rapid || axis.dot(last.axis) < kMinTurnCos || s.end_of_program) {
      last = ToolpathPoint{at, s.speed, laser, rapid, s.line, axis};
      tp.points.push_back(last);
      tp.tilted = tp.tilted || axis.z() < kMinTurnCos;
      any = true;
    }
    if ((tp.periods & 0x3fff) == 0) {
      if (cancel != nullptr && cancel->load()) return make_error(ErrorCode::Internal, "cancelled");
      if (progress && summary->lines > 0)
        progress(std::min(1.0, static_cast<double>(s.line) / summary->lines));
    }
  }
  if (st == SourceStatus::Error) return (*src)->error();
  if (progress) progress(1.0);
  return tp;
}

}  // namespace lcnc::hmi
