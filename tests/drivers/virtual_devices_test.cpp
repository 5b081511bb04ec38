// The virtual devices, driven through the Modbus master exactly as the HMI
// will drive the hardware: plausible behaviour (lag, noise, alarms, a
// surface to measure) and refusals with the right exception codes. Time
// constants are shortened so each test takes a fraction of a second.
#include <gtest/gtest.h>

#include "drivers/devices/displacement_sensor_sim.h"
#include "drivers/devices/laser_source_sim.h"
#include "drivers/devices/power_meter_sim.h"
#include "drivers/devices/probe_3d_sim.h"
#include "drivers/devices/scan_head_sim.h"
#include "modbus_test_support.h"

namespace lcnc::drivers {
namespace {

using namespace testing;

template <typename Sim>
std::unique_ptr<Sim> started(Result<std::unique_ptr<Sim>> made) {
  EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error().to_string());
  if (!made.ok()) return nullptr;
  std::unique_ptr<Sim> sim = std::move(made.value());
  const Status s = sim->start();
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().to_string());
  return sim;
}

std::unique_ptr<ModbusMaster> master_for(const VirtualDevice& dev, const DeviceMap& map) {
  auto m = std::make_unique<ModbusMaster>(map, quick_master(dev.endpoint()));
  EXPECT_TRUE(m->start().ok());
  return m;
}

double read(ModbusMaster& m, const char* name) {
  auto v = m.read(name).get();
  EXPECT_TRUE(v.ok()) << name << ": " << (v.ok() ? "" : v.error().to_string());
  return v.ok() ? v.value() : -1e9;
}

TEST(LaserSourceSim, EmitsAtTheSetpointAndTripsOverTemperatureAtSustainedFullPower) {
  LaserSourceParams p;
  p.thermal_tau_s = 0.05;  // trips after τ·ln 3 ≈ 55 ms at full power
  const DeviceMap map = shipped("laser_source");
  auto laser = started(LaserSourceSim::create(map, {}, p));
  ASSERT_TRUE(laser);
  auto m = master_for(*laser, map);
  EXPECT_EQ(read(*m, "rated_power_w"), 50.0);
  EXPECT_EQ(read(*m, "status"), 0.0);  // standby

  // 60 % settles at 25 + 0.6·30 = 43 °C: below the 45 °C trip.
  ASSERT_TRUE(m->write_block({{"power_setpoint_pct", 60}}).get().ok());
  ASSERT_TRUE(m->write("enable", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return std::abs(read(*m, "output_power_w") - 30.0) < 0.01; }));
  EXPECT_EQ(read(*m, "status"), 2.0);  // emitting
  EXPECT_EQ(read(*m, "emission"), 1.0);
  std::this_thread::sleep_for(200ms);  // 4 τ: about settled
  EXPECT_EQ(read(*m, "alarm"), 0.0);
  EXPECT_NEAR(read(*m, "temperature_c"), 43.0, 0.5);

  // Full power: over-temperature, emission off, enable refused.
  ASSERT_TRUE(m->write("power_setpoint_pct", 100).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*m, "alarm") == 1.0; }));
  EXPECT_EQ(read(*m, "status"), 3.0);
  EXPECT_EQ(read(*m, "alarm_code"), 1.0);
  EXPECT_EQ(read(*m, "enable"), 0.0);
  ASSERT_TRUE(eventually([&] { return read(*m, "output_power_w") == 0.0; }));
  const Status refused = m->write("enable", 1).get();
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("write enable = 1: exception 04 (server device failure)"),
            std::string::npos)
      << refused.error().message;

  // Cooled below 40 °C, alarm_reset clears it and the laser may emit again.
  ASSERT_TRUE(eventually([&] { return read(*m, "temperature_c") < 39.0; }));
  ASSERT_TRUE(m->write("alarm_reset", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*m, "alarm") == 0.0; }));
  EXPECT_EQ(read(*m, "alarm_reset"), 0.0);  // a command: cleared when taken
  ASSERT_TRUE(m->write("power_setpoint_pct", 10).get().ok());
  EXPECT_TRUE(m->write("enable", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*m, "status") == 2.0; }));
}

TEST(PowerMeterSim, FollowsTheLaserWithLagAndNoise) {
  LaserSourceParams lp;
  const DeviceMap laser_map = shipped("laser_source");
  const DeviceMap meter_map = shipped("power_meter");
  auto laser = started(LaserSourceSim::create(laser_map, {}, lp));
  ASSERT_TRUE(laser);
  PowerMeterParams pp;
  pp.tau_s = 0.03;
  pp.source = [l = laser.get()] { return l->output_power_w(); };
  auto meter = started(PowerMeterSim::create(meter_map, {}, pp));
  ASSERT_TRUE(meter);
  auto ml = master_for(*laser, laser_map);
  auto mm = master_for(*meter, meter_map);

  // Dark: the 0.05 W thermal offset shows until the meter is zeroed.
  ASSERT_TRUE(eventually([&] { return std::abs(read(*mm, "power_w") - 0.05) < 0.08; }));
  ASSERT_TRUE(mm->write("zero", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*mm, "zero") == 0.0; }));
  EXPECT_LT(read(*mm, "power_w"), 0.1);

  ASSERT_TRUE(ml->write("power_setpoint_pct", 40).get().ok());
  ASSERT_TRUE(ml->write("enable", 1).get().ok());  // 40 % of 50 W
  const double first = read(*mm, "power_w");
  EXPECT_LT(first, 15.0);  // lags behind the 20 W step
  ASSERT_TRUE(eventually([&] { return std::abs(read(*mm, "power_w") - 20.0) < 0.1; }));
  // Noise: consecutive readings are not all the same.
  const double counter0 = read(*mm, "sample_counter");
  std::vector<double> r;
  for (int i = 0; i < 5; ++i) {
    r.push_back(read(*mm, "power_w"));
    std::this_thread::sleep_for(15ms);
  }
  EXPECT_NE(std::count(r.begin(), r.end(), r[0]), 5);
  EXPECT_GT(read(*mm, "sample_counter"), counter0);
}

TEST(ScanHeadSim, RunsThePatternAndRefusesChangesWhileRunning) {
  ScanHeadParams p;
  p.accel_rpm_s = 1e6;  // spins up in 30 ms
  const DeviceMap map = shipped("scan_head");
  auto head = started(ScanHeadSim::create(map, {}, p));
  ASSERT_TRUE(head);
  auto m = master_for(*head, map);
  const Status no_speed = m->write("run", 1).get();
  ASSERT_FALSE(no_speed.ok());
  EXPECT_NE(no_speed.error().message.find("exception 03"), std::string::npos);

  // Process fields 12–18 as one block (FC16): a helix from 0.1 to 0.4 mm
  // over 50 turns at 30000 rpm = 500 turns/s, 0.1 s.
  const Status s = m->write_block({{"start_radius_mm", 0.1},
                                   {"end_radius_mm", 0.4},
                                   {"radius_turns", 50},
                                   {"scan_speed_mm_s", 1200},
                                   {"wedge_speed_rpm", 30000},
                                   {"beam_offset_mm", 0.05},
                                   {"process_id", 0}})
                       .get();
  ASSERT_TRUE(s.ok()) << s.error().to_string();
  ASSERT_TRUE(m->write("run", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*m, "running") == 1.0; }));
  const Status busy = m->write("end_radius_mm", 0.2).get();
  ASSERT_FALSE(busy.ok());
  EXPECT_NE(busy.error().message.find("exception 06 (server device busy)"), std::string::npos)
      << busy.error().message;
  ASSERT_TRUE(eventually([&] { return read(*m, "status") == 0.0; }));  // done by itself
  EXPECT_EQ(read(*m, "turns_done"), 50.0);
  EXPECT_DOUBLE_EQ(read(*m, "current_radius_mm"), 0.4);
  EXPECT_EQ(read(*m, "run"), 0.0);
  EXPECT_EQ(read(*m, "end_radius_mm"), 0.4);               // the refused write changed nothing
  EXPECT_TRUE(m->write("end_radius_mm", 0.2).get().ok());  // idle again: accepted
}

TEST(DisplacementSensorSim, MeasuresTheDistanceToTheSurface) {
  const DeviceMap map = shipped("displacement_sensor");
  auto sensor = started(DisplacementSensorSim::create(map));
  ASSERT_TRUE(sensor);
  auto m = master_for(*sensor, map);
  const double x = 700, y = 300;
  const double z = sensor->surface().z_at(x, y);
  sensor->set_position(x, y, z + 42.0);
  ASSERT_TRUE(m->write("averaging", 16).get().ok());
  ASSERT_TRUE(eventually([&] { return std::abs(read(*m, "distance_mm") - 42.0) < 0.005; }));
  EXPECT_EQ(read(*m, "in_range"), 1.0);
  EXPECT_GT(read(*m, "intensity_pct"), 50.0);
  sensor->set_position(x, y, z + 90.0);  // beyond the 70 mm range
  ASSERT_TRUE(eventually([&] { return read(*m, "in_range") == 0.0; }));
  EXPECT_EQ(read(*m, "distance_mm"), 0.0);
  EXPECT_FALSE(m->write("averaging", 65).get().ok());  // 1 … 64
}

TEST(Probe3dSim, TriggeredMeasurementOverModbus) {
  Probe3dParams p;
  p.latency = 20ms;
  const DeviceMap map = shipped("probe_3d");
  auto probe = started(Probe3dSim::create(map, {}, p));
  ASSERT_TRUE(probe);
  auto m = master_for(*probe, map);
  const double z = probe->surface().z_at(321, 123);
  probe->set_position(321, 123, z + 2);
  ASSERT_TRUE(m->write("trigger", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*m, "measurement_id") == 1.0; }));
  auto point = m->read_block({"x_mm", "y_mm", "z_mm", "status"}).get();
  ASSERT_TRUE(point.ok()) << point.error().to_string();
  EXPECT_DOUBLE_EQ(point.value()[0], 321.0);
  EXPECT_DOUBLE_EQ(point.value()[1], 123.0);
  EXPECT_NEAR(point.value()[2], z, 0.006);
  EXPECT_EQ(point.value()[3], 0.0);
  EXPECT_EQ(read(*m, "valid"), 1.0);
  EXPECT_EQ(read(*m, "trigger"), 0.0);

  probe->set_position(321, 123, z + 30);  // beyond reach
  ASSERT_TRUE(m->write("trigger", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return read(*m, "measurement_id") == 2.0; }));
  EXPECT_EQ(read(*m, "valid"), 0.0);
  EXPECT_EQ(read(*m, "status"), 1.0);
}

TEST(VirtualDevices, ServeOverRtuToo) {
  PtyLink link;
  ASSERT_TRUE(link.start().ok());
  SlaveConfig sc;
  sc.endpoint.transport = Transport::Rtu;
  sc.endpoint.device = link.b_path();
  const DeviceMap map = shipped("laser_source");
  auto laser = started(LaserSourceSim::create(map, sc));
  ASSERT_TRUE(laser);
  Endpoint ep;
  ep.transport = Transport::Rtu;
  ep.device = link.a_path();
  ModbusMaster m(map, quick_master(ep));
  ASSERT_TRUE(m.start().ok());
  ASSERT_TRUE(m.write("power_setpoint_pct", 25).get().ok());
  ASSERT_TRUE(m.write("enable", 1).get().ok());
  ASSERT_TRUE(eventually([&] { return std::abs(read(m, "output_power_w") - 12.5) < 0.01; }));
}

TEST(VirtualDevices, WrongMapIsAnErrorNotACrash) {
  auto made = LaserSourceSim::create(shipped("power_meter"));
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.error().message.find("the laser_source simulator was given the map of device 'power_meter'"),
            std::string::npos)
      << made.error().message;
  DeviceMap cut = shipped("scan_head");
  std::erase_if(cut.registers, [](const RegisterDef& r) { return r.name == "turns_done"; });
  auto head = ScanHeadSim::create(cut);
  ASSERT_FALSE(head.ok());
  EXPECT_NE(head.error().message.find("needs register 'turns_done'"), std::string::npos);
}

}  // namespace
}  // namespace lcnc::drivers
