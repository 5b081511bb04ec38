// The program screen: a program checked and planned in the background as the
// controller will run it, its toolpath drawn coloured by speed with the
// machine's position on it, loaded into a real lasercncd; a bad program
// shows where and what.
#include <gtest/gtest.h>

#include <QImage>
#include <QPushButton>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "hmi/machine_link.h"
#include "hmi/main_window.h"
#include "hmi/program_page.h"
#include "hmi/toolpath_view.h"
#include "tests/e2e/e2e_support.h"

namespace lcnc::hmi {
namespace {

const QString kBracket = QString(LCNC_SOURCE_DIR) + "/share/examples/bracket.ngc";

TEST(ProgramScreen, PlansTheToolpathColouredBySpeedAndLoadsIt) {
  const std::string shm = "/lcnc_hmi_prog_" + std::to_string(getpid());
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  Result<MachineConfig> m = shipped_machine();
  ASSERT_TRUE(static_cast<bool>(m));
  ProgramPage page(*m, shm);
  page.resize(1000, 600);
  page.show();
  EXPECT_FALSE(page.load());  // nothing planned yet
  page.open_file(kBracket);
  ASSERT_TRUE(page.wait_done());
  ASSERT_TRUE(page.toolpath().has_value()) << page.message().toStdString();
  const Toolpath& t = *page.toolpath();
  EXPECT_GT(t.points.size(), 50u);
  EXPECT_GT(t.time_s, 0.1);
  EXPECT_LE(t.peak_speed, m->axis(Axis::X).max_velocity * std::sqrt(3.0) + 1e-6);
  std::size_t cutting = 0, slow = 0;
  for (const ToolpathPoint& p : t.points) {
    cutting += p.laser ? 1 : 0;
    slow += p.laser && p.speed < 0.5 * t.peak_speed ? 1 : 0;  // the corners' slow-downs
  }
  EXPECT_GT(cutting, 10u);
  EXPECT_GT(slow, 0u);
  EXPECT_TRUE(page.summary().contains("planned time")) << page.summary().toStdString();
  // on the drawing (left of the speed scale): the fast cuts red, the slowed
  // ones (circles, blends) yellow to cyan
  page.refresh();
  const QImage img = page.view()->grab().toImage();
  int fast = 0, slowed = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width() - 100; ++x) {
      const QColor c = img.pixelColor(x, y);
      if (c.saturation() < 200) continue;
      fast += c.hue() <= 15 || c.hue() >= 345 ? 1 : 0;
      slowed += c.hue() >= 50 && c.hue() <= 200 ? 1 : 0;
    }
  EXPECT_GT(fast, 100);
  EXPECT_GT(slowed, 100);
  EXPECT_EQ(ToolpathView::speed_color(0, 100).hue(), 240);
  EXPECT_EQ(ToolpathView::speed_color(100, 100).hue(), 0);
  // into the controller
  ASSERT_TRUE(page.load());
  MachineLink link(shm);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  std::string loaded;
  while (std::chrono::steady_clock::now() < deadline) {
    if (link.poll())
      if (auto j = link.job()) loaded = j->program;
    if (loaded.find("bracket.ngc") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_NE(loaded.find("bracket.ngc"), std::string::npos) << loaded;
}

TEST(ProgramScreen, ABadProgramSaysWhereAndWhat) {
  const auto dir = e2e::temp_dir();
  const auto bad = dir / "bad.ngc";
  std::ofstream(bad) << "G21 G90\nG1 X10 F600\nG1 X2000\nM2\n";
  Result<MachineConfig> m = shipped_machine();
  ASSERT_TRUE(static_cast<bool>(m));
  ProgramPage page(*m, "/lcnc_hmi_prog_none");
  page.open_file(QString::fromStdString(bad.string()));
  ASSERT_TRUE(page.wait_done());
  EXPECT_FALSE(page.toolpath().has_value());
  EXPECT_TRUE(page.message().contains("bad.ngc:3:")) << page.message().toStdString();
  EXPECT_TRUE(page.message().contains("E304")) << page.message().toStdString();
  EXPECT_FALSE(page.findChild<QPushButton*>("loadButton")->isEnabled());
}

}  // namespace
}  // namespace lcnc::hmi

namespace lcnc::hmi {
namespace {

namespace fs = std::filesystem;

TEST(ViewProjection, TopViewIsXYAndTheFrontViewShowsZ) {
  const Vec3 p(10, 20, 30);
  const ScreenPoint top = project(p, kTopView);
  EXPECT_DOUBLE_EQ(top.x, 10);
  EXPECT_DOUBLE_EQ(top.y, 20);
  const ScreenPoint front = project(p, ViewAngles{0.0, 90.0});
  EXPECT_NEAR(front.x, 10, 1e-12);
  EXPECT_NEAR(front.y, 30, 1e-12);
  // from above a helix's turns fall on one circle; in 3D they come apart
  const Vec3 turn1(5, 0, 0), turn2(5, 0, -1);
  EXPECT_NEAR(project(turn1, kTopView).y, project(turn2, kTopView).y, 1e-12);
  EXPECT_GT(std::abs(project(turn1, kIsoView).y - project(turn2, kIsoView).y), 0.5);
  // turning by yaw: X goes where Y was
  const ScreenPoint turned = project(Vec3(1, 0, 0), ViewAngles{90.0, 0.0});
  EXPECT_NEAR(turned.x, 0, 1e-12);
  EXPECT_NEAR(turned.y, 1, 1e-12);
}

TEST(ViewProjection, GridStepsAreOneTwoOrFive) {
  EXPECT_DOUBLE_EQ(nice_step(100, 10), 10);
  EXPECT_DOUBLE_EQ(nice_step(150, 10), 20);
  EXPECT_DOUBLE_EQ(nice_step(40, 10), 5);
  EXPECT_NEAR(nice_step(0.3, 10), 0.05, 1e-15);
}

// A helix, Z moves and a 5-axis bevel: rapids told from cuts, the tool
// axis kept, the 3D view drawing the helix's turns apart, the G-code text
// with the controller's line highlighted.
TEST(ProgramScreen, DrawsIn3DWithTheToolAxisAndShowsTheGcodeLine) {
  const fs::path dir = e2e::temp_dir();
  const fs::path helix = dir / "helix.ngc";
  std::ofstream(helix) << "G21 G90 G64 P0.01\nG0 X100 Y100 Z20\nG1 Z10 F600\nM3 S50\n"
                          "G2 X100 Y100 I10 J0 Z7 P3 F1200\nM5\nG0 Z30\nM2\n";
  Result<MachineConfig> m = shipped_machine();
  ASSERT_TRUE(static_cast<bool>(m));
  ProgramPage page(*m, "/lcnc_hmi_none_3d");
  page.resize(1000, 600);
  page.show();
  page.open_file(QString::fromStdString(helix.string()));
  ASSERT_TRUE(page.wait_done());
  ASSERT_TRUE(page.toolpath().has_value()) << page.message().toStdString();
  const Toolpath& t = *page.toolpath();
  std::size_t rapids = 0, dark_feeds = 0;
  double z_lo = 1e9, z_hi = -1e9;
  for (const ToolpathPoint& p : t.points) {
    rapids += p.rapid ? 1 : 0;
    dark_feeds += !p.rapid && !p.laser && p.speed > 0 ? 1 : 0;  // the G1 Z0 plunge
    if (p.laser) z_lo = std::min(z_lo, p.at.z()), z_hi = std::max(z_hi, p.at.z());
  }
  EXPECT_GT(rapids, 0u);
  EXPECT_GT(dark_feeds, 0u);
  EXPECT_NEAR(z_lo, 7.0, 0.05);
  EXPECT_NEAR(z_hi, 10.0, 0.05);
  EXPECT_FALSE(t.tilted);
  // from above the helix is one circle; in 3D its turns cover more rows
  const auto rows_drawn = [&] {
    const QImage img = page.view()->grab().toImage();
    int rows = 0;
    for (int y = 0; y < img.height() - 60; ++y)
      for (int x = 0; x < img.width() - 100; ++x)
        if (img.pixelColor(x, y).saturation() > 200) {
          ++rows;
          break;
        }
    return rows;
  };
  page.findChild<QPushButton*>("topViewButton")->click();
  const int top_rows = rows_drawn();
  page.findChild<QPushButton*>("isoViewButton")->click();
  EXPECT_DOUBLE_EQ(page.view()->view().pitch_deg, kIsoView.pitch_deg);
  EXPECT_GT(top_rows, 50);
  EXPECT_NE(rows_drawn(), top_rows);
  // the G-code beside it, the line highlighted
  page.set_current_line(5);
  EXPECT_EQ(page.highlighted_text(), "G2 X100 Y100 I10 J0 Z7 P3 F1200");
  page.set_current_line(0);
  EXPECT_EQ(page.highlighted_text(), "");
  // the 5-axis bevel: the tool axis tilts
  page.open_file(QString(LCNC_SOURCE_DIR) + "/share/examples/tcp_bevel.ngc");
  ASSERT_TRUE(page.wait_done());
  ASSERT_TRUE(page.toolpath().has_value()) << page.message().toStdString();
  EXPECT_TRUE(page.toolpath()->tilted);
  double max_tilt_deg = 0;
  for (const ToolpathPoint& p : page.toolpath()->points)
    max_tilt_deg =
        std::max(max_tilt_deg, std::acos(std::clamp(p.axis.z(), -1.0, 1.0)) * 180.0 / 3.14159265358979);
  EXPECT_NEAR(max_tilt_deg, 20.0, 0.5);
}

}  // namespace
}  // namespace lcnc::hmi
