// What the HMI's screens share: the message line (an error in the alarm
// colour) and waiting, with the event loop running, for a screen's work on a
// worker thread to be shown (the tests' and --screenshot's seam).
#pragma once

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QLabel>
#include <QPalette>
#include <QWidget>

namespace lcnc::hmi {

inline constexpr const char* kErrorColor = "#b00020";
inline constexpr const char* kErrorStyle = "color: #b00020;";

inline void set_message(QLabel* label, const QString& text, bool error) {
  label->setText(text);
  label->setStyleSheet(error ? kErrorStyle : "");
}

// A drawing's widget: named, white, at least `w` × `h`.
inline void make_canvas(QWidget* canvas, const char* name, int w, int h) {
  canvas->setObjectName(name);
  canvas->setMinimumSize(w, h);
  canvas->setAutoFillBackground(true);
  QPalette p = canvas->palette();
  p.setColor(QPalette::Window, Qt::white);
  canvas->setPalette(p);
}

// Processes events while `busy` holds, up to `timeout_ms`; true once not busy.
inline bool wait_while(const bool& busy, int timeout_ms) {
  QElapsedTimer timer;
  timer.start();
  while (busy && timer.elapsed() < timeout_ms) QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  return !busy;
}

}  // namespace lcnc::hmi
