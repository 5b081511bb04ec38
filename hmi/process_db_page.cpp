#include "hmi/process_db_page.h"

#include <QFileDialog>
#include <QHeaderView>
#include <QItemSelectionModel>

#include "hmi/page_support.h"
#include "ui_process_db_page.h"

namespace lcnc::hmi {

ProcessDbPage::ProcessDbPage(ProcessDatabase& db, QWidget* parent)
    : QWidget(parent), ui_(std::make_unique<Ui::ProcessDbPage>()), db_(db),
      model_(std::make_unique<HoleTableModel>(db)) {
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
  update_count();
}

ProcessDbPage::~ProcessDbPage() = default;

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
