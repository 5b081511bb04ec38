#include "hmi/program_page.h"

#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QTextBlock>
#include <QVBoxLayout>

#include "hmi/page_support.h"
#include "hmi/toolpath_view.h"
#include "ui_program_page.h"

namespace lcnc::hmi {

ProgramPage::ProgramPage(MachineConfig machine, std::string shm_name, QWidget* parent)
    : QWidget(parent),
      ui_(std::make_unique<Ui::ProgramPage>()),
      machine_(std::move(machine)),
      link_(std::move(shm_name)),
      planning_(
          this, [this](const TaskProgress& p) { ui_->progressBar->setValue(p.done); },
          [this](const Outcome& o) { present(o); }) {
  ui_->setupUi(this);
  view_ = new ToolpathView(ui_->viewHolder);
  auto* l = new QVBoxLayout(ui_->viewHolder);
  l->setContentsMargins(0, 0, 0, 0);
  l->addWidget(view_);
  connect(ui_->openButton, &QPushButton::clicked, this, [this] {
    const QString p = QFileDialog::getOpenFileName(this, tr("Open program"), {},
                                                   tr("G-code (*.ngc *.nc *.gcode);;All (*)"));
    if (!p.isEmpty()) open_file(p);
  });
  connect(ui_->loadButton, &QPushButton::clicked, this, [this] { load(); });
  connect(ui_->topViewButton, &QPushButton::clicked, this, [this] { view_->set_view(kTopView); });
  connect(ui_->isoViewButton, &QPushButton::clicked, this, [this] { view_->set_view(kIsoView); });
  ui_->viewSplitter->setStretchFactor(0, 3);
  ui_->viewSplitter->setStretchFactor(1, 1);
  connect(&timer_, &QTimer::timeout, this, [this] { refresh(); });
  timer_.start(100);
}

ProgramPage::~ProgramPage() = default;

void ProgramPage::open_file(const QString& path) {
  if (planning_.running()) return;
  program_ = QFileInfo(path).absoluteFilePath();
  ui_->fileLabel->setText(QFileInfo(path).fileName());
  // the text as it is now (what the planner reads), at most kMaxShownBytes of it
  {
    QFile f(path);
    QString text;
    if (f.open(QIODevice::ReadOnly)) text = QString::fromUtf8(f.read(kMaxShownBytes));
    ui_->codeView->setPlainText(text);
    current_line_ = 0;
    ui_->codeView->setExtraSelections({});
  }
  ui_->fileLabel->setToolTip(path);
  ui_->loadButton->setEnabled(false);
  ui_->progressBar->setVisible(true);
  ui_->progressBar->setRange(0, 1000);
  ui_->progressBar->setValue(0);
  show_message(tr("Checking and planning %1…").arg(path), false);
  // planned from where the machine stands, as the controller will
  Pose start = Pose::Zero();
  if (link_.poll())
    if (const std::optional<shm::Status> st = link_.status())
      for (int i = 0; i < kAxisCount; ++i) start[i] = st->pos[i];
  planning_.start(
      [m = machine_, p = path.toStdString(), start](TaskProgress& pr) {
        Outcome o;
        Result<Toolpath> t = plan_toolpath(
            p, m, start, [&pr](double f) { pr.done = static_cast<int>(f * 1000); }, &pr.cancel);
        if (t)
          o.path = std::move(t).value();
        else
          o.error = t.error();
        return o;
      },
      1000);
}

void ProgramPage::present(const Outcome& o) {
  ui_->progressBar->setVisible(false);
  if (o.error) {
    path_.reset();
    view_->set_toolpath(nullptr);
    ui_->summaryLabel->clear();
    show_message(QString::fromStdString(o.error->to_string()), true);
    emit finished(false);
    return;
  }
  path_ = o.path;
  view_->set_toolpath(&*path_);
  ui_->summaryLabel->setText(
      tr("%1 lines; path %2 mm; planned time %3 s; peak speed %4 mm/s; %5 points drawn")
          .arg(path_->lines)
          .arg(path_->length_mm, 0, 'f', 1)
          .arg(path_->time_s, 0, 'f', 3)
          .arg(path_->peak_speed, 0, 'f', 1)
          .arg(path_->points.size()));
  ui_->loadButton->setEnabled(true);
  show_message(tr("Planned. Load it into the controller to run it."), false);
  emit finished(true);
}

bool ProgramPage::load() {
  if (!path_ || program_.isEmpty()) return false;
  if (!link_.poll() ||
      link_.send(shm::CommandType::Load, 0.0, 0, QFileInfo(program_).absoluteFilePath().toStdString()) == 0) {
    show_message(tr("Not sent: no link to the controller."), true);
    return false;
  }
  show_message(tr("Sent to the controller; its answer shows on the machine screen."), false);
  return true;
}

void ProgramPage::refresh() {
  std::optional<Vec3> at;
  if (link_.poll())
    if (const std::optional<shm::Status> st = link_.status()) {
      at = Vec3(st->pos[0], st->pos[1], st->pos[2]);
      const std::optional<shm::JobStatus> job = link_.job();
      if (job && job->job_active && !job->mdi && !program_.isEmpty() &&
          QString::fromUtf8(job->program) == program_)
        set_current_line(st->line);
    }
  view_->set_position(at);
}

void ProgramPage::set_current_line(std::uint32_t line) {
  if (line == current_line_) return;
  current_line_ = line;
  QList<QTextEdit::ExtraSelection> marks;
  const QTextBlock block = ui_->codeView->document()->findBlockByNumber(static_cast<int>(line) - 1);
  if (line > 0 && block.isValid()) {
    QTextEdit::ExtraSelection mark;
    mark.format.setBackground(QColor("#fff59d"));
    mark.format.setProperty(QTextFormat::FullWidthSelection, true);
    mark.cursor = QTextCursor(block);
    marks << mark;
    ui_->codeView->setTextCursor(mark.cursor);
    ui_->codeView->centerCursor();
  }
  ui_->codeView->setExtraSelections(marks);
}

QString ProgramPage::highlighted_text() const {
  const QList<QTextEdit::ExtraSelection> marks = ui_->codeView->extraSelections();
  return marks.isEmpty() ? QString() : marks.front().cursor.block().text();
}

bool ProgramPage::wait_done(int timeout_ms) { return planning_.wait(timeout_ms); }
void ProgramPage::show_message(const QString& text, bool error) {
  set_message(ui_->messageLabel, text, error);
}
QString ProgramPage::message() const { return ui_->messageLabel->text(); }
QString ProgramPage::summary() const { return ui_->summaryLabel->text(); }

}  // namespace lcnc::hmi
