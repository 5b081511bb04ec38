// The 3D-measurement screen (six-point positioning, docs/design.md §7): the drawing's
// block and where it nominally stands, 3-2-1 or a best fit on ten points;
// "Measure" runs the
// workflow (hmi/measure_workflow.h) on a worker thread with progress and a
// cancel, each point's approach, measured point and residual shown; the
// fitted placement (corner, turn and tilt, residuals); "Apply to the
// holes…" asks, then moves every hole of the process database with it (all
// or none). Layout and object names in measure_page.ui.
#pragma once

#include <QWidget>

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "hmi/background_task.h"
#include "hmi/measure_workflow.h"
#include "hmi/process_db.h"

class QTableWidget;

namespace Ui {
class MeasurePage;
}

namespace lcnc::hmi {

class MeasurePage : public QWidget {
  Q_OBJECT

 public:
  // `probe_serial`: the 3D probe's serial device (empty: none).
  MeasurePage(ProcessDatabase& db, std::string shm_name, std::string probe_serial, QWidget* parent = nullptr);
  ~MeasurePage() override;

  // Test seams: the workflow started and waited for; the fit applied
  // without the question (the button asks first).
  [[nodiscard]] MeasurePlan plan() const;
  void measure();
  bool wait_done(int timeout_ms = 120000);
  bool apply();
  [[nodiscard]] const std::optional<MeasureOutcome>& outcome() const noexcept { return outcome_; }
  [[nodiscard]] QString message() const;
  [[nodiscard]] QString result_text() const;
  [[nodiscard]] QTableWidget* table() const;
  // How long the probe's answer is waited for (SerialPointProbe::open).
  void set_probe_timeout(std::chrono::milliseconds t) { probe_timeout_ = t; }
  // The operator's yes or no before the placement is applied (a question
  // box by default; a test answers it in code).
  using Confirm = std::function<bool(QWidget* parent, const QString& title, const QString& text)>;
  void set_confirm(Confirm confirm) { confirm_ = std::move(confirm); }

 signals:
  void finished(bool ok);

 private:
  void present(const MeasureOutcome& o);
  void show_plan();
  void show_message(const QString& text, bool error);

  std::unique_ptr<Ui::MeasurePage> ui_;
  ProcessDatabase& db_;
  std::string shm_name_, probe_serial_;
  std::chrono::milliseconds probe_timeout_ = SerialPointProbe::kAnswerTimeout;
  std::optional<MeasureOutcome> outcome_;
  Confirm confirm_;
  BackgroundTask<MeasureOutcome> measuring_;
};

}  // namespace lcnc::hmi
