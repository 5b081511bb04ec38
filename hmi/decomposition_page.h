// The main + auxiliary axes screen (docs/design.md §5.7): open a DXF part,
// set the contour speed, step, field, main-axis acceleration and mode,
// decompose it in the background (progress per contour), then see S, S1 and
// S2 drawn, a row of figures per contour and the whole part's summary, and
// export the kinematics table as CSV. A bad drawing or an unreachable speed
// is shown with its file:line and what is wrong; the last good result stays
// until a new one replaces it. Layout and object names in
// decomposition_page.ui.
#pragma once

#include <QWidget>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "decompose/decompose_options.h"
#include "decompose/part_decomposition.h"
#include "hmi/background_task.h"

class QTableWidget;

namespace Ui {
class DecompositionPage;
}

namespace lcnc::hmi {

class DecompositionView;

class DecompositionPage : public QWidget {
  Q_OBJECT

 public:
  explicit DecompositionPage(QWidget* parent = nullptr);
  ~DecompositionPage() override;

  // Test seams of the file dialogs and the background work.
  void open_file(const QString& path);
  bool export_table(const QString& path);
  // Starts the decomposition of the open drawing with the options shown.
  void decompose();
  // Waits (processing events) until the decomposition started last is shown.
  bool wait_done(int timeout_ms = 30000);
  [[nodiscard]] bool busy() const noexcept { return decomposing_.running(); }

  [[nodiscard]] const decompose::PartResult* result() const noexcept { return part_ ? &*part_ : nullptr; }
  [[nodiscard]] QString message() const;
  [[nodiscard]] QString summary() const;
  [[nodiscard]] QTableWidget* table() const;
  [[nodiscard]] decompose::Options options() const;

 signals:
  void finished(bool ok);

 private:
  struct Outcome {
    std::optional<decompose::PartResult> part;
    std::optional<Diagnostic> error;
    std::vector<std::string> notes;
    double step_mm = 0;
    decompose::Options options{};
  };
  // progress: contours done of total (−1 while the drawing is read)
  static Outcome work(const std::string& path, double step_mm, decompose::Options opt,
                      TaskProgress& progress);
  void present(const Outcome& o);
  void show_message(const QString& text, bool error);
  void fill_table();

  std::unique_ptr<Ui::DecompositionPage> ui_;
  DecompositionView* view_ = nullptr;
  QString path_;
  std::optional<decompose::PartResult> part_;
  decompose::Options shown_options_{};
  BackgroundTask<Outcome> decomposing_;
};

}  // namespace lcnc::hmi
