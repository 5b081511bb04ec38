// The machine screen: DRO, machine state and the job, cycle start / feed
// hold / resume / stop, feed override, e-stop and reset, jog and home of an
// axis, and the alarm list (the kernel's events: faults in the alarm colour,
// newest first, kept up to kMaxAlarmRows) — all through the shared-memory
// link to lasercncd (machine_link.h). Layout in machine_page.ui; the page
// polls the link every kPollPeriod.
#pragma once

#include <QTimer>
#include <QWidget>

#include <chrono>
#include <memory>

#include "hmi/machine_link.h"

namespace Ui {
class MachinePage;
}

namespace lcnc::hmi {

class MachinePage : public QWidget {
  Q_OBJECT

 public:
  static constexpr std::chrono::milliseconds kPollPeriod{50};
  static constexpr int kMaxAlarmRows = 500;

  explicit MachinePage(const std::string& shm_name, QWidget* parent = nullptr);
  ~MachinePage() override;

  // One poll now (the timer's work; a test seam).
  void refresh();
  [[nodiscard]] MachineLink& link() noexcept { return link_; }
  // The jog and home buttons' work: the selected axis by ±step / home.
  void jog(int direction);
  void home();

 private:
  void send(shm::CommandType type, double value = 0.0, std::uint8_t axis = 0);
  void take_events();

  std::unique_ptr<Ui::MachinePage> ui_;
  MachineLink link_;
  QTimer timer_;
  double period_s_ = 75e-6;  // machine time per period (the events carry periods)
};

}  // namespace lcnc::hmi
