// The laser cutting screen: a DXF part planned as `lasercnc cut` plans it
// (holes before the outline), saved as G-code, loaded into a real lasercncd
// and run there; a drawing without units asks for them.
#include <gtest/gtest.h>

#include <QComboBox>
#include <QPushButton>

#include <fstream>
#include <string>

#include "hmi/cut_page.h"
#include "hmi/machine_link.h"
#include "tests/e2e/e2e_support.h"
#include "tests/hmi/hmi_test_support.h"

namespace lcnc::hmi {
namespace {

namespace fs = std::filesystem;
using test::wait_until;

const QString kCutPlate = QString::fromStdString(e2e::kSample);

TEST(CutScreen, PlansHolesBeforeTheOutlineSavesAndRunsTheProgram) {
  const fs::path dir = e2e::temp_dir();
  qputenv("XDG_DATA_HOME", QByteArray::fromStdString((dir / "data").string()));  // the operator's cut folder
  const std::string shm = "/lcnc_hmi_cut_" + std::to_string(getpid());
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  CutPage page(shm);
  EXPECT_FALSE(page.findChild<QPushButton*>("saveButton")->isEnabled());
  ASSERT_TRUE(page.open_file(kCutPlate)) << page.message().toStdString();
  ASSERT_TRUE(page.cut_plan().has_value());
  const cut::CutPlan& plan = *page.cut_plan();
  ASSERT_GE(plan.contours.size(), 2u);
  EXPECT_GT(plan.holes, 0u);
  // every hole before the outline that holds it
  EXPECT_FALSE(plan.contours.back().hole);
  for (std::size_t i = 0; i + 1 < plan.contours.size(); ++i) EXPECT_TRUE(plan.contours[i].hole) << i;
  EXPECT_TRUE(page.summary().contains("holes first")) << page.summary().toStdString();
  EXPECT_TRUE(page.findChild<QPushButton*>("saveButton")->isEnabled());
  // saved, the program checks
  const fs::path ngc = dir / "plate.ngc";
  ASSERT_TRUE(page.save(QString::fromStdString(ngc.string()))) << page.message().toStdString();
  EXPECT_EQ(e2e::slurp(ngc), page.gcode());
  EXPECT_NE(page.gcode().find("M3 S"), std::string::npos);
  const e2e::CmdResult check = e2e::lasercnc("check " + ngc.string());
  EXPECT_EQ(check.exit_code, 0) << check.err;
  // loaded into the controller from the operator's cut folder, and run there
  ASSERT_TRUE(page.load()) << page.message().toStdString();
  const std::string loaded = (dir / "data" / "lasercnc" / "cut" / "plate_decompose.ngc").string();
  MachineLink link(shm);
  std::string program;
  EXPECT_TRUE(wait_until([&] {
    if (link.poll())
      if (auto j = link.job()) program = j->program;
    return program == loaded;
  })) << program;
  const e2e::CmdResult run = e2e::lasercnc("send start --wait --timeout 60 --shm " + shm);
  EXPECT_EQ(run.exit_code, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("job done"), std::string::npos) << run.out;
}

TEST(CutScreen, ADrawingWithoutUnitsAsksForThem) {
  const fs::path dir = e2e::temp_dir();
  const fs::path dxf = dir / "tiny.dxf";
  std::ofstream(dxf) << "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\nCUT\n90\n4\n70\n1\n"
                        "10\n0\n20\n0\n10\n0.5\n20\n0\n10\n0.5\n20\n0.5\n10\n0\n20\n0.5\n0\nENDSEC\n0\nEOF\n";
  CutPage page("/lcnc_hmi_cut_none");
  EXPECT_FALSE(page.open_file(QString::fromStdString(dxf.string())));
  EXPECT_FALSE(page.cut_plan().has_value());
  EXPECT_TRUE(page.message().contains("units")) << page.message().toStdString();
  EXPECT_FALSE(page.findChild<QPushButton*>("saveButton")->isEnabled());
  // inches: half an inch square, planned
  page.findChild<QComboBox*>("unitsCombo")->setCurrentIndex(2);
  ASSERT_TRUE(page.plan()) << page.message().toStdString();
  EXPECT_EQ(page.cut_plan()->contours.size(), 1u);
  EXPECT_NEAR(page.cut_plan()->cut_mm, 4 * 12.7, 2.0);
}

}  // namespace
}  // namespace lcnc::hmi
