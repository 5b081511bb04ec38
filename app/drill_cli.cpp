#include "app/drill_cli.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_values.h"
#include "app/json_text.h"
#include "app/run_job.h"
#include "drivers/devices/scan_head_sim.h"
#include "drivers/modbus/modbus_master.h"
#include "drivers/modbus/register_map.h"
#include "holes/drill_job.h"
#include "holes/hole_fields.h"
#include "holes/hole_table.h"

namespace lcnc::app {
namespace {

constexpr const char* kDrillUsage =
    "usage: lasercnc drill HOLES.csv [--machine FILE] [--devices] [--clearance MM] [--settle S]\n"
    "                      [--feed-override PCT] [--trace FILE.csv] [--json] [--[no-]progress]\n"
    "                      [--fast | --no-realtime]\n"
    "  HOLES.csv      the process database's rows, one hole a row (docs/process_guide.md: drilling)\n"
    "  --devices      scanning head, laser source and power meter as simulated Modbus devices\n"
    "  --fast         the simulated clock, as `lasercnc run --fast` (not with --devices)\n"
    "  --clearance    approach and retract height above each hole, mm along the tool axis (5)\n"
    "  --settle       dwell at the clearance point while the head takes its block, s (0.2)\n";

int drill_usage_error(const std::string& msg) {
  return lcnc::app::usage_error("lasercnc drill", msg, kDrillUsage);
}

// What one hole did, for the report.
struct HoleRecord {
  std::uint32_t hole = 0;
  const char* process = "";
  double start_s = -1.0;  // machine time its travel began
  double end_s = -1.0;    // … and its retract ended
  bool head_written = false;
  std::string head_error;
};

// The four-beam head on Modbus: a simulator of its own (--devices). At a
// hole's settle dwell: run 0, the block of fields 12–18, run 1 — queued in
// order on the master's worker, so the job never waits; at the hole's end:
// run 0.
class HeadLink {
 public:
  // `records` outlives the link; its head_written and head_error are written
  // on the master's worker, under the link's mutex.
  static Result<std::unique_ptr<HeadLink>> simulated(std::vector<HoleRecord>& records) {
    Result<drivers::DeviceMap> map = drivers::shipped_device("scan_head");
    if (!map) return map.error();
    std::unique_ptr<HeadLink> h(new HeadLink(records));
    auto sim = drivers::ScanHeadSim::create(*map);
    if (!sim) return sim.error();
    h->sim_ = std::move(sim).value();
    if (Status s = h->sim_->start(); !s) return s.error();
    drivers::MasterConfig c;
    c.endpoint = h->sim_->endpoint();
    h->master_ = std::make_unique<drivers::ModbusMaster>(*map, c);
    if (Status s = h->master_->start(); !s) return s.error();
    return h;
  }
  ~HeadLink() {
    if (master_) master_->stop();
    if (sim_) sim_->stop();
  }
  void begin_hole(const DrillStep& step, std::size_t k) {
    const ScanHeadParams& p = step.head;
    master_->write_async("run", 0, [this, k](const Status& s) { note(k, s); });
    master_->write_block_async(scan_head_block(p), [this, k](const Status& s) {
      note(k, s);
      std::lock_guard lock(mutex_);
      if (s) records_[k].head_written = true;
    });
    master_->write_async("run", 1, [this, k](const Status& s) { note(k, s); });
  }
  void end_hole(std::size_t k) {
    master_->write_async("run", 0, [this, k](const Status& s) { note(k, s); });
  }
  // Waits for the queued requests; the counters.
  drivers::MasterCounters finish() {
    (void)master_->write("run", 0).get();
    master_->stop();
    return master_->counters();
  }
  std::string who() const { return master_->who(); }

 private:
  explicit HeadLink(std::vector<HoleRecord>& records) : records_(records) {}
  void note(std::size_t k, const Status& s) {
    if (s) return;
    std::lock_guard lock(mutex_);
    if (records_[k].head_error.empty()) records_[k].head_error = s.error().message;
  }
  std::unique_ptr<drivers::ScanHeadSim> sim_;
  std::unique_ptr<drivers::ModbusMaster> master_;
  std::mutex mutex_;
  std::vector<HoleRecord>& records_;
};

}  // namespace

int drill_main(int argc, char** argv) {
  RunOptions opt;
  DrillOptions dopt;
  std::string table;
  bool json = false;
  bool show_progress = isatty(STDERR_FILENO) != 0;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::optional<std::string_view> {
      if (i + 1 >= argc) return std::nullopt;
      return std::string_view(argv[++i]);
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kDrillUsage, stdout);
      return 0;
    } else if (a == "--machine" || a == "--trace") {
      auto v = value();
      if (!v) return drill_usage_error(std::string(a) + " needs a file");
      (a == "--machine" ? opt.machine_file : opt.trace_file) = std::string(*v);
    } else if (a == "--clearance" || a == "--settle" || a == "--feed-override") {
      auto v = value();
      const std::optional<double> x = v ? parse_number(*v) : std::nullopt;
      if (!x || *x < 0.0) return drill_usage_error(std::string(a) + " needs a number ≥ 0");
      if (a == "--clearance")
        dopt.clearance_mm = *x;
      else if (a == "--settle")
        dopt.head_settle_s = *x;
      else
        opt.feed_override_pct = *x;
    } else if (a == "--devices") {
      opt.devices = true;
    } else if (a == "--json") {
      json = true;
    } else if (a == "--progress" || a == "--no-progress") {
      show_progress = a == "--progress";
    } else if (a == "--no-realtime") {
      opt.realtime = false;
    } else if (a == "--fast") {
      opt.clock = rt::RtClock::Simulated;
    } else if (!a.empty() && a[0] == '-') {
      return drill_usage_error("unknown option '" + std::string(a) + "'");
    } else if (table.empty()) {
      table = std::string(a);
    } else {
      return drill_usage_error("more than one hole table");
    }
  }
  if (table.empty()) return drill_usage_error("missing HOLES.csv");

  // Everything is checked before anything moves: machine, table, the job's
  // travel.
  Result<MachineConfig> machine = load_machine(opt);
  if (!machine) {
    std::fprintf(stderr, "%s\n", machine.error().to_string().c_str());
    return 1;
  }
  Result<PreparedDrill> prepared = prepare_drill_job(table, *machine, ReaderOptions{}.start, dopt);
  if (!prepared) {
    std::fprintf(stderr, "%s\n", prepared.error().to_string().c_str());
    return prepared.error().code == ErrorCode::Usage ? 2 : 1;
  }
  const std::vector<HoleProcessParams>* rows = &prepared->rows;
  DrillJob* job = &prepared->job;
  const ProgramSummary* summary = &prepared->summary;
  std::vector<HoleRecord> records(job->holes.size());
  for (std::size_t k = 0; k < job->holes.size(); ++k) {
    records[k].hole = job->holes[k].hole_number;
    records[k].process = process_name((*rows)[k].process);
  }
  std::unique_ptr<HeadLink> head;
  if (opt.devices) {
    Result<std::unique_ptr<HeadLink>> h = HeadLink::simulated(records);
    if (!h) {
      std::fprintf(stderr, "%s\n", h.error().to_string().c_str());
      return 1;
    }
    head = std::move(h).value();
  }
  // Hole k runs over segments [first_segment, end_segment): its start, its
  // settle dwell (the head's block), its end.
  DrillProgress moments(job->holes);
  const auto take = [&](const std::vector<DrillMoment>& ms, double t) {
    for (const DrillMoment& m : ms) {
      switch (m.kind) {
        case DrillMoment::Kind::Start: records[m.hole].start_s = t; break;
        case DrillMoment::Kind::Head:
          if (head) head->begin_hole(job->holes[m.hole], m.hole);
          break;
        case DrillMoment::Kind::End:
          records[m.hole].end_s = t;
          if (head) head->end_hole(m.hole);
          break;
      }
    }
  };
  opt.on_segment = [&](std::uint32_t segment, double t) { take(moments.advance(segment), t); };
  opt.program = table;
  opt.segments = std::make_shared<const std::vector<Segment>>(job->segments);
  opt.summary = *summary;
  opt.line_unit = "holes";
  ProgressFn progress;
  if (show_progress)
    progress = [](double f) {
      std::fprintf(stderr, "\r  drilling %5.1f %%", 100.0 * f);
      if (f >= 1.0) std::fputc('\n', stderr);
    };
  Result<RunReport> report = run_job(opt, progress);
  if (!report) {
    std::fprintf(stderr, "%s\n", report.error().to_string().c_str());
    const ErrorCode code = report.error().code;
    return code == ErrorCode::Usage || code == ErrorCode::OutputIsInput ? 2 : 1;
  }
  take(moments.finish(), report->cycle_time_s);
  drivers::MasterCounters head_counters;
  std::string head_who;
  if (head) {
    head_who = head->who();
    head_counters = head->finish();
  }
  std::size_t head_failures = 0;
  for (const HoleRecord& r : records)
    if (head && (!r.head_written || !r.head_error.empty())) ++head_failures;

  if (json) {
    nlohmann::json j = nlohmann::json::parse(report_json(*report));
    nlohmann::json holes = nlohmann::json::array();
    for (const HoleRecord& r : records)
      holes.push_back({{"hole", r.hole},
                       {"process", r.process},
                       {"start_s", r.start_s},
                       {"time_s", r.end_s - r.start_s},
                       {"head_written", r.head_written},
                       {"head_error", r.head_error}});
    j["holes"] = holes;
    if (head)
      j["scan_head"] = {
          {"device", head_who}, {"requests", head_counters.requests}, {"failed", head_counters.failed}};
    std::printf("%s\n", json_text(j).c_str());
  } else {
    std::fputs(format_report(*report).c_str(), stdout);
    std::printf("  holes            %zu\n", records.size());
    std::printf("    hole  process      start s    time s  head block\n");
    for (const HoleRecord& r : records)
      std::printf("    %4u  %-10s %9.3f %9.3f  %s\n", r.hole, r.process, r.start_s, r.end_s - r.start_s,
                  !head                  ? "-"
                  : r.head_error.empty() ? (r.head_written ? "written" : "not written")
                                         : r.head_error.c_str());
    if (head)
      std::printf("  scan head        %s (simulator): %llu requests, %llu failed\n", head_who.c_str(),
                  static_cast<unsigned long long>(head_counters.requests),
                  static_cast<unsigned long long>(head_counters.failed));
  }
  const bool ok = run_succeeded(*report) && head_failures == 0;
  return ok ? 0 : 3;
}

}  // namespace lcnc::app
