// The laser and head adjustment and monitoring screen (Shao 2022 Fig. 9):
// the laser source's power setpoint, emission gate and alarm reset with its
// read-back (state, monitor-diode power, pump temperature, alarms); the
// power meter's reading and a power-over-time plot (setpoint, laser output,
// measured, the last 60 s); the four-beam scanning head's parameters (fields
// 12–17, written as one block: the device refuses a bad one whole) with run
// and read-back; and the terminal: each device's link and request counters.
// Every device is polled on a thread of its own (hmi/device_poller.h); the
// screen's timer only shows snapshots. Layout and object names in
// adjust_page.ui.
#pragma once

#include <QTimer>
#include <QWidget>

#include <memory>
#include <optional>
#include <vector>

#include "drivers/modbus/modbus_types.h"
#include "hmi/device_poller.h"

class QTableWidget;

namespace Ui {
class AdjustPage;
}

namespace lcnc::hmi {

class PowerPlot;

struct AdjustEndpoints {
  std::optional<drivers::Endpoint> laser, meter, head;
};

class AdjustPage : public QWidget {
  Q_OBJECT

 public:
  explicit AdjustPage(const AdjustEndpoints& at, QWidget* parent = nullptr);
  ~AdjustPage() override;

  // Test seams: the read-back shown now; the plot's samples.
  void refresh();
  // Waits until every configured device has been polled once (--screenshot).
  bool wait_polled(int timeout_ms = 2000);
  [[nodiscard]] QString message() const;
  [[nodiscard]] QTableWidget* links() const;
  [[nodiscard]] std::size_t plot_samples() const;
  [[nodiscard]] DevicePoller* laser() const noexcept { return laser_.get(); }
  [[nodiscard]] DevicePoller* head() const noexcept { return head_.get(); }

 private:
  void show_message(const QString& text, bool error);

  std::unique_ptr<Ui::AdjustPage> ui_;
  std::unique_ptr<DevicePoller> laser_, meter_, head_;
  PowerPlot* plot_ = nullptr;
  QTimer timer_;
};

}  // namespace lcnc::hmi
