// GoogleTest main for the HMI suites: a QApplication first (QtSql loads its
// drivers through it, the widgets need it), offscreen unless told otherwise.
#include <gtest/gtest.h>

#include <QApplication>

#include "hmi/hmi_font.h"
#include "tests/e2e/e2e_support.h"

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  lcnc::hmi::apply_hmi_font();  // as lasercnc-hmi does: the layout is the named font's
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new e2e::NoLeakedSegments);  // every test removes its segments
  return RUN_ALL_TESTS();
}

// Under ASan (the CI's second pass) LeakSanitizer checks at exit. Qt's
// offscreen platform never frees its screen objects (QScreen, its
// QPlatformScreen, the QObject parts and shared-pointer blocks they own):
// Qt's leak, not ours, and the same in every run. Suppressed by those
// allocation sites only — a leak of our own still shows, since its direct
// allocation is in our code.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libqoffscreen.so\n"
         "leak:QScreen::QScreen\n"
         "leak:QPlatformScreen::QPlatformScreen\n"
         "leak:QWindowSystemInterface::handleScreenAdded\n"
         "leak:QObject::QObject\n"
         "leak:QtSharedPointer::ExternalRefCountData::getAndRef\n";
}
