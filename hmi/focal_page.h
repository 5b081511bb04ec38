// The focal-length screen (docs/design.md §7): the process database's holes with a
// tick each; "Measure selected" runs the focal-length workflow
// (hmi/focal_workflow.h) on a worker thread — the machine visits each hole
// through lasercncd, the displacement sensor reads — with progress and a
// cancel; each hole's distance, new offset or error is shown beside its
// stored offset; "Save offsets" stores the measured ones, all or none.
// Layout and object names in focal_page.ui.
#pragma once

#include <QWidget>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drivers/modbus/modbus_types.h"
#include "hmi/background_task.h"
#include "hmi/focal_workflow.h"
#include "hmi/process_db.h"

class QTableWidget;

namespace Ui {
class FocalPage;
}

namespace lcnc::hmi {

class FocalPage : public QWidget {
  Q_OBJECT

 public:
  // `sensor`: the displacement sensor's endpoint (empty: none, measuring is
  // refused with a message).
  FocalPage(ProcessDatabase& db, std::string shm_name, std::optional<drivers::Endpoint> sensor,
            QWidget* parent = nullptr);
  ~FocalPage() override;

  // Test seams: the table reloaded from the database, holes ticked by
  // number, the workflow started and waited for, the offsets saved.
  void reload();
  void select(const std::vector<std::uint32_t>& holes);
  void measure();
  bool wait_done(int timeout_ms = 60000);
  bool save();
  [[nodiscard]] const std::vector<FocalReading>& readings() const noexcept { return readings_; }
  [[nodiscard]] QString message() const;
  [[nodiscard]] QTableWidget* table() const;

 signals:
  void finished();

 protected:
  // Shown (its tab chosen): the holes as the database has them now.
  void showEvent(QShowEvent* event) override;

 private:
  void present(const std::vector<FocalReading>& readings);
  void show_message(const QString& text, bool error);
  [[nodiscard]] std::vector<HoleRecord> ticked() const;

  std::unique_ptr<Ui::FocalPage> ui_;
  ProcessDatabase& db_;
  std::string shm_name_;
  std::optional<drivers::Endpoint> sensor_;
  std::vector<HoleRecord> holes_;
  std::vector<FocalReading> readings_;
  BackgroundTask<std::vector<FocalReading>> measuring_;
};

}  // namespace lcnc::hmi
