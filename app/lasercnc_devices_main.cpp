// lasercnc-devices: starts the virtual devices (simulators) of the register
// map — laser source, power meter, four-beam scanning head, displacement
// sensor and 3D probe — as real Modbus slaves (TCP on loopback, or RTU on
// pseudo-terminals) plus the probe's RS-232 line protocol on a pty, prints
// where each one is, and runs until SIGINT/SIGTERM (or --seconds).
//
// The power meter sits in the laser's beam; the sensor and the probe look at
// the same simulated workpiece surface.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/cli_values.h"
#include "drivers/devices/displacement_sensor_sim.h"
#include "drivers/devices/laser_source_sim.h"
#include "drivers/devices/power_meter_sim.h"
#include "drivers/devices/probe_3d_sim.h"
#include "drivers/devices/scan_head_sim.h"
#include "drivers/modbus/register_map.h"
#include "drivers/serial/pty_link.h"

namespace {

using namespace lcnc;
using namespace lcnc::drivers;

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }

constexpr const char* kUsage =
    "usage: lasercnc-devices [--map FILE] [--host IPV4] [--base-port N] [--rtu] [--seconds S]\n"
    "  --map FILE      register map (default: the shipped share/modbus/register_map.toml)\n"
    "  --host IPV4     address the TCP slaves bind (default 127.0.0.1: loopback only)\n"
    "  --base-port N   TCP ports N … N+4 in the order listed (default: free ports)\n"
    "  --rtu           Modbus RTU on pseudo-terminals instead of TCP (one pty per device)\n"
    "  --seconds S     stop after S seconds (default: until SIGINT/SIGTERM)\n";

int usage_error(const std::string& msg) { return lcnc::app::usage_error("lasercnc-devices", msg, kUsage); }

template <typename Sim>
std::unique_ptr<Sim> must(Result<std::unique_ptr<Sim>> made) {
  if (!made) {
    std::fprintf(stderr, "lasercnc-devices: %s\n", made.error().to_string().c_str());
    std::exit(1);
  }
  return std::move(made.value());
}

}  // namespace

int main(int argc, char** argv) {
  // before any device serves: a SIGTERM as soon as one answers stops cleanly
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::string map_path = default_register_map_path();
  std::string host = "127.0.0.1";
  int base_port = 0;
  bool rtu = false;
  double seconds = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--map" || a == "--host" || a == "--base-port" || a == "--seconds") {
      const char* v = next();
      if (v == nullptr) return usage_error(a + " needs a value");
      if (a == "--map")
        map_path = v;
      else if (a == "--host")
        host = v;
      else if (a == "--base-port")
        base_port = std::atoi(v);
      else
        seconds = std::atof(v);
      if (a == "--base-port" && (base_port < 1 || base_port > 65531))
        return usage_error("--base-port must be 1 … 65531");
    } else if (a == "--rtu") {
      rtu = true;
    } else if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      return usage_error("unknown argument '" + a + "'");
    }
  }

  auto map = load_register_map(map_path);
  if (!map) {
    std::fprintf(stderr, "lasercnc-devices: %s\n", map.error().to_string().c_str());
    return 1;
  }
  auto device = [&](const char* name) {
    auto d = map->device_copy(name);
    if (!d) {
      std::fprintf(stderr, "lasercnc-devices: %s\n", d.error().to_string().c_str());
      std::exit(1);
    }
    return d.value();
  };

  // One slave config per device: a free (or given) TCP port, or a pty pair
  // whose far end (a_path) is printed for the master.
  std::vector<std::unique_ptr<PtyLink>> links;
  int index = 0;
  auto config = [&]() {
    SlaveConfig c;
    if (rtu) {
      auto link = std::make_unique<PtyLink>();
      if (Status s = link->start(); !s) {
        std::fprintf(stderr, "lasercnc-devices: %s\n", s.error().to_string().c_str());
        std::exit(1);
      }
      c.endpoint.transport = Transport::Rtu;
      c.endpoint.device = link->b_path();
      links.push_back(std::move(link));
    } else {
      c.endpoint.host = host;
      c.endpoint.port = static_cast<std::uint16_t>(base_port > 0 ? base_port + index : 0);
    }
    ++index;
    return c;
  };

  SurfaceModel surface;
  auto laser = must(LaserSourceSim::create(device("laser_source"), config()));
  PowerMeterParams meter_params;
  meter_params.source = [l = laser.get()] { return l->output_power_w(); };
  auto meter = must(PowerMeterSim::create(device("power_meter"), config(), meter_params));
  auto head = must(ScanHeadSim::create(device("scan_head"), config()));
  DisplacementSensorParams sensor_params;
  sensor_params.surface = surface;
  auto sensor = must(DisplacementSensorSim::create(device("displacement_sensor"), config(), sensor_params));
  Probe3dParams probe_params;
  probe_params.surface = surface;
  auto probe = must(Probe3dSim::create(device("probe_3d"), config(), probe_params));

  std::vector<VirtualDevice*> all = {laser.get(), meter.get(), head.get(), sensor.get(), probe.get()};
  for (VirtualDevice* d : all)
    if (Status s = d->start(); !s) {
      std::fprintf(stderr, "lasercnc-devices: %s\n", s.error().to_string().c_str());
      return 1;
    }

  std::printf("lasercnc-devices: virtual devices (simulators) running, register map %s\n", map_path.c_str());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Endpoint ep = all[i]->endpoint();
    const std::string where =
        rtu ? "rtu " + links[i]->a_path() + " @" + std::to_string(ep.baud) : ep.to_string();
    std::printf("  %-20s unit %u  %s\n", all[i]->name().c_str(),
                static_cast<unsigned>(all[i]->slave().map().unit_id), where.c_str());
  }
  std::printf("  %-20s serial %s (RS-232 line protocol, drivers/serial/probe_protocol.h)\n", "probe_3d",
              probe->serial_path().c_str());
  if (seconds > 0)
    std::printf("lasercnc-devices: stopping after %g s\n", seconds);
  else
    std::printf("lasercnc-devices: Ctrl-C (SIGINT) or SIGTERM stops them\n");
  std::fflush(stdout);

  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!g_stop.load() && (seconds <= 0 || std::chrono::steady_clock::now() < end))
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  for (VirtualDevice* d : all) d->stop();
  for (auto& l : links) l->stop();
  std::printf("lasercnc-devices: stopped\n");
  return 0;
}
