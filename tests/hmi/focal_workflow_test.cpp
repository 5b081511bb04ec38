// The focal-length workflow against a real lasercncd (over shared memory)
// and the simulated displacement sensor (real Modbus TCP), which rides on
// the simulated carriage: each hole visited, its focus offset the simulated
// surface's height above the hole's Z within the sensor's noise, a hole out
// of reach or out of range an error of its own, and the offsets saved all
// or none.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <QPushButton>
#include <QTableWidget>

#include "hmi/focal_page.h"
#include "hmi/focal_workflow.h"
#include "hmi/machine_mover.h"
#include "hmi/process_db.h"
#include "hmi/sim_peripherals.h"
#include "tests/e2e/e2e_support.h"

namespace lcnc::hmi {
namespace {

HoleRecord hole(std::uint32_t n, double x, double y, double z) {
  HoleRecord r;
  r.params.hole_number = n;
  r.params.position << x, y, z, 0.0, 0.0, 0.0;
  return r;
}

TEST(FocalWorkflow, MeasuresEachHolesFocusOffsetOnTheSimulatedMachine) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_focal_");
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  auto sims = SimPeripherals::start(shm);
  ASSERT_TRUE(static_cast<bool>(sims)) << sims.error().to_string();
  auto sensor = ModbusDistanceSensor::connect((*sims)->sensor_endpoint(), 16);
  ASSERT_TRUE(static_cast<bool>(sensor)) << sensor.error().to_string();
  MachineMover mover(shm, e2e::temp_dir() / "moves");
  // the surface is z = 20 mm at 0,0, tilted and wavy; holes planned at z 20
  const std::vector<HoleRecord> holes = {
      hole(1, 100, 50, 20), hole(2, 400, 300, 20), hole(3, 700, 120, 21.5),
      hole(4, 200, 200, 480),   // 50 mm above: Z 530 beyond the travel
      hole(5, 300, 100, 0.0)};  // sensor at 50: the surface ~20 mm off, out of range
  int calls = 0;
  const std::vector<FocalReading> r =
      run_focal(holes, mover, **sensor, FocalConfig{}, [&](int done, int total) {
        ++calls;
        EXPECT_EQ(total, 5);
        EXPECT_EQ(done, calls);
      });
  ASSERT_EQ(r.size(), 5u);
  EXPECT_EQ(calls, 5);
  const drivers::SurfaceModel& s = (*sims)->surface();
  for (int i : {0, 1, 2}) {
    ASSERT_TRUE(r[i].offset_mm.has_value()) << r[i].error;
    const double x = holes[i].params.position[0], y = holes[i].params.position[1];
    const double truth = s.z_at(x, y) - holes[i].params.position[2];
    // σ = 2 µm per sample, 16 averaged: 0.5 µm; the DRO at 1 µm steps
    EXPECT_NEAR(*r[i].offset_mm, truth, 0.005) << "hole " << r[i].hole;
    EXPECT_NEAR(r[i].at[2], holes[i].params.position[2] + 50.0, 1e-9);
  }
  EXPECT_GT(std::abs(*r[2].offset_mm - *r[0].offset_mm), 0.1);  // the surface's tilt is seen
  EXPECT_FALSE(r[3].offset_mm.has_value());
  EXPECT_NE(r[3].error.find("Z530.000: beyond the machine's travel"), std::string::npos) << r[3].error;
  EXPECT_FALSE(r[4].offset_mm.has_value());
  EXPECT_NE(r[4].error.find("no surface in its range"), std::string::npos) << r[4].error;
  // the machine stands over the last hole it could reach
  Result<Pose> at = mover.position();
  ASSERT_TRUE(static_cast<bool>(at));
  EXPECT_NEAR((*at)[0], 300.0, 1e-3);
  EXPECT_NEAR((*at)[2], 50.0, 1e-3);

  // saved all or none
  const std::string dbp = (e2e::temp_dir() / "p.db").string();
  auto db = ProcessDatabase::open(dbp);
  ASSERT_TRUE(static_cast<bool>(db));
  for (const HoleRecord& h : holes)
    if (h.params.position[2] <= 450.0) {  // hole 4's Z is off the table's range
      ASSERT_TRUE((*db)->put(h).ok());
    }
  const auto offsets = offsets_to_save(r);
  ASSERT_EQ(offsets.size(), 3u);
  ASSERT_TRUE((*db)->set_focus_offsets(offsets).ok());
  EXPECT_NEAR(*(*(*db)->hole(2))->focus_offset_mm, *r[1].offset_mm, 1e-12);
  EXPECT_FALSE((*(*db)->hole(5))->focus_offset_mm.has_value());
  // one bad offset: nothing of the batch is stored
  std::vector<std::pair<std::uint32_t, double>> bad = {{1, 0.5}, {2, 99.0}};
  EXPECT_FALSE((*db)->set_focus_offsets(bad).ok());
  EXPECT_NEAR(*(*(*db)->hole(1))->focus_offset_mm, *r[0].offset_mm, 1e-12);
  EXPECT_GT((*sims)->follows(), 3u);
}

TEST(FocalWorkflow, ALostLinkEndsTheRunAndSaysSo) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_focal_");
  auto sims = SimPeripherals::start(shm);
  ASSERT_TRUE(static_cast<bool>(sims));
  auto sensor = ModbusDistanceSensor::connect((*sims)->sensor_endpoint(), 1);
  ASSERT_TRUE(static_cast<bool>(sensor));
  MachineMover mover(shm, e2e::temp_dir() / "moves");  // no daemon at all
  FocalConfig c;
  c.move_timeout = std::chrono::milliseconds(300);
  const std::vector<FocalReading> r =
      run_focal({hole(1, 100, 50, 20), hole(2, 200, 50, 20)}, mover, **sensor, c);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NE(r[0].error.find("no link to lasercncd"), std::string::npos) << r[0].error;
  EXPECT_NE(r[1].error.find("not measured"), std::string::npos) << r[1].error;
  EXPECT_FALSE(r[0].offset_mm || r[1].offset_mm);
}

// The screen: tick, measure (progress, a worker thread), see, save.
TEST(FocalScreen, MeasuresTheTickedHolesShowsEachAndSavesTheOffsets) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_focal_");
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  auto sims = SimPeripherals::start(shm);
  ASSERT_TRUE(static_cast<bool>(sims));
  auto db = ProcessDatabase::open((e2e::temp_dir() / "p.db").string());
  ASSERT_TRUE(static_cast<bool>(db));
  for (const HoleRecord& h : {hole(1, 100, 50, 20), hole(2, 400, 300, 20), hole(3, 600, 100, 460)})
    ASSERT_TRUE((*db)->put(h).ok());
  FocalPage page(**db, shm, (*sims)->sensor_endpoint());
  QTableWidget* t = page.table();
  ASSERT_EQ(t->rowCount(), 3);
  page.measure();  // nothing ticked
  EXPECT_TRUE(page.message().contains("Tick the holes")) << page.message().toStdString();
  page.select({1, 3});
  page.findChild<QPushButton*>("measureButton")->click();
  EXPECT_FALSE(page.findChild<QPushButton*>("measureButton")->isEnabled());
  EXPECT_TRUE(page.findChild<QPushButton*>("cancelButton")->isEnabled());
  ASSERT_TRUE(page.wait_done());
  ASSERT_EQ(page.readings().size(), 2u);
  const double truth = (*sims)->surface().z_at(100, 50) - 20.0;
  EXPECT_NEAR(t->item(0, 6)->text().toDouble(), truth, 0.005) << t->item(0, 7)->text().toStdString();
  EXPECT_EQ(t->item(0, 7)->text(), "measured");
  EXPECT_TRUE(t->item(1, 6)->text().isEmpty());  // not ticked
  EXPECT_TRUE(t->item(2, 7)->text().contains("travel")) << t->item(2, 7)->text().toStdString();
  EXPECT_TRUE(page.message().contains("1 measured, 1 not")) << page.message().toStdString();
  ASSERT_TRUE(page.findChild<QPushButton*>("saveButton")->isEnabled());
  ASSERT_TRUE(page.save());
  EXPECT_NEAR(*(*(*db)->hole(1))->focus_offset_mm, truth, 0.005);
  EXPECT_FALSE((*(*db)->hole(3))->focus_offset_mm.has_value());
  EXPECT_NEAR(t->item(0, 4)->text().toDouble(), truth, 0.005);  // the stored column, reloaded
}

}  // namespace
}  // namespace lcnc::hmi
