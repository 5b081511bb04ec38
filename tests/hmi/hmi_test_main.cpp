// GoogleTest main for the HMI suites: a QCoreApplication first (QtSql loads
// its drivers through it; widgets get a QApplication of their own).
#include <gtest/gtest.h>

#include <QCoreApplication>

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
