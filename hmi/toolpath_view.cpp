#include "hmi/toolpath_view.h"

#include <QLinearGradient>
#include <QPainter>

#include <algorithm>
#include <limits>

namespace lcnc::hmi {

ToolpathView::ToolpathView(QWidget* parent) : QWidget(parent) {
  setObjectName("toolpathView");
  setMinimumSize(400, 300);
  setAutoFillBackground(true);
  QPalette p = palette();
  p.setColor(QPalette::Window, Qt::white);
  setPalette(p);
}

void ToolpathView::set_toolpath(const Toolpath* path) {
  path_ = path;
  update();
}

void ToolpathView::set_position(std::optional<Vec3> at) {
  if (at == at_) return;
  at_ = at;
  update();
}

QColor ToolpathView::speed_color(double speed, double peak) {
  const double f = peak > 0 ? std::clamp(speed / peak, 0.0, 1.0) : 0.0;
  return QColor::fromHsvF((1.0 - f) * 240.0 / 360.0, 1.0, 0.85);  // blue → red
}

void ToolpathView::paintEvent(QPaintEvent*) {
  QPainter g(this);
  g.setRenderHint(QPainter::Antialiasing);
  if (path_ == nullptr || path_->points.empty()) {
    g.drawText(rect(), Qt::AlignCenter, tr("Open a program to see its toolpath as planned."));
    return;
  }
  // framed on the cut (the rapids to and from it may leave the frame), the
  // colour scale on the cutting speeds
  bool any_cut = false;
  double peak = 0.0;
  for (const ToolpathPoint& p : path_->points)
    if (p.laser) {
      any_cut = true;
      peak = std::max(peak, p.speed);
    }
  if (!any_cut) peak = path_->peak_speed;
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const ToolpathPoint& p : path_->points) {
    if (any_cut && !p.laser) continue;
    x0 = std::min(x0, p.at.x());
    x1 = std::max(x1, p.at.x());
    y0 = std::min(y0, p.at.y());
    y1 = std::max(y1, p.at.y());
  }
  const double margin = 0.05 * std::max(x1 - x0, y1 - y0);
  x0 -= margin;
  x1 += margin;
  y0 -= margin;
  y1 += margin;
  const QRectF area(12, 12, width() - 100, height() - 24);
  const double w = std::max(x1 - x0, 1e-6), h = std::max(y1 - y0, 1e-6);
  const double k = std::min(area.width() / w, area.height() / h);
  const double ox = area.left() + 0.5 * (area.width() - w * k) - x0 * k;
  const double oy = area.bottom() - 0.5 * (area.height() - h * k) + y0 * k;
  const auto px = [&](const Vec3& p) { return QPointF(ox + p.x() * k, oy - p.y() * k); };
  g.setClipRect(area.adjusted(-4, -4, 4, 4));
  for (std::size_t i = 1; i < path_->points.size(); ++i) {
    const ToolpathPoint& a = path_->points[i - 1];
    const ToolpathPoint& b = path_->points[i];
    if (b.laser) {
      g.setPen(QPen(speed_color(b.speed, peak), 1.6));
    } else {
      g.setPen(QPen(QColor("#9e9e9e"), 0.8, Qt::DashLine));
    }
    g.drawLine(px(a.at), px(b.at));
  }
  if (at_) {
    const QPointF c = px(*at_);
    g.setPen(QPen(Qt::black, 1.5));
    g.drawLine(c - QPointF(8, 0), c + QPointF(8, 0));
    g.drawLine(c - QPointF(0, 8), c + QPointF(0, 8));
    g.drawEllipse(c, 4, 4);
  }
  g.setClipping(false);
  // the speed scale (cutting)
  const QRectF bar(width() - 76, 24, 14, height() - 60);
  QLinearGradient grad(bar.bottomLeft(), bar.topLeft());
  for (int s = 0; s <= 10; ++s) grad.setColorAt(s / 10.0, speed_color(s / 10.0, 1.0));
  g.fillRect(bar, grad);
  g.setPen(Qt::black);
  g.drawRect(bar);
  g.drawText(QPointF(bar.right() + 4, bar.top() + 10), QString::number(peak, 'f', 0));
  g.drawText(QPointF(bar.right() + 4, bar.bottom()), QStringLiteral("0"));
  g.drawText(QPointF(bar.left() - 10, bar.bottom() + 18), tr("mm/s"));
}

}  // namespace lcnc::hmi
