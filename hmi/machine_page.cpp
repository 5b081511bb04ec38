#include "hmi/machine_page.h"

#include <QCoreApplication>
#include <QHeaderView>
#include <QTableWidget>

#include "hmi/page_support.h"
#include "ui_machine_page.h"

namespace lcnc::hmi {
namespace {

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

}  // namespace

MachinePage::MachinePage(const std::string& shm_name, QWidget* parent)
    : QWidget(parent), ui_(std::make_unique<Ui::MachinePage>()), link_(shm_name) {
  ui_->setupUi(this);
  connect(ui_->cycleStartButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Start); });
  connect(ui_->holdButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Hold); });
  connect(ui_->resumeButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Resume); });
  connect(ui_->stopButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Stop); });
  connect(ui_->estopButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::EStop); });
  connect(ui_->resetButton, &QPushButton::clicked, this, [this] { send(shm::CommandType::Reset); });
  connect(ui_->overrideSlider, &QSlider::valueChanged, this, [this](int pct) {
    ui_->overrideLabel->setText(QString("%1 %").arg(pct));
    send(shm::CommandType::Override, pct / 100.0);
  });
  connect(ui_->jogMinusButton, &QPushButton::clicked, this, [this] { jog(-1); });
  connect(ui_->jogPlusButton, &QPushButton::clicked, this, [this] { jog(+1); });
  connect(ui_->homeButton, &QPushButton::clicked, this, [this] { home(); });
  connect(ui_->clearAlarmsButton, &QPushButton::clicked, this, [this] { ui_->alarmTable->setRowCount(0); });
  QTableWidget* t = ui_->alarmTable;
  t->setColumnCount(4);
  t->setHorizontalHeaderLabels({tr("Time, s"), tr("Code"), tr("Line"), tr("What")});
  t->verticalHeader()->hide();
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  t->horizontalHeader()->setStretchLastSection(true);
  connect(&timer_, &QTimer::timeout, this, [this] { refresh(); });
  timer_.start(static_cast<int>(kPollPeriod.count()));
  refresh();
}

MachinePage::~MachinePage() = default;

void MachinePage::send(shm::CommandType type, double value, std::uint8_t axis) {
  if (link_.send(type, value, axis) == 0) ui_->jobLabel->setText(tr("Not sent: no link to the controller."));
}

namespace {
constexpr std::uint8_t kJogAxes[5] = {0, 1, 2, 3, 5};  // X Y Z A C, as the combo lists them
}

void MachinePage::jog(int direction) {
  send(shm::CommandType::Jog, direction * ui_->jogStepSpin->value(), kJogAxes[ui_->jogAxisCombo->currentIndex()]);
}

void MachinePage::home() { send(shm::CommandType::Home, 0.0, kJogAxes[ui_->jogAxisCombo->currentIndex()]); }

void MachinePage::take_events() {
  QTableWidget* t = ui_->alarmTable;
  shm::Event e;
  while (link_.next_event(e)) {
    t->insertRow(0);
    const QString cells[] = {QString::number(static_cast<double>(e.period) * period_s_, 'f', 3),
                             e.code != 0 ? QString("E%1").arg(e.code) : QString(),
                             e.line != 0 ? QString::number(e.line) : QString(), QString::fromUtf8(e.text)};
    for (int c = 0; c < 4; ++c) {
      auto* item = new QTableWidgetItem(cells[c]);
      if (e.code != 0) item->setForeground(QColor(kErrorColor));
      t->setItem(0, c, item);
    }
  }
  while (t->rowCount() > kMaxAlarmRows) t->removeRow(t->rowCount() - 1);
}

void MachinePage::refresh() {
  const bool up = link_.poll();
  QLabel* dro[5] = {ui_->droX, ui_->droY, ui_->droZ, ui_->droA, ui_->droC};
  for (QPushButton* b : {ui_->cycleStartButton, ui_->holdButton, ui_->resumeButton, ui_->stopButton,
                         ui_->resetButton, ui_->jogMinusButton, ui_->jogPlusButton, ui_->homeButton})
    b->setEnabled(up);
  ui_->overrideSlider->setEnabled(up);
  if (!up) {
    ui_->linkLabel->setText(tr("Controller: link lost — %1").arg(QString::fromStdString(link_.why())));
    ui_->linkLabel->setStyleSheet("color: #b00020; font-weight: bold;");
    ui_->stateLabel->setText(tr("State: unknown"));
    for (QLabel* l : dro) l->setText("—");
    return;
  }
  ui_->linkLabel->setText(tr("Controller: connected"));
  ui_->linkLabel->setStyleSheet("color: #1b5e20;");
  const std::optional<shm::Status> st = link_.status();
  if (!st) return;
  if (st->periods > 0) period_s_ = st->machine_time_s / static_cast<double>(st->periods);
  take_events();
  constexpr int kAxes[5] = {0, 1, 2, 3, 5};
  for (int i = 0; i < 5; ++i) {
    const bool present = (st->axes_mask >> kAxes[i]) & 1u;
    dro[i]->setText(present ? QString::number(st->pos[kAxes[i]], 'f', 3) : QString("—"));
  }
  ui_->stateLabel->setText(
      tr("State: %1").arg(QCoreApplication::translate("MachinePage", state_text(st->state))));
  if (const std::optional<shm::JobStatus> j = link_.job()) ui_->jobLabel->setText(QString::fromUtf8(j->message));
}

}  // namespace lcnc::hmi
