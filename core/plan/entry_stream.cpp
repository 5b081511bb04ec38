#include "plan/entry_stream.h"

namespace lcnc {
namespace {

std::array<std::int64_t, kAxisCount> steps_of(const StepQuantizer& q) {
  std::array<std::int64_t, kAxisCount> s{};
  for (int i = 0; i < kAxisCount; ++i) s[i] = q.commanded(i);
  return s;
}

}  // namespace

EntryStream::EntryStream(const MachineConfig& machine, Planner& planner, const Pose& start)
    : planner_(planner),
      quant_(machine, start),
      room_(machine, start),
      start_(steps_of(quant_)),
      guard_(machine, start_) {
  last_.pose = start;
}

EntryStream::Next EntryStream::hand_out(PeriodIncrement inc, PeriodIncrement& out) {
  inc.ramp = room_.next(last_.pose);
  if (!guard_.admit(inc)) {
    refused_ = true;
    return Next::Limit;
  }
  out = inc;
  ++entries_;
  return Next::Entry;
}

EntryStream::Next EntryStream::next(PeriodIncrement& out) {
  if (refused_) return Next::Limit;
  if (stage_ == Stage::Planning) {
    PeriodSample s;
    const SourceStatus st = planner_.next(s);
    if (st == SourceStatus::Item) {
      last_ = s;
      return hand_out(quant_.quantize(s), out);
    }
    planned_end_ = st == SourceStatus::Error ? Next::Error : Next::End;
    stage_ = Stage::Paying;
  }
  if (stage_ == Stage::Paying) {
    if (quant_.owed()) return hand_out(quant_.pay_owed(last_), out);
    stage_ = Stage::Done;
    if (entries_ == 0) {
      PeriodIncrement end;  // nothing moved: a controlled end, laser off
      end.end_of_program = true;
      return hand_out(end, out);
    }
  }
  return planned_end_;
}

}  // namespace lcnc
