#include "hmi/machine_page.h"

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
  connect(&timer_, &QTimer::timeout, this, [this] { refresh(); });
  timer_.start(static_cast<int>(kPollPeriod.count()));
  refresh();
}

MachinePage::~MachinePage() = default;

void MachinePage::send(shm::CommandType type, double value) {
  if (link_.send(type, value) == 0) ui_->jobLabel->setText(tr("Not sent: no link to the controller."));
}

void MachinePage::refresh() {
  const bool up = link_.poll();
  QLabel* dro[5] = {ui_->droX, ui_->droY, ui_->droZ, ui_->droA, ui_->droC};
  for (QPushButton* b : {ui_->cycleStartButton, ui_->holdButton, ui_->resumeButton, ui_->stopButton,
                         ui_->resetButton})
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
  constexpr int kAxes[5] = {0, 1, 2, 3, 5};
  for (int i = 0; i < 5; ++i) {
    const bool present = (st->axes_mask >> kAxes[i]) & 1u;
    dro[i]->setText(present ? QString::number(st->pos[kAxes[i]], 'f', 3) : QString("—"));
  }
  ui_->stateLabel->setText(tr("State: %1").arg(tr(state_text(st->state))));
  if (const std::optional<shm::JobStatus> j = link_.job()) ui_->jobLabel->setText(QString::fromUtf8(j->message));
}

}  // namespace lcnc::hmi
