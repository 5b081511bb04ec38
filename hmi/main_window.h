// lasercnc-hmi's main window: one tab per screen (machine, program and
// toolpath, process database, 3D measurement, focal length, laser and head adjustment and
// monitoring, main + auxiliary axes), and rendering every screen to PNG for
// --screenshot.
#pragma once

#include <QMainWindow>
#include <QStringList>

#include <memory>
#include <optional>
#include <string>

#include "drivers/modbus/modbus_types.h"

#include "hmi/process_db.h"
#include "machine/machine_config.h"

class QTabWidget;

namespace lcnc::hmi {

class CutPage;
class DecompositionPage;
class AdjustPage;
class FocalPage;
class MeasurePage;
class ProgramPage;
class MachinePage;
class ProcessDbPage;

// Where the peripherals the screens use are (empty: none).
struct PeripheralEndpoints {
  std::optional<drivers::Endpoint> sensor;              // displacement sensor
  std::string probe_serial;                             // the 3D probe's serial device
  std::optional<drivers::Endpoint> laser, meter, head;  // laser source, power meter, scan head
};

// The shipped default machine config ($LASERCNC_SHARE, else the source
// tree's share/).
[[nodiscard]] Result<MachineConfig> shipped_machine();

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  // `machine`: the machine config the program screen plans with (null: the
  // shipped default, share/machines/default.toml).
  MainWindow(ProcessDatabase& db, const std::string& shm_name, const PeripheralEndpoints& peripherals = {},
             const MachineConfig* machine = nullptr, QWidget* parent = nullptr);
  ~MainWindow() override;

  // Renders each screen to DIR/<objectName>.png; the files written.
  QStringList screenshot_all(const QString& dir);
  [[nodiscard]] QTabWidget* screens() const noexcept { return tabs_; }
  [[nodiscard]] DecompositionPage* decomposition() const noexcept { return decomposition_page_; }
  [[nodiscard]] FocalPage* focal() const noexcept { return focal_page_; }
  [[nodiscard]] MeasurePage* measure() const noexcept { return measure_page_; }
  [[nodiscard]] AdjustPage* adjust() const noexcept { return adjust_page_; }
  [[nodiscard]] ProgramPage* program() const noexcept { return program_page_; }
  [[nodiscard]] CutPage* cutting() const noexcept { return cut_page_; }

 private:
  QTabWidget* tabs_;
  ProcessDbPage* db_page_;
  MachinePage* machine_page_;
  DecompositionPage* decomposition_page_;
  FocalPage* focal_page_;
  MeasurePage* measure_page_;
  AdjustPage* adjust_page_;
  ProgramPage* program_page_;
  CutPage* cut_page_;
};

}  // namespace lcnc::hmi
