// The HMI's font is the one it names, whatever else the system has: its
// families are installed (the .deb depends on them), the application uses
// them, and Chinese text is drawn from the CJK family of the list rather
// than whatever fontconfig would pick.
#include <gtest/gtest.h>

#include <QApplication>
#include <QFontInfo>
#include <QFontMetrics>
#include <QRawFont>
#include <QTextLayout>

#include "hmi/hmi_font.h"

namespace {

TEST(HmiFont, TheNamedFamiliesAreInstalledAndTheApplicationUsesThem) {
  EXPECT_TRUE(lcnc::hmi::missing_hmi_font_families().isEmpty())
      << lcnc::hmi::missing_hmi_font_families().join(", ").toStdString();
  const QFontInfo used(QApplication::font());
  EXPECT_EQ(used.family().toStdString(), "DejaVu Sans");
  EXPECT_EQ(used.pixelSize(), lcnc::hmi::hmi_font().pixelSize());
}

TEST(HmiFont, ChineseTextIsDrawnFromTheNamedCjkFamily) {
  QTextLayout layout(QString::fromUtf8("激光切割"), lcnc::hmi::hmi_font());
  layout.beginLayout();
  layout.createLine();
  layout.endLayout();
  const QList<QGlyphRun> runs = layout.glyphRuns();
  ASSERT_FALSE(runs.isEmpty());
  for (const QGlyphRun& run : runs)
    EXPECT_EQ(run.rawFont().familyName().toStdString(), "WenQuanYi Micro Hei");
}

}  // namespace
