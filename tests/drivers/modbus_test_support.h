// Shared by the Modbus tests: a slave and a master joined over TCP on
// loopback (the slave binds port 0, so no fixed port) or over RTU through a
// PtyLink (two ptys and a relay that can corrupt bytes or drop the line).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "drivers/modbus/modbus_master.h"
#include "drivers/modbus/modbus_slave.h"
#include "drivers/modbus/register_map.h"
#include "drivers/serial/pty_link.h"

namespace lcnc::drivers::testing {

using namespace std::chrono_literals;

inline DeviceMap shipped(std::string_view device) {
  auto d = shipped_device(device);
  EXPECT_TRUE(d.ok()) << (d.ok() ? "" : d.error().to_string());
  return d.ok() ? d.value() : DeviceMap{};
}

// Short timeouts keep the fault tests quick; nothing here is timing-critical
// beyond "an answer arrives well within 150 ms on an idle machine".
inline MasterConfig quick_master(Endpoint ep) {
  MasterConfig c;
  c.endpoint = std::move(ep);
  c.response_timeout = 150ms;
  c.byte_timeout = 50ms;
  c.retries = 2;
  c.reconnect_interval = 50ms;
  return c;
}

// A slave and a master of one device, over the chosen transport.
struct Pair {
  std::unique_ptr<PtyLink> link;  // RTU only
  std::unique_ptr<ModbusSlave> slave;
  std::unique_ptr<ModbusMaster> master;

  static std::unique_ptr<Pair> make(Transport t, const DeviceMap& map,
                                    const std::function<void(ModbusSlave&)>& setup = {},
                                    std::function<void(MasterConfig&)> tune = {}) {
    auto p = std::make_unique<Pair>();
    SlaveConfig sc;
    Endpoint master_ep;
    if (t == Transport::Rtu) {
      p->link = std::make_unique<PtyLink>();
      EXPECT_TRUE(p->link->start().ok());
      sc.endpoint.transport = Transport::Rtu;
      sc.endpoint.device = p->link->b_path();
      master_ep.transport = Transport::Rtu;
      master_ep.device = p->link->a_path();
    }
    p->slave = std::make_unique<ModbusSlave>(map, sc);
    if (setup) setup(*p->slave);
    const Status s = p->slave->start();
    EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
    if (t == Transport::Tcp) master_ep.port = p->slave->port();
    MasterConfig mc = quick_master(master_ep);
    if (tune) tune(mc);
    p->master = std::make_unique<ModbusMaster>(map, mc);
    EXPECT_TRUE(p->master->start().ok());
    return p;
  }
};

inline std::string transport_name(const ::testing::TestParamInfo<Transport>& info) {
  return info.param == Transport::Rtu ? "Rtu" : "Tcp";
}

// Waits for `pred`, polling, up to `limit`; true when it held.
inline bool eventually(const std::function<bool()>& pred, std::chrono::milliseconds limit = 2000ms) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return pred();
}

}  // namespace lcnc::drivers::testing
