// The HMI's font: named, not whatever fontconfig answers for the platform's
// default family. A panel PC's screen is 1280 × 800 and every screen is laid
// out to fit it in English, Chinese and Russian; that only holds for the
// font it was measured with. Left to fontconfig, "Helvetica" or "Sans Serif"
// resolves to DejaVu Sans on one system and to Nimbus Sans (ghostscript's
// URW fonts) or an X11 bitmap font on another, with other widths and line
// heights: the same screens then grow past the panel.
//
// So the HMI asks for its families by name, in order: DejaVu Sans for Latin
// and Cyrillic, WenQuanYi Micro Hei for Chinese (glyphs the first lacks fall
// back to the next in the list, not to fontconfig's choice), at a size in
// pixels (independent of the screen's DPI). Both come with the .deb's
// dependencies (fonts-dejavu-core, fonts-wqy-microhei) and scripts/deps.sh.
#pragma once

#include <QFont>
#include <QStringList>

namespace lcnc::hmi {

// The families, in the order glyphs are looked up.
[[nodiscard]] QStringList hmi_font_families();
// The HMI's font (the application's default).
[[nodiscard]] QFont hmi_font();
// Makes hmi_font() the application's font; call after QApplication is made.
void apply_hmi_font();
// The families of hmi_font_families() this system lacks (fontconfig would
// substitute another font for each): empty when the HMI looks as designed.
[[nodiscard]] QStringList missing_hmi_font_families();

}  // namespace lcnc::hmi
