// The main + auxiliary axes screen offscreen, found by object name: a DXF
// decomposed in the background with progress, its figures the library's own,
// S / S1 / S2 drawn, the table exported; a bad drawing and an unreachable
// speed shown with where and what, the last good result kept.
#include <gtest/gtest.h>

#include <unistd.h>

#include <QDoubleSpinBox>
#include <QImage>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "decompose/part_decomposition.h"
#include "dxf/dxf_reader.h"
#include "hmi/decomposition_page.h"
#include "tests/e2e/e2e_support.h"

namespace lcnc::hmi {
namespace {

namespace fs = std::filesystem;

const QString kStar = QString(LCNC_SOURCE_DIR) + "/share/examples/star_decompose.dxf";
const QString kPlate = QString::fromStdString(e2e::kSample);
const QString kBad = QString(LCNC_SOURCE_DIR) + "/tests/data/dxf/bad_number.dxf";

using e2e::temp_dir;

template <typename T>
T* child(QWidget& w, const char* name) {
  T* c = w.findChild<T*>(name);
  EXPECT_NE(c, nullptr) << name;
  return c;
}

// How many pixels of the picture are mostly this channel (antialiased lines
// blend with the white: the channel stands out, its value need not be 255).
enum class Hue { Red, Green, Blue };
int pixels_of(const QImage& img, Hue h) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const QColor p = img.pixelColor(x, y);
      const int r = p.red(), g = p.green(), b = p.blue();
      const bool hit = h == Hue::Red     ? r - std::max(g, b) > 80
                       : h == Hue::Green ? g - std::max(r, b) > 50
                                         : b - std::max(r, g) > 80;
      n += hit ? 1 : 0;
    }
  return n;
}

TEST(DecompositionScreen, DecomposesInTheBackgroundDrawsThePathsAndExportsTheTable) {
  DecompositionPage page;
  page.resize(1100, 640);
  page.show();
  auto* decompose = child<QPushButton>(page, "decomposeButton");
  EXPECT_FALSE(decompose->isEnabled());  // nothing open yet
  page.open_file(kStar);
  EXPECT_TRUE(decompose->isEnabled());
  child<QDoubleSpinBox>(page, "stepSpin")->setValue(0.05);
  decompose->click();
  EXPECT_TRUE(page.busy());
  EXPECT_TRUE(child<QProgressBar>(page, "progressBar")->isVisible());
  EXPECT_FALSE(decompose->isEnabled());  // one at a time
  ASSERT_TRUE(page.wait_done());
  EXPECT_FALSE(child<QProgressBar>(page, "progressBar")->isVisible());
  ASSERT_NE(page.result(), nullptr) << page.message().toStdString();
  // the library's own figures, contour by contour
  Result<dxf::ReadResult> read = dxf::read_dxf_file(kStar.toStdString(), {});
  ASSERT_TRUE(static_cast<bool>(read));
  Result<decompose::PartResult> direct = decompose::decompose_part(read->drawing, 0.05, page.options());
  ASSERT_TRUE(static_cast<bool>(direct));
  QTableWidget* table = page.table();
  ASSERT_EQ(table->rowCount(), static_cast<int>(direct->contours.size()));
  for (int r = 0; r < table->rowCount(); ++r) {
    EXPECT_EQ(table->item(r, 6)->text(), QString::number(direct->contours[r].peaks.a_main, 'f', 1)) << r;
    EXPECT_EQ(table->item(r, 3)->text(), QString::number(direct->contours[r].polyline.size())) << r;
  }
  EXPECT_TRUE(page.summary().contains("contours")) << page.summary().toStdString();
  EXPECT_TRUE(page.summary().contains("lower on the main axes")) << page.summary().toStdString();
  // S green, S1 blue, S2 red on the screen
  const QImage img = page.grab().toImage();
  EXPECT_GT(pixels_of(img, Hue::Green), 200);
  EXPECT_GT(pixels_of(img, Hue::Blue), 200);
  EXPECT_GT(pixels_of(img, Hue::Red), 200);
  // the kinematics table, every row of every contour
  const fs::path csv = temp_dir() / "table.csv";
  ASSERT_TRUE(page.export_table(QString::fromStdString(csv.string())));
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("contour,i,x_mm,y_mm,p_mm,q_mm,t_s", 0), 0u) << header;
  std::size_t rows = 0, expected = 0;
  for (std::string l; std::getline(in, l);) ++rows;
  for (const decompose::ContourResult& c : direct->contours) expected += c.table.size();
  EXPECT_EQ(rows, expected);
  for (const fs::directory_entry& e : fs::directory_iterator(csv.parent_path()))  // no temporary file left
    EXPECT_NE(e.path().filename().string().rfind(".table.csv.", 0), 0u) << e.path();
}

TEST(DecompositionScreen, ABadDrawingOrSpeedSaysWhereAndWhatAndKeepsTheLastResult) {
  DecompositionPage page;
  page.open_file(kStar);
  child<QDoubleSpinBox>(page, "stepSpin")->setValue(0.05);
  page.decompose();
  ASSERT_TRUE(page.wait_done());
  ASSERT_NE(page.result(), nullptr);
  const std::size_t contours = page.result()->contours.size();
  // a malformed file: its name, line and code
  page.open_file(kBad);
  page.decompose();
  ASSERT_TRUE(page.wait_done());
  EXPECT_TRUE(page.message().contains("bad_number.dxf:")) << page.message().toStdString();
  EXPECT_TRUE(page.message().contains("E601")) << page.message().toStdString();
  ASSERT_NE(page.result(), nullptr);
  EXPECT_EQ(page.result()->contours.size(), contours);  // the last good one stays
  EXPECT_EQ(page.table()->rowCount(), static_cast<int>(contours));
  // a contour speed the limits cannot meet: refused with the highest feasible
  page.open_file(kPlate);
  child<QDoubleSpinBox>(page, "speedSpin")->setValue(30.0);
  page.decompose();
  ASSERT_TRUE(page.wait_done());
  EXPECT_TRUE(page.message().contains("E611")) << page.message().toStdString();
  EXPECT_TRUE(page.message().contains("the highest feasible is")) << page.message().toStdString();
  EXPECT_EQ(page.result()->contours.size(), contours);
  // and nothing to export is said so
  DecompositionPage fresh;
  EXPECT_FALSE(fresh.export_table(QString::fromStdString((temp_dir() / "x.csv").string())));
  EXPECT_TRUE(fresh.message().contains("Nothing to export")) << fresh.message().toStdString();
}

}  // namespace
}  // namespace lcnc::hmi
