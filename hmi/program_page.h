// The program screen: open a G-code program; it is checked and planned in
// the background (progress) with the machine's config, exactly as the
// controller will run it, and its toolpath drawn with the blends visible and
// each move coloured by speed (hmi/toolpath_view.h: from above or in 3D,
// turned with the mouse), the machine's position on it live; the G-code text
// beside it, the line the controller runs highlighted; the summary (lines, length, planned time, peak speed); "Load
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
  // Highlights program line `line` (1-based) in the G-code text and shows
  // it; 0: none. The timer does it with the controller's line while this
  // program is the one loaded there.
  void set_current_line(std::uint32_t line);
  [[nodiscard]] std::uint32_t current_line() const noexcept { return current_line_; }
  [[nodiscard]] QString highlighted_text() const;
  // The G-code text shown: the program's first 8 MiB (a longer program is
  // planned and drawn whole, its text shown up to there).
  static constexpr qint64 kMaxShownBytes = 8 << 20;

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
  std::uint32_t current_line_ = 0;
  std::optional<Toolpath> path_;
  QTimer timer_;  // the machine's position
  BackgroundTask<Outcome> planning_;
};

}  // namespace lcnc::hmi
