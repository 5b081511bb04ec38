#include "hmi/hmi_font.h"

#include <QApplication>
#include <QFontDatabase>

namespace lcnc::hmi {
namespace {
// 12 px: Qt's own default of 9 pt at 96 dpi, the size the screens were
// laid out with.
constexpr int kPixelSize = 12;
}  // namespace

QStringList hmi_font_families() { return {"DejaVu Sans", "WenQuanYi Micro Hei"}; }

QFont hmi_font() {
  QFont f(hmi_font_families().front());
  f.setFamilies(hmi_font_families());
  f.setPixelSize(kPixelSize);
  f.setStyleHint(QFont::SansSerif);
  return f;
}

void apply_hmi_font() { QApplication::setFont(hmi_font()); }

QStringList missing_hmi_font_families() {
  const QStringList installed = QFontDatabase().families();
  QStringList missing;
  for (const QString& f : hmi_font_families())
    if (!installed.contains(f, Qt::CaseInsensitive)) missing << f;
  return missing;
}

}  // namespace lcnc::hmi
