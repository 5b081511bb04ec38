#include "hmi/cut_page.h"

#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QPainter>
#include <QStandardPaths>
#include <QVBoxLayout>

#include <algorithm>
#include <limits>
#include <utility>

#include "common/output_file.h"
#include "dxf/dxf_reader.h"
#include "hmi/page_support.h"
#include "ui_cut_page.h"

namespace lcnc::hmi {

// The plan drawn, framed on the drawing, y up.
class CutView : public QWidget {
 public:
  explicit CutView(QWidget* parent) : QWidget(parent) { make_canvas(this, "cutView", 400, 300); }
  void set_plan(const cut::CutPlan* plan, cut::Vec2 origin) {
    plan_ = plan;
    origin_ = std::move(origin);
    update();
  }

 protected:
  void paintEvent(QPaintEvent*) override {
    QPainter g(this);
    g.setRenderHint(QPainter::Antialiasing);
    if (plan_ == nullptr || plan_->contours.empty()) {
      g.drawText(rect(), Qt::AlignCenter, CutPage::tr("Open a DXF part to plan its cut."));
      return;
    }
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
    const auto grow = [&](const cut::Vec2& p) {
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    };
    for (const cut::CutContour& c : plan_->contours) {
      for (const cut::Vec2& p : c.drawing) grow(p + origin_);
      grow(c.entry.pierce);
    }
    const double m = 0.05 * std::max({x1 - x0, y1 - y0, 1e-3});
    x0 -= m, x1 += m, y0 -= m, y1 += m;
    const QRectF area(10, 10, width() - 20, height() - 20);
    const double k = std::min(area.width() / (x1 - x0), area.height() / (y1 - y0));
    const double ox = area.center().x() - 0.5 * (x0 + x1) * k, oy = area.center().y() + 0.5 * (y0 + y1) * k;
    const auto px = [&](const cut::Vec2& p) { return QPointF(ox + p.x() * k, oy - p.y() * k); };
    const auto polyline = [&](const std::vector<cut::Vec2>& pts, bool closed, const cut::Vec2& shift) {
      QPolygonF poly;
      for (const cut::Vec2& p : pts) poly << px(p + shift);
      if (closed && !poly.isEmpty()) poly << poly.front();
      g.drawPolyline(poly);
    };
    int order = 0;
    for (const cut::CutContour& c : plan_->contours) {
      ++order;
      g.setPen(QPen(QColor("#bdbdbd"), 1.0));
      polyline(c.drawing, true, origin_);
      g.setPen(QPen(c.hole ? QColor("#2e7d32") : QColor("#1565c0"), 1.4));
      polyline(c.entry.path, true, cut::Vec2::Zero());
      g.setPen(QPen(QColor("#c62828"), 1.4));
      if (!c.entry.path.empty()) {
        g.drawLine(px(c.entry.pierce), px(c.entry.path.front()));
        std::vector<cut::Vec2> over = {c.entry.path.front()};
        over.insert(over.end(), c.entry.overcut.begin(), c.entry.overcut.end());
        polyline(over, false, cut::Vec2::Zero());
      }
      g.setBrush(QColor("#c62828"));
      g.drawEllipse(px(c.entry.pierce), 2.5, 2.5);
      g.setBrush(Qt::NoBrush);
      g.setPen(Qt::black);
      g.drawText(px(c.entry.pierce) + QPointF(4, -4), QString::number(order));
    }
  }

 private:
  const cut::CutPlan* plan_ = nullptr;
  cut::Vec2 origin_ = cut::Vec2::Zero();
};

CutPage::CutPage(std::string shm_name, QWidget* parent)
    : QWidget(parent), ui_(std::make_unique<Ui::CutPage>()), link_(std::move(shm_name)) {
  ui_->setupUi(this);
  view_ = new CutView(ui_->viewHolder);
  auto* l = new QVBoxLayout(ui_->viewHolder);
  l->setContentsMargins(0, 0, 0, 0);
  l->addWidget(view_);
  connect(ui_->openButton, &QPushButton::clicked, this, [this] {
    const QString p = QFileDialog::getOpenFileName(this, tr("Open a part"), {}, tr("DXF (*.dxf)"));
    if (!p.isEmpty()) open_file(p);
  });
  connect(ui_->planButton, &QPushButton::clicked, this, [this] { plan(); });
  connect(ui_->saveButton, &QPushButton::clicked, this, [this] {
    const QString p =
        QFileDialog::getSaveFileName(this, tr("Save the cutting program"), {}, tr("G-code (*.ngc)"));
    if (!p.isEmpty()) save(p);
  });
  connect(ui_->loadButton, &QPushButton::clicked, this, [this] { load(); });
}

CutPage::~CutPage() = default;

cut::CutOptions CutPage::options() const {
  cut::CutOptions o;
  o.outer = ui_->directionCombo->currentIndex() == 0 ? cut::Direction::Cw : cut::Direction::Ccw;
  o.lead_in_mm = ui_->leadInSpin->value();
  o.lead_out_mm = ui_->leadOutSpin->value();
  o.process.defaults.feed_mm_min = ui_->feedSpin->value();
  o.process.defaults.power_pct = ui_->powerSpin->value();
  o.process.defaults.pierce_s = ui_->pierceSpin->value();
  o.process.defaults.kerf_mm = ui_->kerfSpin->value();
  o.origin = cut::Vec2(ui_->originXSpin->value(), ui_->originYSpin->value());
  o.units_given = ui_->unitsCombo->currentIndex() != 0;
  return o;
}

bool CutPage::open_file(const QString& path) {
  file_ = QFileInfo(path).absoluteFilePath();
  ui_->fileLabel->setText(QFileInfo(path).fileName());
  ui_->fileLabel->setToolTip(file_);
  return plan();
}

bool CutPage::plan() {
  plan_.reset();
  view_->set_plan(nullptr, cut::Vec2::Zero());
  ui_->summaryLabel->clear();
  ui_->saveButton->setEnabled(false);
  ui_->loadButton->setEnabled(false);
  if (file_.isEmpty()) return false;
  // the drawing's units: its $INSUNITS, or the operator's choice
  static constexpr double kUnitMm[] = {0.0, 1.0, 25.4, 10.0, 1000.0};
  dxf::ReadOptions ro;
  ro.unit_mm = kUnitMm[std::clamp(ui_->unitsCombo->currentIndex(), 0, 4)];
  Result<dxf::ReadResult> read = dxf::read_dxf_file(file_.toStdString(), ro);
  if (!read) {
    show_message(QString::fromStdString(read.error().to_string()), true);
    return false;
  }
  const cut::CutOptions o = options();
  if (Status s = cut::check_units(read->drawing, o.units_given); !s) {
    show_message(QString::fromStdString(s.error().to_string()) + "\n" +
                     tr("Choose the drawing's units above, then plan again."),
                 true);
    return false;
  }
  Result<cut::CutPlan> p = cut::plan_cut(read->drawing, o);
  if (!p) {
    show_message(QString::fromStdString(p.error().to_string()), true);
    return false;
  }
  drawing_ = std::move(read->drawing);
  plan_ = std::move(p).value();
  view_->set_plan(&*plan_, o.origin);
  ui_->summaryLabel->setText(tr("%1 contours (%2 holes, %3 parts), holes first; cut %4 mm, lead-ins %5 mm, "
                                "rapids %6 mm; about %7 s")
                                 .arg(plan_->contours.size())
                                 .arg(plan_->holes)
                                 .arg(plan_->parts)
                                 .arg(plan_->cut_mm, 0, 'f', 1)
                                 .arg(plan_->lead_mm, 0, 'f', 1)
                                 .arg(plan_->rapid_mm, 0, 'f', 1)
                                 .arg(plan_->time_s, 0, 'f', 1));
  QStringList warnings;
  for (const std::string& w : plan_->warnings) warnings << QString::fromStdString(w);
  show_message(warnings.isEmpty() ? tr("Planned. Save the program, or load it into the controller.")
                                  : warnings.join("\n"),
               false);
  ui_->saveButton->setEnabled(true);
  ui_->loadButton->setEnabled(true);
  return true;
}

std::string CutPage::gcode() const {
  return plan_ ? cut::cut_gcode(*plan_, options(), file_.toStdString()) : std::string();
}

bool CutPage::save(const QString& path) {
  if (!plan_) return false;
  const std::string text = gcode();
  // never over the drawing it was made from
  if (const Status s = write_output(path.toStdString(), {file_.toStdString()},
                                    [&text](std::ostream& out) { out << text; });
      !s) {
    show_message(tr("Cannot write %1: %2").arg(path, QString::fromStdString(s.error().to_string())), true);
    return false;
  }
  show_message(tr("Saved %1.").arg(path), false);
  return true;
}

bool CutPage::load() {
  if (!plan_) return false;
  // the operator's cut folder ($XDG_DATA_HOME/lasercnc/cut), the part's name
  const QString dir = QStandardPaths::writableLocation(QStandardPaths::GenericDataLocation) + "/lasercnc/cut";
  if (!QDir().mkpath(dir)) {
    show_message(tr("Cannot make %1.").arg(dir), true);
    return false;
  }
  const QString path = dir + "/" + QFileInfo(file_).completeBaseName() + ".ngc";
  if (!save(path)) return false;
  if (!link_.poll() || link_.send(shm::CommandType::Load, 0.0, 0, path.toStdString()) == 0) {
    show_message(tr("Saved %1; not loaded: no link to the controller.").arg(path), true);
    return false;
  }
  show_message(tr("Loaded %1 into the controller (cycle start on the machine screen).").arg(path), false);
  return true;
}

void CutPage::show_message(const QString& text, bool error) { set_message(ui_->messageLabel, text, error); }
QString CutPage::message() const { return ui_->messageLabel->text(); }
QString CutPage::summary() const { return ui_->summaryLabel->text(); }

}  // namespace lcnc::hmi
