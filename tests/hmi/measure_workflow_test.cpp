// The six-point 3D measurement against a real lasercncd (over shared memory)
// and the simulated probe on the head (its RS-232 protocol on a pty), which
// finds a block clamped a little off its nominal place and turned: the
// points are approached along their faces' normals (A = 90° for the side
// faces), the 3-2-1 frame comes out as the block's true placement within
// the probe's noise, and the holes moved with it are stored all or none.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <QPushButton>
#include <QRegularExpression>
#include <QTableWidget>

#include "hmi/machine_mover.h"
#include "hmi/measure_page.h"
#include "hmi/measure_workflow.h"
#include "hmi/process_db.h"
#include "hmi/sim_peripherals.h"
#include "tests/e2e/e2e_support.h"

namespace lcnc::hmi {
namespace {

// The probe's answer, waited for as long as a loaded computer may need to
// schedule the simulated probe's thread: a bound on a failure, never a wait.
constexpr std::chrono::milliseconds kPatience{30000};

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

TEST(MeasureWorkflow, PlansSixPointsWithTheToolAxisAlongEachFacesNormal) {
  MeasurePlan plan;
  plan.nominal = Eigen::Translation3d(400, 150, 60) * Eigen::Isometry3d::Identity();
  Result<std::vector<ProbePoint>> pts = plan_321(plan);
  ASSERT_TRUE(static_cast<bool>(pts));
  ASSERT_EQ(pts->size(), 6u);
  EXPECT_EQ((*pts)[0].approach[3], 0.0);                     // top: straight down
  EXPECT_NEAR((*pts)[0].approach[2], 65.0, 1e-9);            // 5 mm above the top
  EXPECT_NEAR(std::abs((*pts)[3].approach[3]), 90.0, 1e-9);  // the front face: tilted
  EXPECT_NEAR((*pts)[3].approach[1], 145.0, 1e-9);           // 5 mm in front of it
  EXPECT_NEAR((*pts)[5].approach[0], 395.0, 1e-9);           // 5 mm left of the left face
  plan.block_mm = Vec3(0, 1, 1);
  EXPECT_FALSE(static_cast<bool>(plan_321(plan)));
}

TEST(MeasureWorkflow, FindsTheBlocksPlacementOnTheSimulatedMachine) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_meas_");
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  const drivers::WorkpieceBlock truth = default_sim_block();
  auto sims = SimPeripherals::start(shm, truth);
  ASSERT_TRUE(static_cast<bool>(sims)) << sims.error().to_string();
  auto probe = SerialPointProbe::open((*sims)->probe_serial_path(), kPatience);
  ASSERT_TRUE(static_cast<bool>(probe)) << probe.error().to_string();
  MachineMover mover(shm, e2e::temp_dir() / "moves");
  MeasurePlan plan;
  plan.block_mm = truth.size_mm;
  // the operator's guess: 1 mm off in X and Y, not turned
  plan.nominal = Eigen::Translation3d(401, 149, 60) * Eigen::Isometry3d::Identity();
  int calls = 0;
  const MeasureOutcome o = run_measurement(plan, mover, **probe, [&](int done, int total) {
    EXPECT_EQ(total, 6);
    EXPECT_EQ(done, ++calls);
  });
  ASSERT_TRUE(o.fit.has_value()) << o.error;
  EXPECT_TRUE(o.error.empty()) << o.error;
  EXPECT_EQ(calls, 6);
  const Eigen::Isometry3d& t = o.fit->work_to_machine;
  // σ = 1 µm along each ray; the DRO at 1 µm: the corner within 0.01 mm,
  // the orientation within 0.01°
  EXPECT_LT((t.translation() - truth.work_to_machine.translation()).norm(), 0.01)
      << t.translation().transpose();
  EXPECT_LT(angle_deg(t.linear(), truth.work_to_machine.linear()), 0.01);
  EXPECT_LT(o.fit->max_residual_mm, 0.01);
  for (const ProbePoint& p : o.points) {
    ASSERT_TRUE(p.measured.has_value()) << p.face << ": " << p.error;
    // every measured point lies on its face of the true block
    const Vec3 w = truth.work_to_machine.inverse() * *p.measured;
    EXPECT_NEAR(p.normal_work.dot(w - p.planned_work), 0.0, 0.005) << p.face;
  }
  // the machine is back above the part, head upright
  Result<Pose> at = mover.position();
  ASSERT_TRUE(static_cast<bool>(at));
  EXPECT_GE((*at)[2], 79.99);  // the clearance plane: 20 mm over the top
  EXPECT_NEAR((*at)[3], 0.0, 1e-6);

  // the holes, drawn on the block, moved onto the machine: all or none
  auto db = ProcessDatabase::open((e2e::temp_dir() / "p.db").string());
  ASSERT_TRUE(static_cast<bool>(db));
  std::vector<HoleRecord> holes;
  for (std::uint32_t n = 1; n <= 3; ++n) {
    HoleRecord h;
    h.params.hole_number = n;
    h.params.position << 50.0 * n, 50.0, 0.0, 0.0, 0.0, 0.0;  // on the top face
    holes.push_back(h);
    ASSERT_TRUE((*db)->put(h).ok());
  }
  Result<std::vector<std::pair<std::uint32_t, Pose>>> placed = placed_holes(holes, t);
  ASSERT_TRUE(static_cast<bool>(placed));
  ASSERT_TRUE((*db)->set_positions(*placed).ok());
  const Pose h2 = (*(*db)->hole(2))->params.position;
  const Vec3 true_h2 = truth.work_to_machine * Vec3(100.0, 50.0, 0.0);
  EXPECT_LT((h2.head<3>() - true_h2).norm(), 0.01);
  // the hole's axis follows the top face's tilt (0.3° about X)
  EXPECT_NEAR(std::abs(h2[3]), 0.3, 0.01);
}

// Ten points and the best fit on faces: the same placement, each point's
// residual its distance from its face.
TEST(MeasureWorkflow, BestFitOnTenPointsFindsThePlacementToo) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_meas_");
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  const drivers::WorkpieceBlock truth = default_sim_block();
  auto sims = SimPeripherals::start(shm, truth);
  ASSERT_TRUE(static_cast<bool>(sims));
  auto probe = SerialPointProbe::open((*sims)->probe_serial_path(), kPatience);
  ASSERT_TRUE(static_cast<bool>(probe));
  MachineMover mover(shm, e2e::temp_dir() / "moves");
  MeasurePlan plan;
  plan.block_mm = truth.size_mm;
  plan.nominal = Eigen::Translation3d(401, 149, 60) * Eigen::Isometry3d::Identity();
  plan.best_fit = true;
  const MeasureOutcome o = run_measurement(plan, mover, **probe);
  ASSERT_TRUE(o.fit.has_value()) << o.error;
  ASSERT_EQ(o.points.size(), 10u);
  EXPECT_EQ(o.fit->residuals_mm.size(), 10u);
  EXPECT_LT((o.fit->work_to_machine.translation() - truth.work_to_machine.translation()).norm(), 0.01);
  EXPECT_LT(angle_deg(o.fit->work_to_machine.linear(), truth.work_to_machine.linear()), 0.01);
  EXPECT_LT(o.fit->max_residual_mm, 0.01);
  EXPECT_GT(o.fit->max_residual_mm, 0.0);  // ten points on six unknowns: the noise shows
}

TEST(MeasureWorkflow, APointThatFindsNoFaceEndsTheRunAndSaysWhich) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_meas_");
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  auto sims = SimPeripherals::start(shm);
  ASSERT_TRUE(static_cast<bool>(sims));
  auto probe = SerialPointProbe::open((*sims)->probe_serial_path(), kPatience);
  ASSERT_TRUE(static_cast<bool>(probe));
  MachineMover mover(shm, e2e::temp_dir() / "moves");
  MeasurePlan plan;
  plan.nominal = Eigen::Translation3d(400, 150, 90) * Eigen::Isometry3d::Identity();  // 30 mm too high
  const MeasureOutcome o = run_measurement(plan, mover, **probe);
  EXPECT_FALSE(o.fit.has_value());
  EXPECT_NE(o.error.find("primary 1"), std::string::npos) << o.error;
  EXPECT_NE(o.error.find("no surface"), std::string::npos) << o.error;
}

// The screen: measure (a worker thread, progress), see the points and the
// placement, apply it to the database's holes once.
TEST(MeasureScreen, MeasuresShowsThePlacementAndMovesTheHoles) {
  const std::string shm = e2e::shm_name("/lcnc_hmi_meas_");
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  auto sims = SimPeripherals::start(shm);
  ASSERT_TRUE(static_cast<bool>(sims));
  auto db = ProcessDatabase::open((e2e::temp_dir() / "p.db").string());
  ASSERT_TRUE(static_cast<bool>(db));
  HoleRecord h;
  h.params.hole_number = 1;
  h.params.position << 100.0, 50.0, 0.0, 0.0, 0.0, 0.0;
  ASSERT_TRUE((*db)->put(h).ok());
  MeasurePage none(**db, shm, "");
  none.measure();
  EXPECT_TRUE(none.message().contains("No 3D probe")) << none.message().toStdString();
  EXPECT_FALSE(none.apply());

  MeasurePage page(**db, shm, (*sims)->probe_serial_path());
  page.set_probe_timeout(kPatience);
  EXPECT_EQ(page.table()->rowCount(), 6);  // the plan, before anything moves
  page.findChild<QPushButton*>("measureButton")->click();
  EXPECT_TRUE(page.findChild<QPushButton*>("cancelButton")->isEnabled());
  ASSERT_TRUE(page.wait_done());
  ASSERT_TRUE(page.outcome() && page.outcome()->fit) << page.message().toStdString();
  const QRegularExpressionMatch m =
      QRegularExpression("corner at X ([0-9.]+) Y ([0-9.]+) Z ([0-9.]+) mm, turned ([-0-9.]+)")
          .match(page.result_text());
  ASSERT_TRUE(m.hasMatch()) << page.result_text().toStdString();
  EXPECT_NEAR(m.captured(1).toDouble(), 400.0, 0.01);
  EXPECT_NEAR(m.captured(2).toDouble(), 150.0, 0.01);
  EXPECT_NEAR(m.captured(3).toDouble(), 60.0, 0.01);
  EXPECT_NEAR(m.captured(4).toDouble(), 1.5, 0.01);
  EXPECT_FALSE(page.table()->item(5, 2)->text().isEmpty());
  // the button asks first: a no leaves the holes where they are, a yes moves them
  auto* apply = page.findChild<QPushButton*>("applyButton");
  ASSERT_TRUE(apply->isEnabled());
  QString asked;
  page.set_confirm([&](QWidget*, const QString&, const QString& text) {
    asked = text;
    return false;
  });
  apply->click();
  EXPECT_TRUE(asked.contains("Move every hole")) << asked.toStdString();
  EXPECT_LT(((*(*db)->hole(1))->params.position.head<3>() - Vec3(100.0, 50.0, 0.0)).norm(), 1e-9);
  EXPECT_TRUE(apply->isEnabled());
  page.set_confirm([](QWidget*, const QString&, const QString&) { return true; });
  apply->click();
  EXPECT_FALSE(apply->isEnabled());  // once
  const Vec3 truth = (*sims)->block().work_to_machine * Vec3(100.0, 50.0, 0.0);
  EXPECT_LT(((*(*db)->hole(1))->params.position.head<3>() - truth).norm(), 0.01);
}

}  // namespace
}  // namespace lcnc::hmi
