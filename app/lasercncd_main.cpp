// lasercncd — the LaserCNC daemon: the planner and RT threads on the
// simulated machine, published in shared memory for the HMI and `lasercnc
// status` / `lasercnc send`. SIGTERM or SIGINT: a clean shutdown.
//
// Exit codes: 0 clean shutdown, 1 could not start (config, segment taken),
// 2 bad command line.
#include <csignal>
#include <cstdio>
#include <string>
#include <string_view>

#include "app/cnc_modbus_host.h"
#include "app/daemon.h"
#include "drivers/modbus/endpoint_spec.h"

namespace {

std::atomic<bool> g_quit{false};
extern "C" void on_signal(int) { g_quit.store(true); }

constexpr const char* kUsage =
    "usage: lasercncd [--machine FILE] [--shm NAME] [--no-realtime | --simulated-clock] [--hal]\n"
    "                 [--modbus ENDPOINT]\n"
    "                 [--programs DIR]... [--parameter-file FILE]\n"
    "  --machine      machine config (default: share/machines/default.toml)\n"
    "  --shm          shared-memory segment name (default /lasercnc)\n"
    "  --no-realtime  do not ask for SCHED_FIFO / mlockall\n"
    "  --simulated-clock  the simulated machine on the simulated clock, held to the wall\n"
    "                 clock's pace: never faster than real time, and where the computer\n"
    "                 cannot keep up (a loaded desktop, a sanitizer build) the machine\n"
    "                 runs slower instead of running its buffer dry. Jobs, commands and\n"
    "                 reports as on the wall clock; no latency measured (not with --hal)\n"
    "  --hal          real drives through LinuxCNC's HAL: no RT thread here; the\n"
    "                 HAL component runs the kernel (loadrt lasercnc segment=NAME,\n"
    "                 addf lasercnc.update to a thread of the machine's period).\n"
    "                 The axes come up unhomed; a job is refused until each is homed\n"
    "                 (or the machine sets [machine] allow_unhomed = true)\n"
    "  --modbus       serve the register map's cnc device to a PLC or MES:\n"
    "                 tcp:HOST:PORT (port 0: any free one; bind 127.0.0.1 unless\n"
    "                 another address is given) or rtu:DEVICE[:BAUD[:PARITY]]\n"
    "  --programs     a folder `load` may take programs from (repeatable; default:\n"
    "                 any regular file the sender may read)\n"
    "  --parameter-file  where the work offsets (touch-off, G10, G54-G59.3, G92), G28/G30\n"
    "                 positions and program-set tools are kept from one job, MDI\n"
    "                 command and run to the next (default: the machine's parameter_file,\n"
    "                 else $XDG_DATA_HOME/lasercnc/lasercncd.var)\n";

}  // namespace

int main(int argc, char** argv) {
  // First of all: the segment appears during create(), and a supervisor may
  // send SIGTERM the moment it sees it; that must be a clean shutdown too.
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  lcnc::app::DaemonOptions opt;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if ((a == "--machine" || a == "--shm") && i + 1 < argc) {
      (a == "--machine" ? opt.machine_file : opt.shm_name) = argv[++i];
    } else if (a == "--modbus" && i + 1 < argc) {
      auto ep = lcnc::drivers::parse_endpoint(argv[++i]);
      if (!ep) {
        std::fprintf(stderr, "lasercncd: --modbus %s\n%s", ep.error().message.c_str(), kUsage);
        return 2;
      }
      opt.modbus = *ep;
    } else if (a == "--parameter-file" && i + 1 < argc) {
      opt.parameter_file = argv[++i];
    } else if (a == "--programs" && i + 1 < argc) {
      opt.program_dirs.emplace_back(argv[++i]);
    } else if (a == "--hal") {
      opt.hal = true;
    } else if (a == "--no-realtime") {
      opt.realtime = false;
    } else if (a == "--simulated-clock") {
      opt.simulated_clock = true;
    } else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      std::fprintf(stderr, "lasercncd: bad argument '%s'\n%s", argv[i], kUsage);
      return 2;
    }
  }
  if (opt.hal && opt.simulated_clock) {
    std::fprintf(stderr,
                 "lasercncd: --simulated-clock is the simulated machine's; with --hal, "
                 "HAL's thread keeps the time\n%s",
                 kUsage);
    return 2;
  }
  auto daemon = lcnc::app::Daemon::create(opt);
  if (!daemon) {
    std::fprintf(stderr, "lasercncd: %s\n", daemon.error().to_string().c_str());
    return 1;
  }
  if ((*daemon)->recovered_stale())
    std::fprintf(stderr, "lasercncd: recovered a stale segment left by a daemon that died\n");
  return (*daemon)->run(g_quit);
}
