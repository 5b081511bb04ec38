// Modbus round trips through the project's own master and slave
// (drivers/modbus/), as the HMI will see them: each request goes through
// the master's queue and worker thread, libmodbus framing, the transport,
// the slave's map check and reply, and back to a future.
//
//   RTU: a PtyLink (two ptys and a relay thread) configured at 115200 baud.
//        A pty has no baud-rate timing — bytes move at memory speed — so the
//        measured time is the software's share only. The wire time a real
//        115200 8N1 line adds is computed, not measured:
//          t_wire = (request bytes + response bytes) · 10 bits / 115200
//        plus, for a strictly spec-timed slave, the 1.75 ms inter-frame
//        silence (t3.5 for rates above 19200) after each frame.
//   TCP: loopback; requests/s with one master (Modbus is question–answer:
//        one request outstanding per connection) and with 4 masters on
//        4 connections to the same slave.
//
// usage: modbus_bench [runs]      (default 5; figures are medians over runs)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <memory>
#include <vector>

#include "drivers/modbus/modbus_master.h"
#include "drivers/modbus/modbus_slave.h"
#include "drivers/modbus/register_map.h"
#include "drivers/serial/pty_link.h"

namespace {

using namespace lcnc;
using namespace lcnc::drivers;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

void die(const Diagnostic& d) {
  std::fprintf(stderr, "modbus_bench: %s\n", d.to_string().c_str());
  std::exit(1);
}

// Per-request round-trip times (µs) of `n` requests, one at a time.
std::vector<double> round_trips(ModbusMaster& m, const RawRequest& req, int n) {
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto t0 = Clock::now();
    auto r = m.request(req).get();
    const auto t1 = Clock::now();
    if (!r) die(r.error());
    us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  }
  return us;
}

double wire_ms(int request_bytes, int response_bytes, int baud) {
  return (request_bytes + response_bytes) * 10.0 / baud * 1e3;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  auto cnc = shipped_device("cnc");
  if (!cnc) die(cnc.error());
  const DeviceMap map = cnc.value();

  // FC3 of 10 holding registers (part of the hole block) and FC16 of the
  // whole 25-register hole parameter block (docs/design.md §6 fields 1–18).
  const RawRequest fc3{Function::ReadHoldingRegisters, 0, 10, {}, "bench read"};
  RawRequest fc16{Function::WriteMultipleRegisters, 0, 25, std::vector<std::uint16_t>(25, 0), "bench write"};
  fc16.data[0] = 1;   // hole_number ≥ 1
  fc16.data[19] = 1;  // scan_radius_turns ≥ 1
  const int kRtuN = 1000, kTcpN = 5000;

  // ── RTU over a pty pair ───────────────────────────────────────────────
  PtyLink link;
  if (Status s = link.start(); !s) die(s.error());
  SlaveConfig sc;
  sc.endpoint.transport = Transport::Rtu;
  sc.endpoint.device = link.b_path();
  sc.endpoint.baud = 115200;
  ModbusSlave rtu_slave(map, sc);
  if (Status s = rtu_slave.start(); !s) die(s.error());
  MasterConfig mc;
  mc.endpoint.transport = Transport::Rtu;
  mc.endpoint.device = link.a_path();
  mc.endpoint.baud = 115200;
  ModbusMaster rtu(map, mc);
  if (Status s = rtu.start(); !s) die(s.error());
  round_trips(rtu, fc3, 100);  // warm up
  std::vector<double> rtu3_med, rtu3_p99, rtu16_med;
  for (int r = 0; r < runs; ++r) {
    auto a = round_trips(rtu, fc3, kRtuN);
    rtu3_med.push_back(median(a));
    rtu3_p99.push_back(percentile(a, 0.99));
    rtu16_med.push_back(median(round_trips(rtu, fc16, kRtuN)));
  }
  rtu.stop();
  rtu_slave.stop();
  link.stop();

  // ── TCP on loopback ───────────────────────────────────────────────────
  ModbusSlave tcp_slave(map, SlaveConfig{});
  if (Status s = tcp_slave.start(); !s) die(s.error());
  MasterConfig tc;
  tc.endpoint.port = tcp_slave.port();
  std::vector<std::unique_ptr<ModbusMaster>> masters;
  for (int i = 0; i < 4; ++i) {
    masters.push_back(std::make_unique<ModbusMaster>(map, tc));
    if (Status s = masters.back()->start(); !s) die(s.error());
    round_trips(*masters.back(), fc3, 200);  // connect and warm up
  }
  std::vector<double> tcp1_rps, tcp1_med, tcp4_rps;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = Clock::now();
    auto a = round_trips(*masters[0], fc3, kTcpN);
    const double s1 = std::chrono::duration<double>(Clock::now() - t0).count();
    tcp1_rps.push_back(kTcpN / s1);
    tcp1_med.push_back(median(a));
    const auto t4 = Clock::now();
    std::vector<std::future<std::vector<double>>> f;
    for (auto& m : masters)
      f.push_back(std::async(std::launch::async, [&m, &fc3] { return round_trips(*m, fc3, kTcpN); }));
    for (auto& x : f) x.get();
    const double s4 = std::chrono::duration<double>(Clock::now() - t4).count();
    tcp4_rps.push_back(4.0 * kTcpN / s4);
  }
  for (auto& m : masters) m->stop();
  tcp_slave.stop();

  // FC3 ×10: request 8 bytes (unit, fc, addr 2, count 2, CRC 2), answer
  // 5 + 2·10 = 25. FC16 ×25: request 9 + 50 = 59, answer 8.
  const double w3 = wire_ms(8, 25, 115200), w16 = wire_ms(59, 8, 115200);
  std::printf("modbus_bench: %d runs; medians over runs\n", runs);
  std::printf(
      "RTU over pty @115200 (no baud timing), FC3 x10 regs: median %.0f us, p99 %.0f us "
      "(%d requests/run)\n",
      median(rtu3_med), median(rtu3_p99), kRtuN);
  std::printf("RTU over pty @115200 (no baud timing), FC16 x25 regs: median %.0f us\n", median(rtu16_med));
  std::printf(
      "RTU on a real 115200 8N1 line, theoretical: FC3 x10 %.2f ms wire (+3.50 ms t3.5 "
      "silences = %.2f ms); FC16 x25 %.2f ms wire (%.2f ms)\n",
      w3, w3 + 3.5, w16, w16 + 3.5);
  std::printf("TCP loopback, FC3 x10 regs, 1 master: %.0f requests/s (median round trip %.0f us)\n",
              median(tcp1_rps), median(tcp1_med));
  std::printf("TCP loopback, FC3 x10 regs, 4 masters on 4 connections: %.0f requests/s\n", median(tcp4_rps));
  return 0;
}
