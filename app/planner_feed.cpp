#include "app/planner_feed.h"

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>

#include "plan/entry_stream.h"
#include "plan/motion_stats.h"
#include "plan/planner.h"
#include "plan/program_source.h"

namespace lcnc::app {

PlannerFeed::PlannerFeed(const MachineConfig& machine, rt::PositionBuffer& buffer, rt::KernelControl& kernel)
    : machine_(machine), buffer_(buffer), kernel_(kernel) {}

PlannerFeed::~PlannerFeed() { abort(); }

void PlannerFeed::start(const std::string& program, const ReaderOptions& options) {
  launch(program, options.start, [this, program, options](SegmentSource& source, Diagnostic& error) {
    Result<std::unique_ptr<ProgramSource>> src = ProgramSource::open(program, machine_, options);
    if (!src) {
      error = src.error();
      return false;
    }
    program_source_ = std::move(src).value();
    ProgramSource* ps = program_source_.get();
    source = [this, ps](Segment& out) {
      const SourceStatus st = ps->next(out);
      if (st == SourceStatus::Error) source_error_ = ps->error();
      if (st == SourceStatus::End) result_.warnings = ps->warnings();
      return st;
    };
    return true;
  });
}

void PlannerFeed::start(const std::shared_ptr<const std::vector<Segment>>& segments, const Pose& start,
                        const std::string& name) {
  launch(name, start, [segments](SegmentSource& source, Diagnostic&) {
    source = [segments, i = std::size_t{0}](Segment& out) mutable {
      if (i == segments->size()) return SourceStatus::End;
      out = (*segments)[i++];
      return SourceStatus::Item;
    };
    return true;
  });
}

void PlannerFeed::launch(std::string name, const Pose& start, OpenSource open) {
  abort();
  abort_ = false;
  done_ = false;
  stopped_short_ = false;
  result_ = PlannedJob{};
  kernel_.stream_begin();
  thread_ =
      std::thread([this, name = std::move(name), start, open = std::move(open)] { run(name, start, open); });
}

bool PlannerFeed::prefilled() const noexcept {
  return done() || stopped_short() || buffer_.size() >= rt::kPositionBufferCapacity / 2;
}

void PlannerFeed::wait_prefilled() const {
  while (!prefilled()) std::this_thread::sleep_for(std::chrono::microseconds(200));
}

void PlannerFeed::abort() {
  request_abort();
  if (thread_.joinable()) thread_.join();
}

void PlannerFeed::join() {
  if (thread_.joinable()) thread_.join();
}

bool PlannerFeed::push(const PeriodIncrement& inc) {
  // An aborted job plans no further: the kernel discards what it is sent
  // after a stop faster than it can be planned, so the buffer never fills.
  if (abort_.load(std::memory_order_relaxed)) return false;
  while (result_.increments >= stall_after_.load(std::memory_order_relaxed)) {  // fault injection
    if (abort_.load(std::memory_order_relaxed)) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  while (!buffer_.try_push(inc)) {
    if (abort_.load(std::memory_order_relaxed)) return false;
    std::this_thread::sleep_for(std::chrono::nanoseconds(machine_.period_ns * 16));
  }
  ++result_.increments;
  return true;
}

void PlannerFeed::run(const std::string& name, const Pose& start, const OpenSource& open) {
  program_ = name;
  MotionStats stats(machine_.period_s(), start);
  SegmentSource source;
  const bool opened = open(source, result_.error);
  if (!opened) source = [](Segment&) { return SourceStatus::End; };  // no motion: the stream's end entry
  Planner planner(machine_, std::move(source));
  EntryStream stream(machine_, planner, start);
  for (int i = 0; i < kAxisCount; ++i) result_.start_steps[i] = stream.start_steps(i);
  // An override above 100 % is planned for: from the start (the run's
  // --feed-override), and on every raise (what is not yet handed out is
  // planned again). A lower one the RT applies at once by itself.
  planner.set_feed_scale(kernel_.feed_override_target());
  PeriodIncrement inc;
  EntryStream::Next got = EntryStream::Next::End;
  bool pushed = true;
  while (pushed && (got = stream.next(inc)) == EntryStream::Next::Entry) {
    stats.add(stream.pose());
    pushed = push(inc);
    const double asked = kernel_.feed_override_target();
    if (asked > planner.feed_scale() || (asked < planner.feed_scale() && planner.feed_scale() > 1.0))
      planner.set_feed_scale(asked);
  }
  if (!opened) {
    result_.failed = true;
  } else if (pushed && got == EntryStream::Next::Error) {
    // a read error mid-way (the file changed since it was checked): the
    // motion before it was planned to rest and has ended as a job does
    result_.failed = true;
    result_.error = source_error_;
  }
  if (pushed && got == EntryStream::Next::Limit) {
    // Stopped short of a soft limit or an axis limit while the machine may
    // be moving: no end entry, which would stop it dead; the stream stays
    // open, so the kernel brakes along the path with what is queued, until
    // the caller's stop (RtCommandType::Stop) aborts the job.
    result_.limit = true;
    result_.limit_error = stream.limit_error();
    result_.limit_error.file = program_;
    stopped_short_.store(true, std::memory_order_release);
    while (!abort_.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  } else if (!abort_.load()) {
    // A job cut short (stopped, e-stopped) does not end where the plan
    // does: no stop from the last sample to rest belongs to its figures.
    stats.finish();
  }
  for (int i = 0; i < kAxisCount; ++i) result_.commanded[i] = stream.commanded(i);
  result_.peak_v = stats.peak_velocity();
  result_.peak_a = stats.peak_acceleration();
  // release pairs with the kernel's acquire: the last entry is in the buffer
  kernel_.stream_end();
  done_.store(true, std::memory_order_release);
}

}  // namespace lcnc::app
