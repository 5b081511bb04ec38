// The process-database screen: the holes as a table to edit in place
// (every edit validated and stored at once, a refusal shown with the field
// and range; the columns all, or those of the position or of the process),
// and below it the holes plotted where they are (X Y, numbered, the tilted
// ones with their tool direction, the selected ones marked; a click on a
// hole selects its row); add and remove holes, import and export the CSV
// hole table; send the holes to lasercncd as a drilling job, each hole's Z
// raised by its measured focus offset (the focal-length workflow's) — the
// run takes the database as it is. Layout and object names in
// process_db_page.ui.
#pragma once

#include <QPointF>
#include <QWidget>

#include <memory>
#include <string>

#include "hmi/hole_table_model.h"
#include "hmi/machine_link.h"
#include "hmi/process_db.h"

namespace Ui {
class ProcessDbPage;
}

namespace lcnc::hmi {

class ProcessDbPage : public QWidget {
  Q_OBJECT

 public:
  ProcessDbPage(ProcessDatabase& db, std::string shm_name = {}, QWidget* parent = nullptr);
  ~ProcessDbPage() override;

  [[nodiscard]] HoleTableModel& model() noexcept { return *model_; }
  // Where the plot draws the hole of table row `row` (its pixel; a test seam).
  [[nodiscard]] QPointF plotted_at(int row) const;
  [[nodiscard]] QWidget* plot() const noexcept;
  // Test seams of the file dialogs: import/export this path.
  bool import_file(const QString& path, ProcessDatabase::ImportMode mode);
  bool export_file(const QString& path);
  // The holes as the run takes them (Z + focus offset), written as a hole
  // table and loaded into lasercncd; the file sent, or empty when not.
  std::string send_to_controller();
  // A new hole (the next free number, a valid helix at the table's centre).
  bool add_hole();
  // The message line (a refusal, or what an import did).
  [[nodiscard]] QString message() const;

 private:
  void show_message(const QString& text, bool error);
  void update_count();

  std::unique_ptr<Ui::ProcessDbPage> ui_;
  ProcessDatabase& db_;
  std::unique_ptr<HoleTableModel> model_;
  class HolePlot* plot_ = nullptr;
  MachineLink link_;
};

}  // namespace lcnc::hmi
