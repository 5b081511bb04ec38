// The machine screen: DRO, machine state and the job, cycle start / feed
// hold / resume / stop, feed override, e-stop and reset — all through the
// shared-memory link to lasercncd (machine_link.h). Layout in
// machine_page.ui; the page polls the link every kPollPeriod.
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

  explicit MachinePage(const std::string& shm_name, QWidget* parent = nullptr);
  ~MachinePage() override;

  // One poll now (the timer's work; a test seam).
  void refresh();
  [[nodiscard]] MachineLink& link() noexcept { return link_; }

 private:
  void send(shm::CommandType type, double value = 0.0);

  std::unique_ptr<Ui::MachinePage> ui_;
  MachineLink link_;
  QTimer timer_;
};

}  // namespace lcnc::hmi
