// lasercnc-hmi's main window: one tab per screen (process database,
// machine; the measurement, focal-length, adjustment and monitoring screens
// join them), and rendering every screen to PNG for --screenshot.
#pragma once

#include <QMainWindow>
#include <QStringList>

#include <memory>
#include <string>

#include "hmi/process_db.h"

class QTabWidget;

namespace lcnc::hmi {

class DecompositionPage;
class MachinePage;
class ProcessDbPage;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  MainWindow(ProcessDatabase& db, const std::string& shm_name, QWidget* parent = nullptr);
  ~MainWindow() override;

  // Renders each screen to DIR/<objectName>.png; the files written.
  QStringList screenshot_all(const QString& dir);
  [[nodiscard]] QTabWidget* screens() const noexcept { return tabs_; }
  [[nodiscard]] DecompositionPage* decomposition() const noexcept { return decomposition_page_; }

 private:
  QTabWidget* tabs_;
  ProcessDbPage* db_page_;
  MachinePage* machine_page_;
  DecompositionPage* decomposition_page_;
};

}  // namespace lcnc::hmi
