#include "hmi/machine_page.h"

#include <QCoreApplication>
#include <QDateTime>
#include <QHeaderView>
#include <QTableWidget>

#include <cmath>

#include "hmi/page_support.h"
#include "machine/machine_config.h"
#include "ui_machine_page.h"

namespace lcnc::hmi {
namespace {

constexpr const char* kContext = "MachinePage";

const char* state_text(shm::MachineState s) {
  switch (s) {
    case shm::MachineState::Idle: return QT_TRANSLATE_NOOP("MachinePage", "idle");
    case shm::MachineState::Running: return QT_TRANSLATE_NOOP("MachinePage", "running");
    case shm::MachineState::FeedHold: return QT_TRANSLATE_NOOP("MachinePage", "feed hold");
    case shm::MachineState::Stopping: return QT_TRANSLATE_NOOP("MachinePage", "stopping");
    case shm::MachineState::EStop: return QT_TRANSLATE_NOOP("MachinePage", "e-stop");
    case shm::MachineState::Jog: return QT_TRANSLATE_NOOP("MachinePage", "jog");
    case shm::MachineState::Homing: return QT_TRANSLATE_NOOP("MachinePage", "homing");
  }
  return "?";
}

// The banner's colours by state: green at rest, blue running, amber held,
// red in e-stop, teal while jogging or homing.
const char* state_style(shm::MachineState s) {
  switch (s) {
    case shm::MachineState::Idle: return "background-color: #2e7d32;";
    case shm::MachineState::Running: return "background-color: #1565c0;";
    case shm::MachineState::FeedHold:
    case shm::MachineState::Stopping: return "background-color: #ef6c00;";
    case shm::MachineState::EStop: return "background-color: #c62828;";
    case shm::MachineState::Jog:
    case shm::MachineState::Homing: return "background-color: #00838f;";
  }
  return "";
}
constexpr const char* kBannerText = "color: white; font-size: 18pt; font-weight: bold; padding: 4px 10px;";
constexpr const char* kWarningColor = "#ef6c00";

constexpr int kDroAxes[5] = {0, 1, 2, 3, 5};  // X Y Z A C, as the DRO rows and the jog combo list them

QString format_seconds(double s) {
  const long total = std::lround(s);
  return total >= 3600 ? QString("%1:%2:%3")
                             .arg(total / 3600)
                             .arg(total / 60 % 60, 2, 10, QChar('0'))
                             .arg(total % 60, 2, 10, QChar('0'))
                       : QString("%1:%2").arg(total / 60).arg(total % 60, 2, 10, QChar('0'));
}

}  // namespace

MachinePage::MachinePage(const std::string& shm_name, QWidget* parent)
    : QWidget(parent), ui_(std::make_unique<Ui::MachinePage>()), link_(shm_name) {
  ui_->setupUi(this);
  for (int i = 0; i < lcnc::kWorkOffsetCount; ++i) ui_->workSystemCombo->addItem(work_system_name(i));
  connect(ui_->cycleStartButton, &QPushButton::clicked, this, [this] { start(); });
  connect(ui_->holdButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Hold); });
  connect(ui_->resumeButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Resume); });
  connect(ui_->stopButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Stop); });
  connect(ui_->estopButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::EStop); });
  connect(ui_->resetButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Reset); });
  connect(ui_->frameButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Frame); });
  connect(ui_->overrideSlider, &QSlider::valueChanged, this, [this](int pct) {
    ui_->overrideLabel->setText(QString("%1 %").arg(pct));
    send(shm::CommandType::Override, pct / 100.0);
  });
  connect(ui_->jogMinusButton, &QPushButton::clicked, this, [this] { jog(-1); });
  connect(ui_->jogPlusButton, &QPushButton::clicked, this, [this] { jog(+1); });
  connect(ui_->homeButton, &QPushButton::clicked, this, [this] { home(); });
  connect(ui_->mdiSendButton, &QPushButton::clicked, this, [this] { send_mdi(ui_->mdiEdit->text()); });
  connect(ui_->mdiEdit, &QLineEdit::returnPressed, this, [this] { send_mdi(ui_->mdiEdit->text()); });
  connect(ui_->touchOffButton, &QPushButton::clicked, this, [this] {
    send_mdi(QString::fromStdString(
        touch_off_gcode(ui_->touchOffAxisCombo->currentIndex(), ui_->touchOffSpin->value())));
  });
  connect(ui_->workSystemCombo, QOverload<int>::of(&QComboBox::activated), this,
          [this](int index) { send_mdi(QString::fromStdString(work_system_gcode(index))); });
  connect(ui_->acknowledgeButton, &QPushButton::clicked, this, [this] {
    alarms_.acknowledge_all();
    show_alarms();
  });
  connect(ui_->clearAlarmsButton, &QPushButton::clicked, this, [this] {
    alarms_.clear();
    show_alarms();
  });
  QTableWidget* t = ui_->alarmTable;
  t->setColumnCount(5);
  t->setHorizontalHeaderLabels({tr("Time"), tr("Code"), tr("Line"), tr("What"), tr("Count")});
  t->verticalHeader()->hide();
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  t->horizontalHeader()->setSectionResizeMode(3, QHeaderView::Stretch);
  connect(&timer_, &QTimer::timeout, this, [this] { refresh(); });
  timer_.start(static_cast<int>(kPollPeriod.count()));
  refresh();
}

MachinePage::~MachinePage() = default;

void MachinePage::send(shm::CommandType type, double value, std::uint8_t axis, const std::string& text) {
  if (link_.send(type, value, axis, text) == 0)
    set_message(ui_->jobLabel, tr("Not sent: no link to the controller."), true);
}

void MachinePage::start() {
  const std::uint8_t flags =
      static_cast<std::uint8_t>((ui_->singleBlockCheck->isChecked() ? shm::kStartSingleBlock : 0) |
                                (ui_->dryRunCheck->isChecked() ? shm::kStartDryRun : 0));
  send(shm::CommandType::Start, ui_->fromLineSpin->value(), flags);
}

bool MachinePage::send_mdi(const QString& gcode) {
  const std::string text = gcode.trimmed().toStdString();
  if (text.empty()) return false;
  if (text.size() >= sizeof(shm::Command::text)) {
    set_message(ui_->jobLabel,
                tr("MDI: a line of at most %1 characters.").arg(sizeof(shm::Command::text) - 1), true);
    return false;
  }
  if (link_.send(shm::CommandType::Mdi, 0.0, 0, text) == 0) {
    set_message(ui_->jobLabel, tr("Not sent: no link to the controller."), true);
    return false;
  }
  ui_->mdiEdit->clear();
  return true;
}

void MachinePage::jog(int direction) {
  send(shm::CommandType::Jog, direction * ui_->jogStepSpin->value(),
       static_cast<std::uint8_t>(kDroAxes[ui_->jogAxisCombo->currentIndex()]));
}

void MachinePage::home() {
  send(shm::CommandType::Home, 0.0, static_cast<std::uint8_t>(kDroAxes[ui_->jogAxisCombo->currentIndex()]));
}

void MachinePage::take_events() {
  shm::Event e;
  while (link_.next_event(e)) {
    alarms_.add(e, AlarmLog::Clock::now());
    alarms_changed_ = true;
  }
  if (alarms_changed_) show_alarms();
}

void MachinePage::show_alarms() {
  alarms_changed_ = false;
  QTableWidget* t = ui_->alarmTable;
  const auto& rows = alarms_.rows();
  t->setRowCount(static_cast<int>(rows.size()));
  for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
    const AlarmLog::Row& a = rows[static_cast<std::size_t>(r)];
    const QDateTime when = QDateTime::fromMSecsSinceEpoch(
        std::chrono::duration_cast<std::chrono::milliseconds>(a.last.time_since_epoch()).count());
    const QString cells[] = {when.toString("HH:mm:ss"), a.code != 0 ? QString("E%1").arg(a.code) : QString(),
                             a.line != 0 ? QString::number(a.line) : QString(),
                             QString::fromStdString(a.text),
                             a.count > 1 ? QString("×%1").arg(a.count) : QString()};
    const QColor colour = a.acknowledged                         ? QColor("#78909c")
                          : a.severity == shm::Severity::Error   ? QColor(kErrorColor)
                          : a.severity == shm::Severity::Warning ? QColor(kWarningColor)
                                                                 : QColor();
    for (int c = 0; c < 5; ++c) {
      auto* item = new QTableWidgetItem(cells[c]);
      if (colour.isValid()) item->setForeground(colour);
      QFont f = item->font();
      f.setBold(!a.acknowledged && a.severity == shm::Severity::Error);
      item->setFont(f);
      t->setItem(r, c, item);
    }
  }
  const std::size_t open = alarms_.unacknowledged();
  ui_->unacknowledgedLabel->setText(open > 0 ? tr("%n to acknowledge", nullptr, static_cast<int>(open))
                                             : QString());
  ui_->unacknowledgedLabel->setStyleSheet(open > 0 ? kErrorStyle : "");
  ui_->acknowledgeButton->setEnabled(open > 0);
}

void MachinePage::enable(const ControlView& view) {
  const ControlsEnabled c = controls_enabled(view);
  ui_->cycleStartButton->setEnabled(c.start);
  ui_->frameButton->setEnabled(c.frame);
  ui_->holdButton->setEnabled(c.hold);
  ui_->resumeButton->setEnabled(c.resume);
  ui_->stopButton->setEnabled(c.stop);
  ui_->resetButton->setEnabled(c.reset);
  for (QWidget* w : std::initializer_list<QWidget*>{ui_->jogMinusButton, ui_->jogPlusButton})
    w->setEnabled(c.jog);
  ui_->homeButton->setEnabled(c.home);
  ui_->mdiSendButton->setEnabled(c.mdi);
  ui_->mdiEdit->setEnabled(c.mdi);
  ui_->touchOffButton->setEnabled(c.touch_off);
  ui_->workSystemCombo->setEnabled(c.touch_off);
  ui_->overrideSlider->setEnabled(c.override_feed);
}

void MachinePage::refresh() {
  const bool up = link_.poll();
  QLabel* dro[5] = {ui_->droX, ui_->droY, ui_->droZ, ui_->droA, ui_->droC};
  QLabel* mach[5] = {ui_->droMachX, ui_->droMachY, ui_->droMachZ, ui_->droMachA, ui_->droMachC};
  QLabel* homed[5] = {ui_->homedX, ui_->homedY, ui_->homedZ, ui_->homedA, ui_->homedC};
  QLabel* to_go[5] = {ui_->toGoX, ui_->toGoY, ui_->toGoZ, ui_->toGoA, ui_->toGoC};
  const std::optional<shm::Status> st = up ? link_.status() : std::nullopt;
  if (!st) {
    enable(ControlView{});
    ui_->linkLabel->setText(tr("Controller: link lost — %1").arg(QString::fromStdString(link_.why())));
    ui_->linkLabel->setStyleSheet("color: #b00020; font-weight: bold;");
    ui_->stateLabel->setText(tr("State: unknown"));
    ui_->stateLabel->setStyleSheet(QString("background-color: #616161; ") + kBannerText);
    for (QLabel* l : dro) l->setText("—");
    for (QLabel* l : mach) l->setText("—");
    for (QLabel* l : homed) l->setText("—");
    for (QLabel* l : to_go) l->setText("—");
    return;
  }
  ui_->linkLabel->setText(tr("Controller: connected"));
  ui_->linkLabel->setStyleSheet("color: #1b5e20;");
  take_events();
  const std::optional<shm::JobStatus> job = link_.job();
  show_status(*st, job ? &*job : nullptr);
  ControlView v;
  v.linked = true;
  v.state = st->state;
  v.program_pause = st->program_pause;
  v.job_active = job && job->job_active;
  v.program_loaded = job && job->program[0] != '\0';
  enable(v);
  for (int i = 0; i < 5; ++i) {
    const int a = kDroAxes[i];
    const bool present = (st->axes_mask >> a) & 1u;
    const double work = st->pos[a] - (job ? job->work_offset[a] : 0.0);
    dro[i]->setText(present ? QString::number(work, 'f', 3) : QString("—"));
    mach[i]->setText(present ? QString::number(st->pos[a], 'f', 3) : QString("—"));
    // the distance to go of the linear axes while a job moves
    to_go[i]->setText(present && a < 3 && job && job->job_active
                          ? QString::number(job->distance_to_go[a], 'f', 3)
                          : QString("—"));
    const bool is_homed = (st->homed_mask >> a) & 1u;
    homed[i]->setText(!present ? QString("—") : is_homed ? QString("✔") : QString("✘"));
    homed[i]->setStyleSheet(!present   ? ""
                            : is_homed ? "color: #2e7d32; font-size: 16pt;"
                                       : "color: #b00020; font-size: 16pt;");
    homed[i]->setToolTip(!present ? QString() : is_homed ? tr("homed") : tr("not homed"));
  }
}

void MachinePage::show_status(const shm::Status& st, const shm::JobStatus* job) {
  QString banner = QCoreApplication::translate(kContext, state_text(st.state));
  if (st.program_pause)
    banner += job && job->single_block ? tr(" — single block: Resume runs the next block")
                                       : tr(" — program pause: Resume goes on");
  if (st.input_wait >= 0) banner += tr(" — waiting for input %1").arg(st.input_wait);
  ui_->stateLabel->setText(tr("State: %1").arg(banner));
  ui_->stateLabel->setStyleSheet(QString(state_style(st.state)) + kBannerText);
  // the override as the controller has it (the operator's target), unless
  // the operator is moving the slider right now
  const int pct = static_cast<int>(std::lround(st.feed_override_target * 100.0));
  if (!ui_->overrideSlider->isSliderDown() && ui_->overrideSlider->value() != pct) {
    const QSignalBlocker quiet(ui_->overrideSlider);
    ui_->overrideSlider->setValue(pct);
    ui_->overrideLabel->setText(QString("%1 %").arg(pct));
  }
  ui_->laserLabel->setText(st.power_pct > 0.0f
                               ? tr("Laser: on, %1 %").arg(static_cast<double>(st.power_pct), 0, 'f', 0)
                               : tr("Laser: off"));
  ui_->laserLabel->setStyleSheet(st.power_pct > 0.0f ? "color: #c62828; font-weight: bold;" : "");
  ui_->gasLabel->setText((st.outputs & shm::kGasHighBit) != 0  ? tr("Gas: high (M8)")
                         : (st.outputs & shm::kGasLowBit) != 0 ? tr("Gas: low (M7)")
                                                               : tr("Gas: off"));
  if (!job) return;
  if (job->job_active && !job_was_active_) job_started_s_ = st.machine_time_s;
  job_was_active_ = job->job_active;
  ui_->programLabel->setText(job->program[0] ? tr("Program: %1").arg(QString::fromUtf8(job->program))
                                             : tr("Program: none loaded"));
  ui_->lineLabel->setText(tr("Line %1").arg(st.line));
  ui_->progressBar->setValue(static_cast<int>(std::lround(job->progress * 100.0)));
  const std::optional<double> left =
      job->job_active ? time_left_s(job->progress, st.machine_time_s - job_started_s_) : std::nullopt;
  ui_->timeLeftLabel->setText(left ? tr("Time left %1").arg(format_seconds(*left)) : QString());
  QStringList how;
  if (job->mdi) how << tr("MDI");
  if (job->single_block) how << tr("single block");
  if (job->dry_run) how << tr("dry run");
  if (job->start_line > 0) how << tr("from line %1").arg(job->start_line);
  ui_->runModeLabel->setText(how.join(", "));
  ui_->modesLabel->setText(QString::fromUtf8(job->modes));
  if (ui_->workSystemCombo->currentIndex() != job->coord_system && !ui_->workSystemCombo->view()->isVisible())
    ui_->workSystemCombo->setCurrentIndex(job->coord_system);
  set_message(ui_->jobLabel, QString::fromUtf8(job->message), job->ack_code != 0);
}

}  // namespace lcnc::hmi
