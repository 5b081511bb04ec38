// Parse throughput of the G-code front end: check_program() over a program
// file (every line read, tokenized, interpreted into segments and checked).
//
//   bench/gen_program.py /tmp/bench_1M.ngc --lines 1000000
//   build/bench/parse_bench /tmp/bench_1M.ngc [runs]
//
// Prints each run and the median in lines/s, beside a baseline measured in the
// same run: only reading the file's lines (std::getline), so the ratio says
// what parsing and checking cost over I/O. Results go to BENCHMARKS.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "gcode/program_reader.h"
#include "machine/machine_config.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: parse_bench PROGRAM [runs] [machine.toml]\n");
    return 2;
  }
  const std::string program = argv[1];
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  const std::string machine_file =
      argc > 3 ? argv[3] : std::string(LCNC_SHARE_DIR) + "/machines/default.toml";
  auto machine = lcnc::load_machine_config(machine_file);
  if (!machine) {
    std::fprintf(stderr, "%s\n", machine.error().to_string().c_str());
    return 1;
  }
  std::vector<double> rates, baseline;
  for (int r = 0; r < runs; ++r) {
    const auto b0 = std::chrono::steady_clock::now();
    std::ifstream in(program);
    std::string line;
    std::uint64_t n = 0;
    while (std::getline(in, line)) ++n;
    const auto b1 = std::chrono::steady_clock::now();
    baseline.push_back(static_cast<double>(n) / std::chrono::duration<double>(b1 - b0).count());

    const auto t0 = std::chrono::steady_clock::now();
    auto summary = lcnc::check_program(program, *machine);
    const auto t1 = std::chrono::steady_clock::now();
    if (!summary) {
      std::fprintf(stderr, "%s\n", summary.error().to_string().c_str());
      return 1;
    }
    const double s = std::chrono::duration<double>(t1 - t0).count();
    const double rate = summary->lines / s;
    rates.push_back(rate);
    std::printf("run %d: %u lines, %llu segments in %.3f s = %.0f lines/s\n", r + 1, summary->lines,
                static_cast<unsigned long long>(summary->segments), s, rate);
  }
  std::sort(rates.begin(), rates.end());
  std::sort(baseline.begin(), baseline.end());
  const double med = rates[rates.size() / 2], base = baseline[baseline.size() / 2];
  std::printf("median: %.0f lines/s over %d runs (line reading alone: %.0f lines/s, ratio %.2f)\n", med, runs,
              base, med / base);
  return 0;
}
