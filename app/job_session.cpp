#include "app/job_session.h"

#include <utility>

namespace lcnc::app {

JobSource JobSource::program(std::string path, ReaderOptions options) {
  JobSource s;
  s.name_ = std::move(path);
  s.options_ = std::move(options);
  return s;
}

JobSource JobSource::segments(std::shared_ptr<const std::vector<Segment>> segments, std::string name,
                              const Pose& start) {
  JobSource s;
  s.name_ = std::move(name);
  s.options_.start = start;
  s.segments_ = std::move(segments);
  return s;
}

void JobSource::start(PlannerFeed& feed) const {
  if (segments_) {
    feed.start(segments_, options_.start, name_);
    return;
  }
  ReaderOptions job = options_;
  job.keep_parameters = true;  // what it sets outlives it (machine.parameter_file)
  feed.start(name_, job);
}

Result<std::unique_ptr<PathCheck>> JobSource::path_check(const MachineConfig& machine) const {
  if (segments_) return PathCheck::for_segments(segments_, machine);
  return PathCheck::for_program(name_, machine, options_);
}

JobCheck::JobCheck(const MachineConfig& machine, std::unique_ptr<PathCheck> path,
                   const std::array<std::int64_t, kAxisCount>& at, std::int64_t t0_ns,
                   std::uint64_t next_period)
    : machine_(machine),
      path_(std::move(path)),
      motion_(machine, at),
      t0_ns_(t0_ns),
      next_period_(next_period) {}

void JobCheck::add(const rt::TraceRecord& r) {
  if (r.t_ns > t0_ns_) {
    if (r.period != next_period_) motion_.gap();
    motion_.add(r.t_ns - t0_ns_, r.pos_steps, r.line);
    if (r.on_path) {  // (idle and underrun periods hold a position of no segment)
      Pose p = Pose::Zero();
      for (int i = 0; i < kAxisCount; ++i)
        if (machine_.axes[i].present)
          p[i] = static_cast<double>(r.pos_steps[i]) / machine_.axes[i].steps_per_unit;
      path_->add(p, r.segment, r.line);
    }
  }
  next_period_ = r.period + 1;
}

std::vector<std::string> JobCheck::breaches() const {
  std::vector<std::string> out = motion_.breaches();
  for (std::string& b : path_->breaches()) out.push_back(std::move(b));
  return out;
}

JobSession::JobSession(const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& start_steps,
                       std::uint8_t inputs_high, float adaptive_feed)
    : buffer_(std::make_unique<rt::PositionBuffer>()),
      trace_(std::make_unique<rt::TraceRing>()),
      rt_log_(std::make_unique<rt::RtLogRing>()),
      sim_(std::make_unique<drivers::SimMachine>(start_steps)) {
  sim_->set_digital_inputs(inputs_high);
  sim_->set_adaptive_feed(adaptive_feed);
  kernel_ = std::make_unique<rt::RtKernel>(machine, *buffer_, *sim_, trace_.get(), start_steps);
  kernel_->set_log(rt_log_.get());
  feed_ = std::make_unique<PlannerFeed>(machine, *buffer_, *kernel_);
}

Status JobSession::link_laser(bool devices, const std::optional<drivers::Endpoint>& laser,
                              const std::optional<drivers::Endpoint>& power_meter) {
  Result<std::unique_ptr<LaserLink>> link =
      devices ? LaserLink::simulated() : LaserLink::connect(*laser, power_meter);
  if (!link) return link.error();
  laser_ = std::move(link).value();
  return laser_->enable();  // failed: the link's destructor switches emission off
}

void JobSession::start(const JobSource& source, double k, bool realtime, rt::RtClock clock,
                       std::uint64_t pause_periods) {
  // The override first: one above 100 % is planned for from the first entry.
  kernel_->set_feed_override(k);
  source.start(*feed_);
  feed_->wait_prefilled();
  rt::RtOptions rt_options;
  // a thread that never sleeps must not hold a core at SCHED_FIFO
  rt_options.try_realtime = realtime && clock == rt::RtClock::Wall;
  rt_options.clock = clock;
  rt_options.program_pause_periods = pause_periods;
  kernel_->start(rt_options);
}

}  // namespace lcnc::app
