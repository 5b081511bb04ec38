// The machine screen, for an operator's shift: a state banner in the
// state's colour; the work-coordinate DRO (large) with the machine
// coordinates, the distance to go and each axis's homed flag beside it;
// the work system and touch-off (G10 L20, kept by the controller); the job — program, line,
// progress, time left, laser power, how it runs (single block, dry run,
// from a line); cycle start / feed hold / resume / stop, framing, feed
// override that follows the controller, e-stop and reset, jog and home, MDI;
// the alarm list (severity, wall-clock time, repeats counted on one row,
// acknowledge). Each control is enabled only in the states that allow it
// (machine_controls.h). All through the shared-memory link to lasercncd
// (machine_link.h); layout in machine_page.ui; polled every kPollPeriod.
#pragma once

#include <QTimer>
#include <QWidget>

#include <chrono>
#include <memory>
#include <string>

#include "hmi/machine_controls.h"
#include "hmi/machine_link.h"

namespace Ui {
class MachinePage;
}

namespace lcnc::hmi {

class MachinePage : public QWidget {
  Q_OBJECT

 public:
  static constexpr std::chrono::milliseconds kPollPeriod{50};

  explicit MachinePage(const std::string& shm_name, QWidget* parent = nullptr);
  ~MachinePage() override;

  // One poll now (the timer's work; a test seam).
  void refresh();
  [[nodiscard]] MachineLink& link() noexcept { return link_; }
  [[nodiscard]] const AlarmLog& alarms() const noexcept { return alarms_; }
  // The jog and home buttons' work: the selected axis by ±step / home.
  void jog(int direction);
  void home();
  // The MDI line's work: sends it; false (and says why) if not sent.
  bool send_mdi(const QString& gcode);

 private:
  void send(shm::CommandType type, double value = 0.0, std::uint8_t axis = 0, const std::string& text = {});
  void start();
  void take_events();
  void show_alarms();
  void show_status(const shm::Status& st, const shm::JobStatus* job);
  void enable(const ControlView& view);

  std::unique_ptr<Ui::MachinePage> ui_;
  MachineLink link_;
  QTimer timer_;
  AlarmLog alarms_;
  bool alarms_changed_ = false;
  bool job_was_active_ = false;
  double job_started_s_ = 0.0;  // machine time at the job's start (for the time left)
};

}  // namespace lcnc::hmi
