#include "hmi/measure_page.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QHeaderView>
#include <QMessageBox>
#include <QTableWidget>

#include <cmath>
#include <filesystem>

#include "hmi/page_support.h"
#include "ui_measure_page.h"

namespace lcnc::hmi {
namespace {

enum Column { kFace, kApproach, kMeasured, kResidual, kColumns };

QString xyz(const Vec3& v) {
  return QString("%1, %2, %3").arg(v.x(), 0, 'f', 4).arg(v.y(), 0, 'f', 4).arg(v.z(), 0, 'f', 4);
}

// A probe point's face as the operator reads it: "primary 2" → the face's
// word in the screen's language and its number.
QString face_text(const std::string& face) {
  static const char* const kFaces[] = {QT_TRANSLATE_NOOP("MeasurePage", "primary"),
                                       QT_TRANSLATE_NOOP("MeasurePage", "secondary"),
                                       QT_TRANSLATE_NOOP("MeasurePage", "tertiary")};
  const std::size_t space = face.find(' ');
  const std::string word = face.substr(0, space);
  for (const char* f : kFaces) {
    if (word != f) continue;
    const QString name = QCoreApplication::translate("MeasurePage", f);
    return space == std::string::npos ? name : name + QString::fromStdString(face.substr(space));
  }
  return QString::fromStdString(face);
}

}  // namespace

MeasurePage::MeasurePage(ProcessDatabase& db, std::string shm_name, std::string probe_serial, QWidget* parent)
    : QWidget(parent),
      ui_(std::make_unique<Ui::MeasurePage>()),
      db_(db),
      shm_name_(std::move(shm_name)),
      probe_serial_(std::move(probe_serial)),
      confirm_([](QWidget* parent, const QString& title, const QString& text) {
        return QMessageBox::question(parent, title, text) == QMessageBox::Yes;
      }),
      measuring_(
          this, [this](const TaskProgress& p) { ui_->progressBar->setValue(p.done); },
          [this](const MeasureOutcome& o) { present(o); }) {
  ui_->setupUi(this);
  QTableWidget* t = ui_->pointTable;
  t->setColumnCount(kColumns);
  t->setHorizontalHeaderLabels(
      {tr("Point"), tr("Approach X, Y, Z mm; A, C °"), tr("Measured X, Y, Z mm"), tr("Residual mm")});
  t->verticalHeader()->hide();
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  t->horizontalHeader()->setStretchLastSection(true);
  connect(ui_->measureButton, &QPushButton::clicked, this, [this] { measure(); });
  connect(ui_->cancelButton, &QPushButton::clicked, this, [this] { measuring_.cancel(); });
  connect(ui_->applyButton, &QPushButton::clicked, this, [this] {
    if (confirm_(this, tr("Apply the measured placement"),
                 tr("Move every hole of the process database onto the measured placement? "
                    "Their X, Y, Z, A and C are read as drawing coordinates.")))
      apply();
  });
  connect(ui_->bestFitCheck, &QCheckBox::toggled, this, [this] { show_plan(); });
  show_plan();
}

// The planned points, before anything moves.
void MeasurePage::show_plan() {
  QTableWidget* t = ui_->pointTable;
  Result<std::vector<ProbePoint>> planned = plan_321(plan());
  if (planned) {
    MeasureOutcome o;
    o.points = *planned;
    t->setRowCount(static_cast<int>(o.points.size()));
    for (int r = 0; r < static_cast<int>(o.points.size()); ++r) {
      const Pose& a = o.points[r].approach;
      t->setItem(r, kFace, new QTableWidgetItem(face_text(o.points[r].face)));
      t->setItem(r, kApproach,
                 new QTableWidgetItem(xyz(a.head<3>()) +
                                      tr("; %1, %2 (planned)").arg(a[3], 0, 'f', 2).arg(a[5], 0, 'f', 2)));
      for (int c = kMeasured; c < kColumns; ++c) t->setItem(r, c, new QTableWidgetItem());
    }
  }
}

MeasurePage::~MeasurePage() = default;

MeasurePlan MeasurePage::plan() const {
  MeasurePlan p;
  p.block_mm = Vec3(ui_->lengthSpin->value(), ui_->widthSpin->value(), ui_->heightSpin->value());
  p.nominal = Eigen::Translation3d(ui_->nominalXSpin->value(), ui_->nominalYSpin->value(),
                                   ui_->nominalZSpin->value()) *
              Eigen::AngleAxisd(ui_->nominalCSpin->value() * M_PI / 180.0, Vec3::UnitZ());
  p.best_fit = ui_->bestFitCheck->isChecked();
  return p;
}

void MeasurePage::measure() {
  if (measuring_.running()) return;
  if (probe_serial_.empty()) {
    show_message(tr("No 3D probe configured."), true);
    return;
  }
  ui_->measureButton->setEnabled(false);
  ui_->applyButton->setEnabled(false);
  ui_->cancelButton->setEnabled(true);
  ui_->progressBar->setVisible(true);
  ui_->progressBar->setRange(0, plan().best_fit ? 10 : 6);
  ui_->progressBar->setValue(0);
  show_message(tr("Measuring: the machine moves to each point…"), false);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("lasercnc_hmi_" + std::to_string(QCoreApplication::applicationPid()));
  measuring_.start(
      [plan = plan(), dir, shm = shm_name_, dev = probe_serial_, timeout = probe_timeout_](TaskProgress& p) {
        Result<std::unique_ptr<SerialPointProbe>> probe = SerialPointProbe::open(dev, timeout);
        if (!probe) {
          MeasureOutcome o;
          o.error = "3D probe: " + probe.error().to_string();
          return o;
        }
        MachineMover mover(shm, dir);
        return run_measurement(
            plan, mover, **probe, [&p](int done, int) { p.done = done; }, &p.cancel);
      });
}

void MeasurePage::present(const MeasureOutcome& o) {
  ui_->progressBar->setVisible(false);
  ui_->measureButton->setEnabled(true);
  ui_->cancelButton->setEnabled(false);
  outcome_ = o;
  QTableWidget* t = ui_->pointTable;
  t->setRowCount(static_cast<int>(o.points.size()));
  for (int r = 0; r < static_cast<int>(o.points.size()); ++r) {
    const ProbePoint& p = o.points[r];
    const Vec3 a = p.approach.head<3>();
    const QString cells[] = {
        face_text(p.face),
        xyz(a) + QString("; %1, %2").arg(p.approach[3], 0, 'f', 2).arg(p.approach[5], 0, 'f', 2),
        p.measured ? xyz(*p.measured) : QString::fromStdString(p.error),
        p.residual_mm ? QString::number(*p.residual_mm, 'f', 4) : QString()};
    for (int c = 0; c < kColumns; ++c) {
      auto* item = new QTableWidgetItem(cells[c]);
      if (c == kMeasured && !p.measured && !p.error.empty()) item->setForeground(QColor(kErrorColor));
      t->setItem(r, c, item);
    }
  }
  if (!o.fit) {
    ui_->resultLabel->clear();
    show_message(tr("Not measured: %1").arg(QString::fromStdString(o.error)), true);
    emit finished(false);
    return;
  }
  const Eigen::Isometry3d& w = o.fit->work_to_machine;
  const Vec3 x = w.linear().col(0), z = w.linear().col(2);
  const double turn = std::atan2(x.y(), x.x()) * 180.0 / M_PI;
  const double tilt = std::acos(std::clamp(z.z(), -1.0, 1.0)) * 180.0 / M_PI;
  ui_->resultLabel->setText(tr("The block's datum corner at X %1 Y %2 Z %3 mm, turned %4° about Z, its top "
                               "tilted %5°; residuals max %6 mm, rms %7 mm.")
                                .arg(w.translation().x(), 0, 'f', 4)
                                .arg(w.translation().y(), 0, 'f', 4)
                                .arg(w.translation().z(), 0, 'f', 4)
                                .arg(turn, 0, 'f', 4)
                                .arg(tilt, 0, 'f', 4)
                                .arg(o.fit->max_residual_mm, 0, 'f', 4)
                                .arg(o.fit->rms_residual_mm, 0, 'f', 4));
  ui_->applyButton->setEnabled(true);
  show_message(o.error.empty() ? tr("Measured. Apply the placement to the holes when it looks right.")
                               : QString::fromStdString(o.error),
               !o.error.empty());
  emit finished(true);
}

bool MeasurePage::apply() {
  if (!outcome_ || !outcome_->fit) {
    show_message(tr("Nothing measured to apply."), true);
    return false;
  }
  Result<std::vector<HoleRecord>> holes = db_.holes();
  if (!holes) {
    show_message(QString::fromStdString(holes.error().to_string()), true);
    return false;
  }
  Result<std::vector<std::pair<std::uint32_t, Pose>>> placed =
      placed_holes(*holes, outcome_->fit->work_to_machine);
  if (!placed) {
    show_message(QString::fromStdString(placed.error().to_string()), true);
    return false;
  }
  if (Status s = db_.set_positions(*placed); !s) {
    show_message(QString::fromStdString(s.error().to_string()), true);
    return false;
  }
  ui_->applyButton->setEnabled(false);  // once: the holes are in machine coordinates now
  show_message(tr("Moved %n hole(s) onto the measured placement.", nullptr, static_cast<int>(placed->size())),
               false);
  return true;
}

bool MeasurePage::wait_done(int timeout_ms) { return measuring_.wait(timeout_ms); }

void MeasurePage::show_message(const QString& text, bool error) {
  set_message(ui_->messageLabel, text, error);
}

QString MeasurePage::message() const { return ui_->messageLabel->text(); }
QString MeasurePage::result_text() const { return ui_->resultLabel->text(); }
QTableWidget* MeasurePage::table() const { return ui_->pointTable; }

}  // namespace lcnc::hmi
