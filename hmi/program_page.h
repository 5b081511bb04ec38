// The program screen: open a G-code program; it is checked and planned in
// the background (progress) with the machine's config, exactly as the
// controller will run it, and its toolpath drawn with the blends visible and
// each move coloured by speed (hmi/toolpath_view.h), the machine's position
// on it live; the summary (lines, length, planned time, peak speed); "Load
// into the controller" sends it to lasercncd (cycle start is on the machine
// screen). An error in the program shows with its file:line:col. Layout and
// object names in program_page.ui.
#pragma once

#include <QTimer>
#include <QWidget>

#include <memory>
#include <optional>
#include <string>

#include "hmi/background_task.h"
#include "hmi/machine_link.h"
#include "hmi/toolpath.h"
#include "machine/machine_config.h"

namespace Ui {
class ProgramPage;
}

namespace lcnc::hmi {

class ToolpathView;

class ProgramPage : public QWidget {
  Q_OBJECT

 public:
  ProgramPage(MachineConfig machine, std::string shm_name, QWidget* parent = nullptr);
  ~ProgramPage() override;

  // Test seams.
  void open_file(const QString& path);
  bool wait_done(int timeout_ms = 60000);
  bool load();
  void refresh();  // the machine's position (the timer's work)
  [[nodiscard]] const std::optional<Toolpath>& toolpath() const noexcept { return path_; }
  [[nodiscard]] QString message() const;
  [[nodiscard]] QString summary() const;
  [[nodiscard]] ToolpathView* view() const noexcept { return view_; }

 signals:
  void finished(bool ok);

 private:
  struct Outcome {
    std::optional<Toolpath> path;
    std::optional<Diagnostic> error;
  };
  void present(const Outcome& o);
  void show_message(const QString& text, bool error);

  std::unique_ptr<Ui::ProgramPage> ui_;
  MachineConfig machine_;
  MachineLink link_;
  ToolpathView* view_ = nullptr;
  QString program_;
  std::optional<Toolpath> path_;
  QTimer timer_;  // the machine's position
  BackgroundTask<Outcome> planning_;
};

}  // namespace lcnc::hmi
