#include "hmi/decomposition_page.h"

#include <QCoreApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QHeaderView>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>

#include "common/output_file.h"
#include "decompose/decompose_tolerances.h"
#include "decompose/kinematics_table.h"
#include "dxf/dxf_reader.h"
#include "hmi/decomposition_view.h"
#include "hmi/page_support.h"
#include "ui_decomposition_page.h"

namespace lcnc::hmi {
namespace {

using decompose::kG_mm_s2;

const char* const kColumnTitles[] = {"#",
                                     QT_TRANSLATE_NOOP("DecompositionPage", "first entity"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "length mm"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "points"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "time s"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "τ s"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "main a mm/s²"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "main v mm/s"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "aux v mm/s"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "aux max mm"),
                                     QT_TRANSLATE_NOOP("DecompositionPage", "a_eff mm/s²")};

}  // namespace

DecompositionPage::DecompositionPage(QWidget* parent)
    : QWidget(parent),
      ui_(std::make_unique<Ui::DecompositionPage>()),
      decomposing_(
          this,
          [this](const TaskProgress& p) {
            const int total = p.total;
            ui_->progressBar->setRange(0, std::max(total, 0));  // 0, 0: busy while reading
            if (total > 0) ui_->progressBar->setValue(p.done);
          },
          [this](const Outcome& o) { present(o); }, std::chrono::milliseconds(50)) {
  ui_->setupUi(this);
  view_ = new DecompositionView(ui_->viewHolder);
  auto* holder = new QVBoxLayout(ui_->viewHolder);
  holder->setContentsMargins(0, 0, 0, 0);
  holder->addWidget(view_);
  QTableWidget* t = ui_->contourTable;
  t->setColumnCount(static_cast<int>(std::size(kColumnTitles)));
  QStringList headers;
  for (const char* c : kColumnTitles) headers << QCoreApplication::translate("DecompositionPage", c);
  t->setHorizontalHeaderLabels(headers);
  t->verticalHeader()->hide();
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  connect(ui_->openButton, &QPushButton::clicked, this, [this] {
    const QString p = QFileDialog::getOpenFileName(this, tr("Open drawing"), {}, tr("DXF (*.dxf)"));
    if (!p.isEmpty()) open_file(p);
  });
  connect(ui_->decomposeButton, &QPushButton::clicked, this, [this] { decompose(); });
  connect(ui_->exportButton, &QPushButton::clicked, this, [this] {
    const QString p =
        QFileDialog::getSaveFileName(this, tr("Export kinematics table"), {}, tr("CSV (*.csv)"));
    if (!p.isEmpty()) export_table(p);
  });
}

DecompositionPage::~DecompositionPage() = default;

void DecompositionPage::open_file(const QString& path) {
  path_ = path;
  ui_->fileLabel->setText(QFileInfo(path).fileName());
  ui_->fileLabel->setToolTip(path);
  ui_->decomposeButton->setEnabled(!decomposing_.running());
  show_message(tr("Drawing %1: set the options and decompose.").arg(path), false);
}

decompose::Options DecompositionPage::options() const {
  decompose::Options o;
  o.mode = ui_->modeCombo->currentIndex() == 1 ? decompose::Mode::Seed : decompose::Mode::Sync;
  o.speed_mm_s = ui_->speedSpin->value() * 1000.0 / 60.0;
  o.aux_half_field_mm = ui_->fieldSpin->value() / 2.0;
  o.main_accel_mm_s2 = ui_->accelSpin->value() * kG_mm_s2;
  return o;
}

void DecompositionPage::decompose() {
  if (decomposing_.running() || path_.isEmpty()) return;
  ui_->decomposeButton->setEnabled(false);
  ui_->progressBar->setVisible(true);
  ui_->progressBar->setRange(0, 0);
  show_message(tr("Decomposing…"), false);
  decomposing_.start([path = path_.toStdString(), step = ui_->stepSpin->value(),
                      opt = options()](TaskProgress& p) { return work(path, step, opt, p); },
                     -1);
}

// The worker thread: read, prepare (chain, discretize, check), then each
// contour on its own so the screen can show how far it is.
DecompositionPage::Outcome DecompositionPage::work(const std::string& path, double step_mm,
                                                   decompose::Options opt, TaskProgress& progress) {
  Outcome o;
  o.step_mm = step_mm;
  o.options = opt;
  const auto fail = [&](Diagnostic d) {
    if (d.file.empty()) d.file = path;
    o.error = std::move(d);
    return o;
  };
  if (Status s = decompose::check_options(opt); !s) return fail(s.error());
  Result<dxf::ReadResult> read = dxf::read_dxf_file(path, {});
  if (!read) return fail(read.error());
  o.notes = read->notes;
  Result<decompose::PreparedPart> prep = decompose::prepare_part(read->drawing, step_mm);
  if (!prep) return fail(prep.error());
  progress.total = static_cast<int>(prep->contours.size());
  decompose::PartResult all;
  for (std::size_t i = 0; i < prep->contours.size(); ++i) {
    decompose::PreparedPart one;
    one.contours.push_back(prep->contours[i]);
    one.polylines.push_back(prep->polylines[i]);
    Result<decompose::PartResult> r = decompose::decompose_prepared(one, opt);
    if (!r) return fail(r.error());
    all.points += r->points;
    for (decompose::ContourResult& c : r->contours) all.contours.push_back(std::move(c));
    progress.done = static_cast<int>(i + 1);
  }
  o.part = std::move(all);
  return o;
}

void DecompositionPage::present(const Outcome& o) {
  ui_->progressBar->setVisible(false);
  ui_->decomposeButton->setEnabled(!path_.isEmpty());
  if (o.error) {
    // the last good result stays on screen; the error says what is wrong
    show_message(QString::fromStdString(o.error->to_string()), true);
    emit finished(false);
    return;
  }
  part_ = o.part;
  shown_options_ = o.options;
  view_->set_result(&*part_, o.options.aux_half_field_mm);
  fill_table();
  double total_t = 0, a_main = 0, a_eff = 0, aux_max = 0, exact = 0;
  int exceeded = 0;
  for (const decompose::ContourResult& c : part_->contours) {
    total_t += c.peaks.duration_s;
    a_main = std::max(a_main, c.peaks.a_main);
    a_eff = std::max(a_eff, c.peaks.a_eff);
    aux_max = std::max(aux_max, c.peaks.aux_excursion);
    exact = std::max(exact, c.peaks.exactness);
    exceeded += static_cast<int>(c.exceeded.size());
  }
  QString s = tr("%1 contours, %2 points at %3 mm; time %4 s; peak main-axis acceleration %5 mm/s² "
                 "(%6 g), effective %7 mm/s² — %8× lower on the main axes; aux excursion %9 mm; "
                 "|S1 + S2 − S| ≤ %10 mm")
                  .arg(part_->contours.size())
                  .arg(part_->points)
                  .arg(o.step_mm)
                  .arg(total_t, 0, 'f', 4)
                  .arg(a_main, 0, 'f', 1)
                  .arg(a_main / kG_mm_s2, 0, 'f', 3)
                  .arg(a_eff, 0, 'f', 1)
                  .arg(a_main > 0 ? a_eff / a_main : 0.0, 0, 'f', 1)
                  .arg(aux_max, 0, 'f', 4)
                  .arg(exact, 0, 'e', 1);
  ui_->summaryLabel->setText(s);
  ui_->exportButton->setEnabled(true);
  QString msg = tr("Decomposed.");
  if (exceeded > 0)
    msg =
        tr("The published algorithm breaks %n limit(s) (see the table's tooltips); "
           "the synchronous mode guarantees them.",
           nullptr, exceeded);
  for (const std::string& n : o.notes) msg += "\n" + QString::fromStdString(n);
  show_message(msg, exceeded > 0);
  emit finished(true);
}

void DecompositionPage::fill_table() {
  QTableWidget* t = ui_->contourTable;
  t->setRowCount(static_cast<int>(part_->contours.size()));
  int row = 0;
  for (const decompose::ContourResult& c : part_->contours) {
    const decompose::Peaks& p = c.peaks;
    const QString first =
        QString::fromUtf8(dxf::entity_name(c.contour.first_kind)) + tr(" line %1").arg(c.contour.first_line);
    const QString cells[] = {QString::number(c.contour.index),
                             first,
                             QString::number(c.polyline.length_mm, 'f', 3),
                             QString::number(c.polyline.size()),
                             QString::number(p.duration_s, 'f', 4),
                             QString::number(c.tau_s, 'f', 4),
                             QString::number(p.a_main, 'f', 1),
                             QString::number(p.v_main, 'f', 1),
                             QString::number(p.v_aux, 'f', 1),
                             QString::number(p.aux_excursion, 'f', 4),
                             QString::number(p.a_eff, 'f', 1)};
    QString tip;
    for (const std::string& e : c.exceeded) tip += QString::fromStdString(e) + "\n";
    for (int col = 0; col < static_cast<int>(std::size(cells)); ++col) {
      auto* item = new QTableWidgetItem(cells[col]);
      if (col >= 2) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      if (!tip.isEmpty()) {
        item->setToolTip(tip.trimmed());
        item->setForeground(QColor(kErrorColor));
      }
      t->setItem(row, col, item);
    }
    ++row;
  }
}

bool DecompositionPage::export_table(const QString& path) {
  if (!part_) {
    show_message(tr("Nothing to export: decompose a drawing first."), true);
    return false;
  }
  std::vector<const decompose::KinematicsTable*> tables;
  for (const decompose::ContourResult& c : part_->contours) tables.push_back(&c.table);
  if (const Status s = write_output(path.toStdString(), {path_.toStdString()},
                                    [&](std::ostream& f) { decompose::write_csv(f, tables); });
      !s) {
    show_message(tr("Cannot write %1.").arg(path) + " " + QString::fromStdString(s.error().to_string()),
                 true);
    return false;
  }
  show_message(tr("Exported %1.").arg(path), false);
  return true;
}

bool DecompositionPage::wait_done(int timeout_ms) { return decomposing_.wait(timeout_ms); }

void DecompositionPage::show_message(const QString& text, bool error) {
  set_message(ui_->messageLabel, text, error);
}

QString DecompositionPage::message() const { return ui_->messageLabel->text(); }
QString DecompositionPage::summary() const { return ui_->summaryLabel->text(); }
QTableWidget* DecompositionPage::table() const { return ui_->contourTable; }

}  // namespace lcnc::hmi
