#include "hmi/adjust_page.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QHeaderView>
#include <QPainter>
#include <QPainterPath>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>

#include "hmi/page_support.h"
#include "holes/hole_fields.h"
#include "ui_adjust_page.h"

namespace lcnc::hmi {

// Setpoint (converted to W), laser output and measured power over time.
class PowerPlot : public QWidget {
 public:
  explicit PowerPlot(QWidget* parent) : QWidget(parent) {
    setObjectName("powerPlot");
    setMinimumSize(360, 180);
  }
  struct Sample {
    double t, setpoint_w, output_w, measured_w;
  };
  void set(std::vector<Sample> s) {
    samples_ = std::move(s);
    update();
  }
  [[nodiscard]] std::size_t size() const noexcept { return samples_.size(); }

 protected:
  void paintEvent(QPaintEvent*) override {
    QPainter g(this);
    g.fillRect(rect(), Qt::white);
    g.setRenderHint(QPainter::Antialiasing);
    const QRectF area(46, 8, width() - 56, height() - 34);
    g.setPen(Qt::black);
    g.drawRect(area);
    double top = 1.0;
    for (const Sample& s : samples_) top = std::max({top, s.setpoint_w, s.output_w, s.measured_w});
    top *= 1.1;
    const double t1 = samples_.empty() ? 60.0 : samples_.back().t, t0 = t1 - 60.0;
    for (int k = 0; k <= 4; ++k) {
      const double y = area.bottom() - area.height() * k / 4.0;
      g.drawText(QRectF(0, y - 8, 42, 16), Qt::AlignRight | Qt::AlignVCenter,
                 QString::number(top * k / 4.0, 'f', 1));
    }
    QFont small = g.font();
    small.setPointSizeF(small.pointSizeF() * 0.8);
    g.setFont(small);
    g.drawText(QRectF(area.left() - 40, area.bottom() + 4, area.width() + 50, 18), Qt::AlignCenter,
               AdjustPage::tr("W, 60 s: setpoint grey, output blue, measured green"));
    const auto curve = [&](auto value, const QColor& color) {
      QPainterPath p;
      bool first = true;
      for (const Sample& s : samples_) {
        const QPointF q(area.left() + (s.t - t0) / 60.0 * area.width(),
                        area.bottom() - value(s) / top * area.height());
        if (first)
          p.moveTo(q);
        else
          p.lineTo(q);
        first = false;
      }
      g.setPen(QPen(color, 1.5));
      g.drawPath(p);
    };
    curve([](const Sample& s) { return s.setpoint_w; }, QColor("#999999"));
    curve([](const Sample& s) { return s.output_w; }, QColor("blue"));
    curve([](const Sample& s) { return s.measured_w; }, QColor("green"));
  }

 private:
  std::vector<Sample> samples_;
};

namespace {

QString laser_state(double s) {
  switch (static_cast<int>(s)) {
    case 0: return AdjustPage::tr("standby");
    case 1: return AdjustPage::tr("ready");
    case 2: return AdjustPage::tr("emitting");
    case 3: return AdjustPage::tr("ALARM");
  }
  return QStringLiteral("?");
}

QString head_state(double s) {
  switch (static_cast<int>(s)) {
    case 0: return AdjustPage::tr("idle");
    case 1: return AdjustPage::tr("spinning up");
    case 2: return AdjustPage::tr("scanning");
  }
  return QStringLiteral("?");
}

}  // namespace

AdjustPage::AdjustPage(const AdjustEndpoints& at, QWidget* parent)
    : QWidget(parent), ui_(std::make_unique<Ui::AdjustPage>()) {
  ui_->setupUi(this);
  plot_ = new PowerPlot(ui_->plotHolder);
  auto* l = new QVBoxLayout(ui_->plotHolder);
  l->setContentsMargins(0, 0, 0, 0);
  l->addWidget(plot_);
  QStringList errors;
  const auto start = [&](const char* device, const std::optional<drivers::Endpoint>& ep,
                         std::vector<std::string> history) -> std::unique_ptr<DevicePoller> {
    if (!ep) return nullptr;
    auto p = DevicePoller::start(device, *ep, std::move(history));
    if (!p) {
      errors << QString("%1: %2").arg(device, QString::fromStdString(p.error().message));
      return nullptr;
    }
    return std::move(p).value();
  };
  laser_ = start("laser_source", at.laser, {"power_setpoint_pct", "output_power_w", "rated_power_w"});
  meter_ = start("power_meter", at.meter, {"power_w"});
  head_ = start("scan_head", at.head, {});
  if (!errors.isEmpty()) show_message(errors.join("; "), true);
  QTableWidget* t = ui_->linkTable;
  t->setColumnCount(6);
  t->setHorizontalHeaderLabels(
      {tr("Device"), tr("Link"), tr("Requests"), tr("Failed"), tr("Retries"), tr("Last error")});
  t->verticalHeader()->hide();
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  t->horizontalHeader()->setStretchLastSection(true);
  connect(ui_->applySetpointButton, &QPushButton::clicked, this, [this] {
    if (laser_) laser_->write("power_setpoint_pct", ui_->setpointSpin->value());
  });
  connect(ui_->enableButton, &QPushButton::toggled, this, [this](bool on) {
    if (laser_) laser_->write("enable", on ? 1 : 0);
  });
  connect(ui_->alarmResetButton, &QPushButton::clicked, this, [this] {
    if (laser_) laser_->write("alarm_reset", 1);
  });
  connect(ui_->zeroButton, &QPushButton::clicked, this, [this] {
    if (meter_) meter_->write("zero", 1);
  });
  connect(ui_->writeHeadButton, &QPushButton::clicked, this, [this] {
    if (!head_) return;
    ScanHeadParams h;
    h.start_radius_mm = ui_->startRadiusSpin->value();
    h.end_radius_mm = ui_->endRadiusSpin->value();
    h.radius_turns = static_cast<std::uint32_t>(ui_->turnsSpin->value());
    h.scan_speed_mm_s = ui_->scanSpeedSpin->value();
    h.wedge_speed_rpm = ui_->wedgeSpin->value();
    h.beam_offset_mm = ui_->beamOffsetSpin->value();
    (void)head_->write_block(scan_head_block(h));
  });
  connect(ui_->runHeadButton, &QPushButton::toggled, this, [this](bool on) {
    if (head_) head_->write("run", on ? 1 : 0);
  });
  timer_.setInterval(200);
  connect(&timer_, &QTimer::timeout, this, [this] { refresh(); });
  timer_.start();
  refresh();
}

AdjustPage::~AdjustPage() = default;

void AdjustPage::refresh() {
  const auto value = [](const PollSnapshot& s, const char* name) {
    const auto it = s.values.find(name);
    return it == s.values.end() ? 0.0 : it->second;
  };
  QStringList write_errors;
  if (laser_) {
    const PollSnapshot s = laser_->snapshot();
    ui_->laserStateLabel->setText(s.linked ? laser_state(value(s, "status")) : tr("no link"));
    ui_->laserPowerLabel->setText(QString::number(value(s, "output_power_w"), 'f', 2));
    // the setpoint in W too, as the plot shows it
    const double rated_w = value(s, "rated_power_w");
    ui_->setpointWattLabel->setText(
        s.linked && rated_w > 0.0 ? tr("= %1 W").arg(ui_->setpointSpin->value() / 100.0 * rated_w, 0, 'f', 1)
                                  : QString());
    ui_->laserTempLabel->setText(QString::number(value(s, "temperature_c"), 'f', 1));
    const int alarm = static_cast<int>(value(s, "alarm_code"));
    ui_->laserAlarmLabel->setText(alarm == 0 ? tr("none")
                                             : (alarm & 1 ? tr("over-temperature") : QString::number(alarm)));
    if (!s.last_write.empty()) write_errors << tr("laser: %1").arg(QString::fromStdString(s.last_write));
  }
  if (meter_) {
    const PollSnapshot s = meter_->snapshot();
    ui_->meterPowerLabel->setText(s.linked
                                      ? QString::number(value(s, "power_w"), 'f', 3) +
                                            (value(s, "over_range") != 0.0 ? tr(" (over range)") : QString())
                                      : tr("no link"));
  }
  if (head_) {
    const PollSnapshot s = head_->snapshot();
    ui_->headStateLabel->setText(
        s.linked ? (value(s, "fault") != 0.0 ? tr("FAULT") : head_state(value(s, "status"))) : tr("no link"));
    ui_->headRpmLabel->setText(QString::number(value(s, "actual_wedge_rpm"), 'f', 0));
    ui_->headRadiusLabel->setText(QString::number(value(s, "current_radius_mm"), 'f', 3));
    ui_->headTurnsLabel->setText(QString::number(value(s, "turns_done"), 'f', 0));
    if (!s.last_write.empty()) write_errors << tr("head: %1").arg(QString::fromStdString(s.last_write));
  }
  // the plot: setpoint in W, the laser's output and the meter's reading, by time
  if (laser_ && meter_) {
    const std::vector<HistorySample> lh = laser_->history(), mh = meter_->history();
    std::vector<PowerPlot::Sample> samples;
    std::size_t j = 0;
    for (const HistorySample& h : lh) {
      while (j + 1 < mh.size() && mh[j + 1].t_s <= h.t_s) ++j;
      const double measured = mh.empty() ? 0.0 : mh[j].values[0];
      samples.push_back({h.t_s, h.values[0] / 100.0 * h.values[2], h.values[1], measured});
    }
    plot_->set(std::move(samples));
  }
  // the terminal
  QTableWidget* t = ui_->linkTable;
  const std::pair<const char*, DevicePoller*> devices[] = {
      {"laser_source", laser_.get()}, {"power_meter", meter_.get()}, {"scan_head", head_.get()}};
  t->setRowCount(static_cast<int>(std::size(devices)));
  int row = 0;
  for (const auto& [name, p] : devices) {
    const PollSnapshot s = p ? p->snapshot() : PollSnapshot{};
    const QString cells[] = {QString::fromLatin1(name),
                             !p             ? tr("not configured")
                             : s.polls == 0 ? tr("connecting…")
                             : s.linked     ? tr("up")
                                            : tr("down"),
                             QString::number(s.counters.requests),
                             QString::number(s.counters.failed),
                             QString::number(s.counters.retries),
                             QString::fromStdString(s.error)};
    for (int c = 0; c < 6; ++c) {
      QTableWidgetItem* item = t->item(row, c);
      if (item == nullptr) t->setItem(row, c, item = new QTableWidgetItem());
      item->setText(cells[c]);
    }
    ++row;
  }
  if (!write_errors.isEmpty()) show_message(tr("Refused: %1").arg(write_errors.join("; ")), true);
}

bool AdjustPage::wait_polled(int timeout_ms) {
  const auto polled = [this] {
    for (DevicePoller* p : {laser_.get(), meter_.get(), head_.get()})
      if (p != nullptr && p->snapshot().polls == 0) return false;
    return true;
  };
  QElapsedTimer t;
  t.start();
  while (!polled() && t.elapsed() < timeout_ms) QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  refresh();
  return polled();
}

std::size_t AdjustPage::plot_samples() const { return plot_->size(); }
void AdjustPage::show_message(const QString& text, bool error) {
  set_message(ui_->messageLabel, text, error);
}
QString AdjustPage::message() const { return ui_->messageLabel->text(); }
QTableWidget* AdjustPage::links() const { return ui_->linkTable; }

}  // namespace lcnc::hmi
