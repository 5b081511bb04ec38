#include "hmi/process_db_page.h"

#include <QComboBox>
#include <QCoreApplication>
#include <QFileDialog>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QMouseEvent>
#include <QPainter>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "common/output_file.h"
#include "hmi/page_support.h"
#include "holes/hole_table.h"
#include "ui_process_db_page.h"

namespace lcnc::hmi {

// The holes in X Y (y up), framed on them: each a circle of its scan radius
// (at least a few pixels), numbered; a tilted one (A ≠ 0) with a stroke
// along its tool direction; the table's selected rows in the alarm colour.
class HolePlot : public QWidget {
 public:
  HolePlot(const HoleTableModel& model, QItemSelectionModel& selection, QWidget* parent)
      : QWidget(parent), model_(model), selection_(selection) {
    make_canvas(this, "holePlot", 300, 160);
  }
  // Where hole `row` is drawn.
  [[nodiscard]] QPointF at(int row) const {
    const Frame f = frame();
    const Pose& p = model_.record(row).params.position;
    return QPointF(f.ox + p[0] * f.k, f.oy - p[1] * f.k);
  }
  // The row of the hole drawn nearest `px`, within 12 px; −1 if none.
  [[nodiscard]] int row_at(const QPointF& px) const {
    int best = -1;
    double best_d = 12.0;
    for (int r = 0; r < model_.rowCount(); ++r) {
      const double d = QLineF(at(r), px).length();
      if (d <= best_d) best = r, best_d = d;
    }
    return best;
  }

 protected:
  void paintEvent(QPaintEvent*) override {
    QPainter g(this);
    g.setRenderHint(QPainter::Antialiasing);
    if (model_.rowCount() == 0) {
      g.drawText(rect(), Qt::AlignCenter, ProcessDbPage::tr("No holes yet."));
      return;
    }
    const Frame f = frame();
    for (int r = 0; r < model_.rowCount(); ++r) {
      const HoleProcessParams& h = model_.record(r).params;
      const QPointF c = at(r);
      const bool selected = selection_.isRowSelected(r, {});
      const QColor colour = selected ? QColor(kErrorColor) : QColor("#1565c0");
      g.setPen(QPen(colour, selected ? 2.0 : 1.2));
      const double radius = std::max(4.0, h.head.start_radius_mm * f.k);
      g.drawEllipse(c, radius, radius);
      const double a = h.position[3] * std::numbers::pi / 180.0,
                   cz = h.position[5] * std::numbers::pi / 180.0;
      if (h.position[3] != 0.0)  // the tool axis tipped by A, turned by C: its X Y shadow
        g.drawLine(c, c + QPointF(std::sin(a) * std::sin(cz), std::sin(a) * std::cos(cz)) * 24.0);
      g.setPen(Qt::black);
      g.drawText(c + QPointF(radius + 2, -radius - 2), QString::number(h.hole_number));
    }
  }
  void mousePressEvent(QMouseEvent* e) override {
    const int r = row_at(e->pos());
    if (r < 0) return;
    selection_.select(model_.index(r, 0), QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
  }

 private:
  struct Frame {
    double k = 1.0, ox = 0.0, oy = 0.0;
  };
  [[nodiscard]] Frame frame() const {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (int r = 0; r < model_.rowCount(); ++r) {
      const Pose& p = model_.record(r).params.position;
      x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
    }
    const double span = std::max({x1 - x0, y1 - y0, 1.0});
    x0 -= 0.1 * span, x1 += 0.1 * span, y0 -= 0.1 * span, y1 += 0.1 * span;
    const QRectF area(8, 8, width() - 16, height() - 16);
    Frame f;
    f.k = std::min(area.width() / (x1 - x0), area.height() / (y1 - y0));
    f.ox = area.center().x() - 0.5 * (x0 + x1) * f.k;
    f.oy = area.center().y() + 0.5 * (y0 + y1) * f.k;
    return f;
  }
  const HoleTableModel& model_;
  QItemSelectionModel& selection_;
};

namespace {

// The column groups (HoleTableModel's columns): the hole number always; the
// position (X Y Z A C and the focus offset) or the process (the rest).
bool column_shown(int group, int column, int columns) {
  if (group == 0 || column == 0) return true;
  const bool position = column <= 5 || column == columns - 1;
  return group == 1 ? position : !position;
}

}  // namespace

ProcessDbPage::ProcessDbPage(ProcessDatabase& db, std::string shm_name, QWidget* parent)
    : QWidget(parent),
      ui_(std::make_unique<Ui::ProcessDbPage>()),
      db_(db),
      model_(std::make_unique<HoleTableModel>(db)),
      link_(std::move(shm_name)) {
  ui_->setupUi(this);
  ui_->holeTable->setModel(model_.get());
  ui_->holeTable->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  ui_->holeTable->verticalHeader()->hide();  // the hole number is the first column
  connect(model_.get(), &HoleTableModel::refused, this, [this](const QString& m) { show_message(m, true); });
  connect(model_.get(), &QAbstractItemModel::dataChanged, this,
          [this] { show_message(tr("Stored."), false); });
  connect(ui_->addButton, &QPushButton::clicked, this, [this] { add_hole(); });
  connect(ui_->removeButton, &QPushButton::clicked, this, [this] {
    const QModelIndexList rows = ui_->holeTable->selectionModel()->selectedRows();
    for (const QModelIndex& i : rows) {
      const Status s = db_.remove(model_->record(i.row()).params.hole_number);
      if (!s) show_message(QString::fromStdString(s.error().message), true);
    }
    model_->reload();
    update_count();
  });
  connect(ui_->importButton, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Import hole table"), {}, tr("CSV (*.csv)"));
    if (!path.isEmpty()) import_file(path, ProcessDatabase::ImportMode::Merge);
  });
  connect(ui_->exportButton, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export hole table"), {}, tr("CSV (*.csv)"));
    if (!path.isEmpty()) export_file(path);
  });
  connect(ui_->sendButton, &QPushButton::clicked, this, [this] { send_to_controller(); });
  plot_ = new HolePlot(*model_, *ui_->holeTable->selectionModel(), ui_->plotHolder);
  auto* l = new QVBoxLayout(ui_->plotHolder);
  l->setContentsMargins(0, 0, 0, 0);
  l->addWidget(plot_);
  connect(ui_->holeTable->selectionModel(), &QItemSelectionModel::selectionChanged, plot_,
          [this] { plot_->update(); });
  connect(model_.get(), &QAbstractItemModel::modelReset, plot_, [this] { plot_->update(); });
  connect(model_.get(), &QAbstractItemModel::dataChanged, plot_, [this] { plot_->update(); });
  connect(ui_->columnsCombo, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int group) {
    const int n = model_->columnCount();
    for (int c = 0; c < n; ++c) ui_->holeTable->setColumnHidden(c, !column_shown(group, c, n));
  });
  ui_->tableSplitter->setStretchFactor(0, 3);
  ui_->tableSplitter->setStretchFactor(1, 2);
  update_count();
}

QPointF ProcessDbPage::plotted_at(int row) const { return plot_->at(row); }
QWidget* ProcessDbPage::plot() const noexcept { return plot_; }

ProcessDbPage::~ProcessDbPage() = default;

std::string ProcessDbPage::send_to_controller() {
  Result<std::vector<HoleRecord>> holes = db_.holes();
  if (!holes) {
    show_message(QString::fromStdString(holes.error().to_string()), true);
    return {};
  }
  if (holes->empty()) {
    show_message(tr("No holes to send."), true);
    return {};
  }
  std::vector<HoleProcessParams> rows;
  int with_offset = 0;
  for (const HoleRecord& h : *holes) {
    HoleProcessParams p = h.params;
    if (h.focus_offset_mm) {
      p.position[2] += *h.focus_offset_mm;
      ++with_offset;
    }
    rows.push_back(p);
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("lasercnc_hmi_" + std::to_string(QCoreApplication::applicationPid()));
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::string path = (dir / "holes_run.csv").string();
  // replaced whole: the controller may still be reading the last one sent
  if (const Status s =
          write_output(path, {db_.path()}, [&](std::ostream& out) { out << write_hole_table(rows); });
      !s) {
    show_message(tr("Cannot write %1.").arg(QString::fromStdString(path)) + " " +
                     QString::fromStdString(s.error().to_string()),
                 true);
    return {};
  }
  if (!link_.poll() || link_.send(shm::CommandType::Load, 0.0, 0, path) == 0) {
    show_message(tr("Not sent: no link to the controller."), true);
    return {};
  }
  show_message(tr("Sent %1 holes (%2 with a measured focus offset) to the controller; start the cycle on the "
                  "machine screen.")
                   .arg(rows.size())
                   .arg(with_offset),
               false);
  return path;
}

void ProcessDbPage::show_message(const QString& text, bool error) {
  set_message(ui_->messageLabel, text, error);
}

QString ProcessDbPage::message() const { return ui_->messageLabel->text(); }

void ProcessDbPage::update_count() {
  ui_->countLabel->setText(tr("%n hole(s)", nullptr, model_->rowCount()));
}

bool ProcessDbPage::import_file(const QString& path, ProcessDatabase::ImportMode mode) {
  const Status s = db_.import_csv(path.toStdString(), mode);
  model_->reload();
  update_count();
  if (!s) {
    show_message(QString::fromStdString(s.error().to_string()), true);
    return false;
  }
  show_message(tr("Imported %1.").arg(path), false);
  return true;
}

bool ProcessDbPage::export_file(const QString& path) {
  const Status s = db_.export_csv(path.toStdString());
  if (!s) {
    show_message(QString::fromStdString(s.error().to_string()), true);
    return false;
  }
  show_message(tr("Exported %1.").arg(path), false);
  return true;
}

bool ProcessDbPage::add_hole() {
  std::uint32_t next = 1;
  for (int i = 0; i < model_->rowCount(); ++i)
    next = std::max(next, model_->record(i).params.hole_number + 1);
  HoleRecord r;
  r.params.hole_number = next;
  r.params.position << 500.0, 225.0, 0.0, 0.0, 0.0, 0.0;
  const Status s = db_.put(r);
  model_->reload();
  update_count();
  if (!s) {
    show_message(QString::fromStdString(s.error().message), true);
    return false;
  }
  show_message(tr("Hole %1 added.").arg(next), false);
  return true;
}

}  // namespace lcnc::hmi
