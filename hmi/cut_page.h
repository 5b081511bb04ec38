// The laser cutting screen (CypCut's workflow): open a DXF part, set the
// kerf, lead-in and lead-out, feed, power, pierce time, direction and (when
// the drawing does not say) its units; the cut is planned as `lasercnc cut`
// plans it (core/cut/cut_program.h: inner contours before outer, kerf
// offset to the scrap side, a lead-in from the scrap side) and drawn — the
// drawing grey, the cut paths in order, outlines blue and holes green, the
// lead-ins and overcuts red, the pierce points with their numbers — then
// saved as G-code or loaded into lasercncd. Layout in cut_page.ui.
#pragma once

#include <QWidget>

#include <memory>
#include <optional>
#include <string>

#include "cut/cut_program.h"
#include "dxf/drawing.h"
#include "hmi/machine_link.h"

namespace Ui {
class CutPage;
}

namespace lcnc::hmi {

class CutView;

class CutPage : public QWidget {
  Q_OBJECT

 public:
  explicit CutPage(std::string shm_name, QWidget* parent = nullptr);
  ~CutPage() override;

  // Test seams: the buttons' work.
  bool open_file(const QString& path);  // reads and plans; false (and why) if not
  bool plan();                          // again, with the options as set
  bool save(const QString& path);       // the G-code
  bool load();                          // saved to the operator's cut folder, loaded into lasercncd
  [[nodiscard]] const std::optional<cut::CutPlan>& cut_plan() const noexcept { return plan_; }
  [[nodiscard]] QString message() const;
  [[nodiscard]] QString summary() const;
  [[nodiscard]] std::string gcode() const;

 private:
  [[nodiscard]] cut::CutOptions options() const;
  void show_message(const QString& text, bool error);

  std::unique_ptr<Ui::CutPage> ui_;
  MachineLink link_;
  CutView* view_ = nullptr;
  QString file_;
  std::optional<dxf::Drawing> drawing_;
  std::optional<cut::CutPlan> plan_;
};

}  // namespace lcnc::hmi
