// What the HMI's screen tests share, beside tests/e2e/e2e_support.h (the
// daemon process, temporary folders): waiting with the event loop running.
#pragma once

#include <unistd.h>

#include <QApplication>
#include <QElapsedTimer>

namespace lcnc::hmi::test {

// Processes events until `done` or the time is up.
template <typename F>
bool wait_until(F done, int ms = 5000) {
  QElapsedTimer t;
  t.start();
  while (!done() && t.elapsed() < ms) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    usleep(5000);
  }
  return done();
}

}  // namespace lcnc::hmi::test
