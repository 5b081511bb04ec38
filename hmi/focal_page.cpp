#include "hmi/focal_page.h"

#include <QCoreApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QHeaderView>
#include <QTableWidget>

#include <filesystem>

#include "hmi/page_support.h"
#include "ui_focal_page.h"

namespace lcnc::hmi {
namespace {

enum Column { kHole, kX, kY, kZ, kStored, kDistance, kOffset, kStatus, kColumns };

}  // namespace

FocalPage::FocalPage(ProcessDatabase& db, std::string shm_name, std::optional<drivers::Endpoint> sensor,
                     QWidget* parent)
    : QWidget(parent),
      ui_(std::make_unique<Ui::FocalPage>()),
      db_(db),
      shm_name_(std::move(shm_name)),
      sensor_(std::move(sensor)),
      measuring_(
          this,
          [this](const TaskProgress& p) {
            ui_->progressBar->setRange(0, p.total);
            ui_->progressBar->setValue(p.done);
          },
          [this](const std::vector<FocalReading>& r) { present(r); }) {
  ui_->setupUi(this);
  QTableWidget* t = ui_->holeTable;
  t->setColumnCount(kColumns);
  t->setHorizontalHeaderLabels({tr("Hole"), tr("X mm"), tr("Y mm"), tr("Z mm"), tr("Stored offset mm"),
                                tr("Distance mm"), tr("New offset mm"), tr("Status")});
  t->verticalHeader()->hide();
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  t->horizontalHeader()->setStretchLastSection(true);
  connect(ui_->reloadButton, &QPushButton::clicked, this, [this] { reload(); });
  connect(ui_->selectAllButton, &QPushButton::clicked, this, [this] {
    for (int r = 0; r < ui_->holeTable->rowCount(); ++r)
      ui_->holeTable->item(r, kHole)->setCheckState(Qt::Checked);
  });
  connect(ui_->measureButton, &QPushButton::clicked, this, [this] { measure(); });
  connect(ui_->cancelButton, &QPushButton::clicked, this, [this] { measuring_.cancel(); });
  connect(ui_->saveButton, &QPushButton::clicked, this, [this] { save(); });
  reload();
}

FocalPage::~FocalPage() = default;

void FocalPage::reload() {
  Result<std::vector<HoleRecord>> holes = db_.holes();
  if (!holes) {
    show_message(QString::fromStdString(holes.error().to_string()), true);
    return;
  }
  holes_ = std::move(holes).value();
  QTableWidget* t = ui_->holeTable;
  t->setRowCount(static_cast<int>(holes_.size()));
  for (int r = 0; r < static_cast<int>(holes_.size()); ++r) {
    const HoleRecord& h = holes_[r];
    auto* n = new QTableWidgetItem(QString::number(h.params.hole_number));
    n->setFlags(n->flags() | Qt::ItemIsUserCheckable);
    n->setCheckState(Qt::Unchecked);
    t->setItem(r, kHole, n);
    for (int c : {kX, kY, kZ}) {
      auto* i = new QTableWidgetItem(QString::number(h.params.position[c - kX], 'f', 3));
      i->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      t->setItem(r, c, i);
    }
    t->setItem(r, kStored,
               new QTableWidgetItem(h.focus_offset_mm ? QString::number(*h.focus_offset_mm, 'f', 4)
                                                      : QStringLiteral("—")));
    for (int c : {kDistance, kOffset, kStatus}) t->setItem(r, c, new QTableWidgetItem());
  }
  readings_.clear();
  ui_->saveButton->setEnabled(false);
}

void FocalPage::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  if (!measuring_.running() && readings_.empty()) reload();
}

void FocalPage::select(const std::vector<std::uint32_t>& holes) {
  for (int r = 0; r < static_cast<int>(holes_.size()); ++r) {
    const bool on = std::find(holes.begin(), holes.end(), holes_[r].params.hole_number) != holes.end();
    ui_->holeTable->item(r, kHole)->setCheckState(on ? Qt::Checked : Qt::Unchecked);
  }
}

std::vector<HoleRecord> FocalPage::ticked() const {
  std::vector<HoleRecord> out;
  for (int r = 0; r < static_cast<int>(holes_.size()); ++r)
    if (ui_->holeTable->item(r, kHole)->checkState() == Qt::Checked) out.push_back(holes_[r]);
  return out;
}

void FocalPage::measure() {
  if (measuring_.running()) return;
  const std::vector<HoleRecord> holes = ticked();
  if (holes.empty()) {
    show_message(tr("Tick the holes to measure first."), true);
    return;
  }
  if (!sensor_) {
    show_message(tr("No displacement sensor configured."), true);
    return;
  }
  ui_->measureButton->setEnabled(false);
  ui_->saveButton->setEnabled(false);
  ui_->cancelButton->setEnabled(true);
  ui_->progressBar->setVisible(true);
  ui_->progressBar->setRange(0, static_cast<int>(holes.size()));
  ui_->progressBar->setValue(0);
  show_message(tr("Measuring %n hole(s)…", nullptr, static_cast<int>(holes.size())), false);
  FocalConfig config;
  config.standoff_mm = ui_->standoffSpin->value();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("lasercnc_hmi_" + std::to_string(QCoreApplication::applicationPid()));
  measuring_.start(
      [holes, config, dir, shm = shm_name_, ep = *sensor_](TaskProgress& p) {
        Result<std::unique_ptr<ModbusDistanceSensor>> sensor = ModbusDistanceSensor::connect(ep, 16);
        if (!sensor) {
          std::vector<FocalReading> none;
          for (const HoleRecord& h : holes) {
            FocalReading r;
            r.hole = h.params.hole_number;
            r.error = "displacement sensor: " + sensor.error().message;
            none.push_back(r);
          }
          return none;
        }
        MachineMover mover(shm, dir);
        return run_focal(
            holes, mover, **sensor, config, [&p](int done, int) { p.done = done; }, &p.cancel);
      },
      static_cast<int>(holes.size()));
}

void FocalPage::present(const std::vector<FocalReading>& readings) {
  ui_->progressBar->setVisible(false);
  ui_->measureButton->setEnabled(true);
  ui_->cancelButton->setEnabled(false);
  readings_ = readings;
  int measured = 0;
  for (const FocalReading& r : readings_) {
    for (int row = 0; row < static_cast<int>(holes_.size()); ++row) {
      if (holes_[row].params.hole_number != r.hole) continue;
      QTableWidget* t = ui_->holeTable;
      t->item(row, kDistance)->setText(r.distance_mm ? QString::number(*r.distance_mm, 'f', 4) : QString());
      t->item(row, kOffset)->setText(r.offset_mm ? QString::number(*r.offset_mm, 'f', 4) : QString());
      t->item(row, kStatus)->setText(r.offset_mm ? tr("measured") : QString::fromStdString(r.error));
      t->item(row, kStatus)->setForeground(r.offset_mm ? palette().text().color() : QColor(kErrorColor));
    }
    measured += r.offset_mm ? 1 : 0;
  }
  const int failed = static_cast<int>(readings_.size()) - measured;
  ui_->saveButton->setEnabled(measured > 0);
  show_message(
      failed == 0
          ? tr("%n hole(s) measured; save to store the offsets.", nullptr, measured)
          : tr("%1 measured, %2 not (see Status); save stores the measured ones.").arg(measured).arg(failed),
      failed > 0);
  emit finished();
}

bool FocalPage::save() {
  const auto offsets = offsets_to_save(readings_);
  if (offsets.empty()) {
    show_message(tr("Nothing measured to save."), true);
    return false;
  }
  if (Status s = db_.set_focus_offsets(offsets); !s) {
    show_message(QString::fromStdString(s.error().to_string()), true);
    return false;
  }
  reload();
  show_message(tr("Stored the focus offsets of %n hole(s).", nullptr, static_cast<int>(offsets.size())),
               false);
  return true;
}

bool FocalPage::wait_done(int timeout_ms) { return measuring_.wait(timeout_ms); }

void FocalPage::show_message(const QString& text, bool error) { set_message(ui_->messageLabel, text, error); }

QString FocalPage::message() const { return ui_->messageLabel->text(); }
QTableWidget* FocalPage::table() const { return ui_->holeTable; }

}  // namespace lcnc::hmi
