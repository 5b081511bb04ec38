#include "hmi/process_db_page.h"

#include <QCoreApplication>
#include <QFileDialog>
#include <QHeaderView>
#include <QItemSelectionModel>

#include <filesystem>

#include "hmi/page_support.h"
#include "hmi/replace_file.h"
#include "holes/hole_table.h"
#include "ui_process_db_page.h"

namespace lcnc::hmi {

ProcessDbPage::ProcessDbPage(ProcessDatabase& db, std::string shm_name, QWidget* parent)
    : QWidget(parent), ui_(std::make_unique<Ui::ProcessDbPage>()), db_(db),
      model_(std::make_unique<HoleTableModel>(db)), link_(std::move(shm_name)) {
  ui_->setupUi(this);
  ui_->holeTable->setModel(model_.get());
  ui_->holeTable->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  ui_->holeTable->verticalHeader()->hide();  // the hole number is the first column
  connect(model_.get(), &HoleTableModel::refused, this, [this](const QString& m) { show_message(m, true); });
  connect(model_.get(), &QAbstractItemModel::dataChanged, this, [this] { show_message(tr("Stored."), false); });
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
  update_count();
}

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
  const std::string path = (dir / "holes_run.csv").string();
  // replaced whole: the controller may still be reading the last one sent
  std::string why;
  if (!replace_file(path, [&](std::ostream& out) { out << write_hole_table(rows); }, why)) {
    show_message(tr("Cannot write %1.").arg(QString::fromStdString(path)), true);
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

void ProcessDbPage::show_message(const QString& text, bool error) { set_message(ui_->messageLabel, text, error); }

QString ProcessDbPage::message() const { return ui_->messageLabel->text(); }

void ProcessDbPage::update_count() { ui_->countLabel->setText(tr("%n hole(s)", nullptr, model_->rowCount())); }

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
  for (int i = 0; i < model_->rowCount(); ++i) next = std::max(next, model_->record(i).params.hole_number + 1);
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
