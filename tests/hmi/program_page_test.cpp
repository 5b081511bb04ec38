// The program screen: a program checked and planned in the background as the
// controller will run it, its toolpath drawn coloured by speed with the
// machine's position on it, loaded into a real lasercncd; a bad program
// shows where and what.
#include <gtest/gtest.h>

#include <QImage>
#include <QPushButton>

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
