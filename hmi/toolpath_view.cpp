#include "hmi/toolpath_view.h"

#include <QLinearGradient>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>
#include <limits>

#include "hmi/page_support.h"

namespace lcnc::hmi {
namespace {

const QColor kRapidColor("#9e9e9e");
const QColor kDarkFeedColor("#8d6e63");  // a feed move with the laser off
const QColor kToolAxisColor("#7b1fa2");
const QColor kGridColor("#eceff1");

}  // namespace

ToolpathView::ToolpathView(QWidget* parent) : QWidget(parent) { make_canvas(this, "toolpathView", 400, 300); }

void ToolpathView::set_toolpath(const Toolpath* path) {
  path_ = path;
  update();
}

void ToolpathView::set_position(const std::optional<Vec3>& at) {
  if (at == at_) return;
  at_ = at;
  update();
}

void ToolpathView::set_view(const ViewAngles& v) {
  view_ = v;
  view_.pitch_deg = std::clamp(v.pitch_deg, 0.0, 90.0);
  zoom_ = 1.0;
  pan_ = {};
  update();
}

QColor ToolpathView::speed_color(double speed, double peak) {
  const double f = peak > 0 ? std::clamp(speed / peak, 0.0, 1.0) : 0.0;
  return QColor::fromHsvF((1.0 - f) * 240.0 / 360.0, 1.0, 0.85);  // blue → red
}

void ToolpathView::mousePressEvent(QMouseEvent* e) { drag_from_ = e->pos(); }

void ToolpathView::mouseMoveEvent(QMouseEvent* e) {
  const QPoint d = e->pos() - drag_from_;
  drag_from_ = e->pos();
  if (e->buttons() & Qt::LeftButton) {
    view_.yaw_deg += 0.5 * d.x();
    view_.pitch_deg = std::clamp(view_.pitch_deg - 0.5 * d.y(), 0.0, 90.0);
  } else if (e->buttons() & Qt::RightButton) {
    pan_ += d;
  }
  update();
}

void ToolpathView::wheelEvent(QWheelEvent* e) {
  zoom_ = std::clamp(zoom_ * std::pow(1.0015, e->angleDelta().y()), 0.05, 200.0);
  update();
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
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  double sx0 = kInf, sy0 = kInf, sx1 = -kInf, sy1 = -kInf;
  for (const ToolpathPoint& p : path_->points) {
    if (any_cut && !p.laser) continue;
    lo = lo.cwiseMin(p.at);
    hi = hi.cwiseMax(p.at);
    const ScreenPoint s = project(p.at, view_);
    sx0 = std::min(sx0, s.x), sx1 = std::max(sx1, s.x), sy0 = std::min(sy0, s.y), sy1 = std::max(sy1, s.y);
  }
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z(), 1e-3});
  const double margin = 0.05 * std::max({sx1 - sx0, sy1 - sy0, 1e-3});
  sx0 -= margin, sx1 += margin, sy0 -= margin, sy1 += margin;
  const QRectF area(12, 12, width() - 100, height() - 56);
  const double w = sx1 - sx0, h = sy1 - sy0;
  const double k = std::min(area.width() / w, area.height() / h) * zoom_;
  const double ox = area.center().x() - 0.5 * (sx0 + sx1) * k + pan_.x();
  const double oy = area.center().y() + 0.5 * (sy0 + sy1) * k + pan_.y();
  const auto px = [&](const Vec3& p) {
    const ScreenPoint s = project(p, view_);
    return QPointF(ox + s.x * k, oy - s.y * k);
  };
  g.setClipRect(area.adjusted(-4, -4, 4, 4));
  // the grid on the lowest cut's plane, over the cut's X Y extents
  const double step = nice_step(std::max(hi.x() - lo.x(), hi.y() - lo.y()), 10);
  g.setPen(QPen(kGridColor, 1.0));
  const double gx0 = std::floor(lo.x() / step) * step, gx1 = std::ceil(hi.x() / step) * step;
  const double gy0 = std::floor(lo.y() / step) * step, gy1 = std::ceil(hi.y() / step) * step;
  for (double x = gx0; x <= gx1 + 1e-9; x += step)
    g.drawLine(px(Vec3(x, gy0, lo.z())), px(Vec3(x, gy1, lo.z())));
  for (double y = gy0; y <= gy1 + 1e-9; y += step)
    g.drawLine(px(Vec3(gx0, y, lo.z())), px(Vec3(gx1, y, lo.z())));
  // the moves
  for (std::size_t i = 1; i < path_->points.size(); ++i) {
    const ToolpathPoint& a = path_->points[i - 1];
    const ToolpathPoint& b = path_->points[i];
    if (b.laser) {
      g.setPen(QPen(speed_color(b.speed, peak), 1.6));
    } else if (b.rapid) {
      g.setPen(QPen(kRapidColor, 0.8, Qt::DashLine));
    } else {
      g.setPen(QPen(kDarkFeedColor, 1.0));
    }
    g.drawLine(px(a.at), px(b.at));
  }
  // the tool axis along the cut of a 5-axis program, every 1/40 of its size
  if (path_->tilted) {
    g.setPen(QPen(kToolAxisColor, 1.0));
    double since = kInf;
    for (std::size_t i = 1; i < path_->points.size(); ++i) {
      const ToolpathPoint& p = path_->points[i];
      since += (p.at - path_->points[i - 1].at).norm();
      if (!p.laser || since < span / 40.0) continue;
      since = 0.0;
      g.drawLine(px(p.at), px(p.at + p.axis * (span / 12.0)));
    }
  }
  if (at_) {
    const QPointF c = px(*at_);
    g.setPen(QPen(Qt::black, 1.5));
    g.drawLine(c - QPointF(8, 0), c + QPointF(8, 0));
    g.drawLine(c - QPointF(0, 8), c + QPointF(0, 8));
    g.drawEllipse(c, 4, 4);
  }
  g.setClipping(false);
  // the axes, from the corner
  const QPointF origin(area.left() + 30, area.bottom() - 10);
  const auto axis_end = [&](const Vec3& d) {
    const ScreenPoint s = project(d, view_);
    return origin + QPointF(s.x * 24.0, -s.y * 24.0);
  };
  const std::pair<Vec3, const char*> axes[] = {
      {Vec3::UnitX(), "X"}, {Vec3::UnitY(), "Y"}, {Vec3::UnitZ(), "Z"}};
  const QColor axis_colours[] = {QColor("#c62828"), QColor("#2e7d32"), QColor("#1565c0")};
  for (int i = 0; i < 3; ++i) {
    g.setPen(QPen(axis_colours[i], 2.0));
    const QPointF end = axis_end(axes[i].first);
    g.drawLine(origin, end);
    g.drawText(end + QPointF(2, -2), axes[i].second);
  }
  // the extents and the legend
  g.setPen(Qt::black);
  const double bottom = height() - 26;
  g.drawText(QPointF(12, bottom), tr("Cut: X %1 … %2, Y %3 … %4, Z %5 … %6 mm; grid %7 mm")
                                      .arg(lo.x(), 0, 'f', 1)
                                      .arg(hi.x(), 0, 'f', 1)
                                      .arg(lo.y(), 0, 'f', 1)
                                      .arg(hi.y(), 0, 'f', 1)
                                      .arg(lo.z(), 0, 'f', 1)
                                      .arg(hi.z(), 0, 'f', 1)
                                      .arg(step, 0, 'g', 3));
  double lx = 12;
  const auto legend = [&](const QPen& pen, const QString& text) {
    g.setPen(pen);
    g.drawLine(QPointF(lx, bottom + 14), QPointF(lx + 24, bottom + 14));
    g.setPen(Qt::black);
    g.drawText(QPointF(lx + 30, bottom + 18), text);
    lx += 40 + g.fontMetrics().horizontalAdvance(text);
  };
  legend(QPen(speed_color(peak, peak), 2.0), tr("cut (colour: speed)"));
  legend(QPen(kDarkFeedColor, 1.5), tr("feed, laser off"));
  legend(QPen(kRapidColor, 1.0, Qt::DashLine), tr("rapid"));
  if (path_->tilted) legend(QPen(kToolAxisColor, 1.5), tr("tool axis"));
  // the speed scale (cutting)
  const QRectF bar(width() - 76, 24, 14, height() - 92);
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
