// lasercnc — the command line: check or run a G-code program on the
// simulated machine and print the report.
//
// Exit codes: 0 done, 1 bad input (program, config), 2 bad command line,
// 3 the run finished but failed its own checks (steps, pulses, an axis past
// its velocity or acceleration limit, the path past its tolerance).
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/cli_values.h"
#include "app/cnc_modbus_host.h"
#include "app/control_client.h"
#include "app/cut_cli.h"
#include "app/decompose_cli.h"
#include "app/drill_cli.h"
#include "app/moves_list.h"
#include "app/run_job.h"
#include "drivers/modbus/endpoint_spec.h"
#include "gcode/program_reader.h"
#include "machine/config_keys.h"
#include "plan/program_source.h"

namespace {

using lcnc::app::parse_number;

constexpr const char* kUsage =
    "usage:\n"
    "  lasercnc run PROGRAM [--machine FILE] [--vmax V] [--amax A] [--tolerance E]\n"
    "                       [--feed-override PCT] [--pause S] [--trace FILE.csv] [--json]\n"
    "                       [--[no-]progress] [--fast | --no-realtime] [--input N]... [--adaptive-feed F]\n"
    "                       [--devices | --laser ENDPOINT [--power-meter ENDPOINT]]\n"
    "  lasercnc check PROGRAM [--machine FILE] [--moves FILE]\n"
    "  lasercnc status [--json] [--shm NAME]\n"
    "  lasercnc send CMD [ARG...] [--wait] [--timeout S] [--shm NAME]\n"
    "       CMD: load PROGRAM | start [--from-line N] [--single-block] [--dry-run] |\n"
    "            hold | resume | stop | estop | reset | override PCT | jog AXIS DIST |\n"
    "            home AXIS | mdi G-CODE | frame\n"
    "  lasercnc drill HOLES.csv [--devices] [--clearance MM] [--settle S] [--json] ...\n"
    "                       (lasercnc drill --help for its options)\n"
    "  lasercnc decompose PART.dxf [--speed V] [--step MM] [--mode sync|seed] ...\n"
    "                       (lasercnc decompose --help for its options)\n"
    "  lasercnc cut PART.dxf -o PROGRAM.ngc [--svg FILE] [--process TABLE.csv] ...\n"
    "                       (lasercnc cut --help for its options)\n"
    "  lasercnc config --reference\n"
    "  lasercnc --help | --version\n"
    "\n"
    "  run     plans PROGRAM, runs it on the simulated machine with the real RT thread\n"
    "          and prints the report (--json: as one JSON object on stdout)\n"
    "  check   reads the whole program and reports the first error, runs nothing\n"
    "          (--moves: also writes its canonical moves, a line each: LINE rapid|feed\n"
    "          X Y Z A B C, LINE arc X Y Z A B C CX CY CZ PLANE TURNS, LINE dwell S;\n"
    "          - for standard output)\n"
    "  status  the state of lasercncd (machine, job, latency)\n"
    "  send    a command to lasercncd; prints its answer (--wait: start, mdi and frame\n"
    "          wait for the job's end and print how it ended)\n"
    "          start --from-line N: reads the program up to line N without moving\n"
    "            (modes, offsets, feed, power as there), then approaches at rapid\n"
    "            with the beam off: up to the higher Z, across, down; runs on from N\n"
    "          start --single-block: stops after each block; resume runs the next\n"
    "          start --dry-run: every move as programmed, the beam off\n"
    "          mdi \"G1 X10 F600\": one line now, in the modes the last MDI left\n"
    "            (touch-off: mdi \"G10 L20 P0 X0 Y0\" makes here the work zero)\n"
    "          frame: traces the loaded program's X Y extents, beam off\n"
    "  drill   runs the holes of a process-database table (CSV) as one drilling job\n"
    "  decompose  splits each contour of a DXF part into main- and auxiliary-axis paths\n"
    "  cut     a laser cutting program from a DXF part: holes first, kerf offset,\n"
    "          lead-ins, power and feed per layer\n"
    "  config  --reference: every key of the machine config (TOML) with its unit,\n"
    "          allowed range, default and meaning, as Markdown (docs/machine_config.md)\n"
    "  --vmax/--amax   max velocity (mm/s) / acceleration (mm/s^2) of every linear axis\n"
    "  --tolerance     E mm: the P of every G64 without P for this run (the machine's\n"
    "                  path_tolerance_mm): how far a blended corner may leave the path,\n"
    "                  and what the path check allows there. A program only blends in\n"
    "                  G64: one that never says G64 runs exact path (G61) unless the\n"
    "                  machine's startup_code says G64 (the default machine's does);\n"
    "                  a G64 P<n> in the program keeps its own P\n"
    "  --feed-override feed override for the whole run, %: feeds at PCT/100 of F, never\n"
    "                  past an axis limit (below 100 also the rapids slower);\n"
    "                  1 <= PCT <= 100 x machine.max_feed_override (150 on the default\n"
    "                  machine); default 100\n"
    "  --pause         an M0, M1 or M60 pauses the job; unattended, the run goes on after\n"
    "                  S seconds of machine time (default 0). (lasercncd waits for `send resume`.)\n"
    "  --input         the simulated machine's digital input N (0-7) is high for the whole\n"
    "                  run (M66 P N L3 goes on at once; repeat for more inputs)\n"
    "  --adaptive-feed the simulated machine's adaptive-feed input, 0 to 1 (default 1):\n"
    "                  scales the feed of the moves after M52 P1\n"
    "  --trace         commanded position and laser power every RT period as CSV\n"
    "                  t,x,y,z,a,b,c,power (s of machine time, mm, deg, % of rated)\n"
    "  --progress      progress bar on stderr (default: only when stderr is a terminal)\n"
    "  --fast          the simulated clock: each RT period runs as soon as the last is done\n"
    "                  (the same planner, kernel, periods, steps and report; the cycle time\n"
    "                  is machine time), so a job's cycle time is known in a fraction of it;\n"
    "                  no latency is measured and no real-time scheduling asked for\n"
    "  --no-realtime   do not ask for SCHED_FIFO / mlockall\n"
    "  --devices       a simulated laser source and power meter over Modbus (loopback):\n"
    "                  enabled before motion, the setpoint follows the commanded power\n"
    "  --laser, --power-meter  the real devices instead: tcp:HOST:PORT or\n"
    "                  rtu:DEVICE[:BAUD[:PARITY]]\n";

int usage_error(const std::string& msg) { return lcnc::app::usage_error("lasercnc", msg, kUsage); }

void draw_progress(double f) {
  constexpr int kWidth = 40;
  const int filled = static_cast<int>(std::lround(f * kWidth));
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r  [%s] %5.1f %%", bar.c_str(), f * 100.0);
  if (f >= 1.0) std::fputc('\n', stderr);
  std::fflush(stderr);
}

int run(int argc, char** argv) {
  if (argc < 2) return usage_error("missing command");
  const std::string_view cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "--version") {
    std::puts("lasercnc 0.1.0");
    return 0;
  }
  if (cmd == "decompose") return lcnc::app::decompose_main(argc - 1, argv + 1);
  if (cmd == "drill") return lcnc::app::drill_main(argc - 1, argv + 1);
  if (cmd == "cut") return lcnc::app::cut_main(argc - 1, argv + 1);
  if (cmd == "config") {
    if (argc != 3 || std::string_view(argv[2]) != "--reference")
      return usage_error("config takes --reference");
    std::fputs(lcnc::config_reference_markdown().c_str(), stdout);
    return 0;
  }
  if (cmd == "status" || cmd == "send") {
    lcnc::app::ClientOptions co;
    std::vector<std::string> args;
    for (int i = 2; i < argc; ++i) {
      const std::string_view a = argv[i];
      if (a == "--shm" && i + 1 < argc) {
        co.shm_name = argv[++i];
      } else if (a == "--json") {
        co.json = true;
      } else if (a == "--wait") {
        co.wait = true;
      } else if (a == "--single-block") {
        co.single_block = true;
      } else if (a == "--dry-run") {
        co.dry_run = true;
      } else if (a == "--from-line" && i + 1 < argc) {
        const auto n = parse_number(argv[++i]);
        if (!n || *n < 1 || *n > 4e9 || *n != std::floor(*n))
          return usage_error("--from-line needs a line number (1 or more)");
        co.from_line = static_cast<std::uint32_t>(*n);
      } else if (a == "--timeout" && i + 1 < argc) {
        const auto t = parse_number(argv[++i]);
        if (!t || !(*t > 0) || *t > lcnc::app::kMaxTimeoutS)
          return usage_error("--timeout needs a number of seconds, more than 0 and at most " +
                             std::to_string(static_cast<int>(lcnc::app::kMaxTimeoutS)));
        co.timeout_s = *t;
      } else if (a.size() > 2 && a.substr(0, 2) == "--") {
        return usage_error("unknown option '" + std::string(a) + "'");
      } else {
        args.emplace_back(a);
      }
    }
    if (cmd == "status") {
      if (!args.empty()) return usage_error("status takes no argument");
      return lcnc::app::client_status(co);
    }
    if ((co.from_line != 0 || co.single_block || co.dry_run) && (args.empty() || args[0] != "start"))
      return usage_error("--from-line, --single-block and --dry-run go with send start");
    return lcnc::app::client_send(args, co);
  }
  if (cmd != "run" && cmd != "check") return usage_error("unknown command '" + std::string(cmd) + "'");

  lcnc::app::RunOptions opt;
  bool json = false;
  std::string moves_file;
  bool show_progress = isatty(STDERR_FILENO) != 0;
  for (int i = 2; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::optional<std::string_view> {
      if (i + 1 >= argc) return std::nullopt;
      return std::string_view(argv[++i]);
    };
    auto number = [&](std::optional<double>& out) -> bool {
      auto v = value();
      if (!v) return false;
      out = parse_number(*v);
      return out.has_value();
    };
    if (a == "--machine") {
      auto v = value();
      if (!v) return usage_error("--machine needs a file");
      opt.machine_file = *v;
    } else if (a == "--trace") {
      auto v = value();
      if (!v) return usage_error("--trace needs a file");
      opt.trace_file = *v;
    } else if (a == "--vmax") {
      if (!number(opt.vmax)) return usage_error("--vmax needs a number (mm/s)");
    } else if (a == "--amax") {
      if (!number(opt.amax)) return usage_error("--amax needs a number (mm/s^2)");
    } else if (a == "--tolerance") {
      if (!number(opt.tolerance_mm)) return usage_error("--tolerance needs a number (mm)");
    } else if (a == "--feed-override") {
      std::optional<double> pct;
      if (!number(pct)) return usage_error("--feed-override needs a number (%, e.g. 150)");
      opt.feed_override_pct = *pct;
    } else if (a == "--pause") {
      std::optional<double> s;
      if (!number(s) || !(*s >= 0.0 && *s <= 3600.0))
        return usage_error("--pause needs the seconds to stay paused at M0/M1/M60, 0 to 3600");
      opt.pause_s = *s;
    } else if (a == "--input") {
      std::optional<double> n;
      if (!number(n) || !(*n >= 0.0 && *n < lcnc::kDigitalInputs && *n == std::floor(*n)))
        return usage_error("--input needs the number of a digital input to hold high, 0 to 7");
      opt.inputs_high = static_cast<std::uint8_t>(opt.inputs_high | (1u << static_cast<int>(*n)));
    } else if (a == "--adaptive-feed") {
      std::optional<double> f;
      if (!number(f) || !(*f >= 0.0 && *f <= 1.0))
        return usage_error("--adaptive-feed needs the factor on the feed under M52, 0 to 1");
      opt.adaptive_feed = static_cast<float>(*f);
    } else if (a == "--moves" && cmd == "check") {
      auto v = value();
      if (!v) return usage_error("--moves needs a file (- for standard output)");
      moves_file = *v == "-" ? "/dev/stdout" : std::string(*v);
    } else if (a == "--json") {
      json = true;
    } else if (a == "--no-progress") {
      show_progress = false;
    } else if (a == "--progress") {
      show_progress = true;
    } else if (a == "--devices") {
      opt.devices = true;
    } else if (a == "--laser" || a == "--power-meter") {
      auto v = value();
      if (!v) return usage_error(std::string(a) + " needs an endpoint");
      auto ep = lcnc::drivers::parse_endpoint(*v);
      if (!ep) return usage_error(std::string(a) + " " + ep.error().message);
      (a == "--laser" ? opt.laser : opt.power_meter) = *ep;
    } else if (a == "--no-realtime") {
      opt.realtime = false;
    } else if (a == "--fast") {
      opt.clock = lcnc::rt::RtClock::Simulated;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + std::string(a) + "'");
    } else if (opt.program.empty()) {
      opt.program = a;
    } else {
      return usage_error("more than one program given");
    }
  }
  if (opt.program.empty()) return usage_error("missing PROGRAM");

  if (cmd == "check") {
    auto machine = lcnc::app::load_machine(opt);
    if (!machine) {
      std::fprintf(stderr, "%s\n", machine.error().to_string().c_str());
      return 1;
    }
    auto summary = lcnc::check_job_program(opt.program, *machine);
    if (!summary) {
      std::fprintf(stderr, "%s\n", summary.error().to_string().c_str());
      return 1;
    }
    for (const auto& w : summary->warnings) std::fprintf(stderr, "%s\n", w.to_string().c_str());
    if (!moves_file.empty()) {
      std::fflush(stdout);
      if (lcnc::Status st =
              lcnc::app::write_moves(opt.program, *machine, moves_file, lcnc::app::job_inputs(opt, *summary));
          !st) {
        std::fprintf(stderr, "%s\n", st.error().to_string().c_str());
        return st.error().code == lcnc::ErrorCode::OutputIsInput ? 2 : 1;
      }
      if (moves_file == "/dev/stdout") return 0;
    }
    std::printf("%s: OK, %u lines, %llu segments, path %.3f mm\n", opt.program.c_str(), summary->lines,
                static_cast<unsigned long long>(summary->segments), summary->path_length_mm);
    return 0;
  }

  lcnc::app::ProgressFn progress;
  if (show_progress) progress = draw_progress;
  auto report = lcnc::app::run_job(opt, progress);
  if (!report) {
    if (report.error().code == lcnc::ErrorCode::Usage) return usage_error(report.error().message);
    std::fprintf(stderr, "%s\n", report.error().to_string().c_str());
    return report.error().code == lcnc::ErrorCode::OutputIsInput ? 2 : 1;
  }
  if (json) {
    std::printf("%s\n", lcnc::app::report_json(*report).c_str());
  } else {
    std::fputs(lcnc::app::format_report(*report).c_str(), stdout);
  }
  return lcnc::app::run_succeeded(*report) ? 0 : 3;
}

}  // namespace

// Nothing escapes as an abort: what the commands do not turn into a
// diagnostic themselves (the computer out of memory) ends with its message
// and exit code 1.
int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lasercnc: error: %s\n", e.what());
    return 1;
  }
}
