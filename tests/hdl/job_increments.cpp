// A real program's increment stream for the GHDL replay: the entries
// `lasercnc run` pushes to the RT kernel — ProgramReader → Planner (line
// merger, corner blending, look-ahead, coarse interpolation) → EntryStream
// (steps, ramp room, the limit guard; owed steps paid after the last
// sample: plan/entry_stream.h) — on a machine config,
// written as a vector file (tests/vectors/README.md) plus the expected
// signed pulse totals per axis: the commanded position in steps minus the
// start (docs/design.md §4: Σ pulses = commanded steps).
//
//   job_increments MACHINE.toml PROGRAM.ngc OUT.inc OUT.totals [KEY=VALUE …]
//
// KEY=VALUE pairs are added to the "#!" line: the interpolator's timing
// generics of the replay (reset_divider is also the divider of every period).
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gcode/program_reader.h"
#include "machine/machine_config.h"
#include "plan/entry_stream.h"
#include "plan/planner.h"

using namespace lcnc;

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr,
                 "usage: job_increments MACHINE.toml PROGRAM.ngc OUT.inc OUT.totals [KEY=VALUE ...]\n");
    return 2;
  }
  const std::string machine_path = argv[1], program = argv[2], inc_path = argv[3], totals_path = argv[4];
  std::string extra;
  long divider = 1;
  for (int i = 5; i < argc; ++i) {
    const std::string kv = argv[i];
    extra += " " + kv;
    if (kv.rfind("reset_divider=", 0) == 0) divider = std::strtol(kv.c_str() + 14, nullptr, 10);
  }

  Result<MachineConfig> loaded = load_machine_config(machine_path);
  if (!loaded) {
    std::fprintf(stderr, "%s\n", loaded.error().to_string().c_str());
    return 1;
  }
  const MachineConfig machine = std::move(loaded).value();
  ReaderOptions ropt;  // starts at machine zero, as `lasercnc run` does
  Result<std::unique_ptr<ProgramReader>> reader = ProgramReader::open(program, machine, ropt);
  if (!reader) {
    std::fprintf(stderr, "%s\n", reader.error().to_string().c_str());
    return 1;
  }
  ProgramReader& r = **reader;
  Planner planner(machine, [&r](Segment& out) {
    switch (r.next(out)) {
      case ProgramReader::Next::Segment: return SourceStatus::Item;
      case ProgramReader::Next::End: return SourceStatus::End;
      case ProgramReader::Next::Error: return SourceStatus::Error;
    }
    return SourceStatus::Error;
  });
  EntryStream stream(machine, planner, ropt.start);

  std::FILE* out = std::fopen(inc_path.c_str(), "w");
  if (out == nullptr) {
    std::fprintf(stderr, "%s: cannot write\n", inc_path.c_str());
    return 1;
  }
  std::fprintf(out,
               "# The increment stream of %s on %s (machine '%s'), written by job_increments:\n"
               "# ProgramReader -> Planner -> EntryStream, as `lasercnc run` plans it.\n",
               program.c_str(), machine_path.c_str(), machine.name.c_str());
  std::fprintf(out, "#! axes=%d mag_width=%u capacity=%u%s\n", kAxisCount, machine.dda.magnitude_bits,
               machine.dda.capacity, extra.c_str());

  std::array<std::int64_t, kAxisCount> sum{};
  std::uint64_t periods = 0, pulses = 0;
  auto write = [&](const PeriodIncrement& inc) {
    std::fprintf(out, "%ld", divider);
    for (int i = 0; i < kAxisCount; ++i) {
      std::fprintf(out, " %d", inc.steps[i]);
      sum[i] += inc.steps[i];
      pulses += static_cast<std::uint64_t>(std::abs(inc.steps[i]));
    }
    std::fputc('\n', out);
    ++periods;
  };
  PeriodIncrement inc;
  EntryStream::Next got;
  while ((got = stream.next(inc)) == EntryStream::Next::Entry) write(inc);
  if (got != EntryStream::Next::End) {
    std::fprintf(stderr, "%s\n",
                 (got == EntryStream::Next::Limit ? stream.limit_error() : r.error()).to_string().c_str());
    std::fclose(out);
    return 1;
  }
  if (std::fclose(out) != 0) {
    std::fprintf(stderr, "%s: write failed\n", inc_path.c_str());
    return 1;
  }

  std::FILE* tot = std::fopen(totals_path.c_str(), "w");
  if (tot == nullptr) {
    std::fprintf(stderr, "%s: cannot write\n", totals_path.c_str());
    return 1;
  }
  for (int i = 0; i < kAxisCount; ++i) {
    const std::int64_t commanded = stream.commanded(i) - stream.start_steps(i);
    if (sum[i] != commanded) {  // the quantizer's own invariant; never expected to fire
      std::fprintf(stderr, "axis %c: increments sum to %lld, commanded %lld steps\n", kAxisLetters[i],
                   static_cast<long long>(sum[i]), static_cast<long long>(commanded));
      std::fclose(tot);
      return 1;
    }
    std::fprintf(tot, "%d %lld\n", i, static_cast<long long>(commanded));
  }
  std::fclose(tot);
  std::printf("%s: %llu periods (%.3f s at %u us), %llu pulses; commanded steps X %lld Y %lld Z %lld\n",
              inc_path.c_str(), static_cast<unsigned long long>(periods),
              static_cast<double>(periods) * machine.period_s(), machine.period_ns / 1000,
              static_cast<unsigned long long>(pulses), static_cast<long long>(sum[0]),
              static_cast<long long>(sum[1]), static_cast<long long>(sum[2]));
  return 0;
}
