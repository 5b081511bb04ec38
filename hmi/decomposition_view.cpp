#include "hmi/decomposition_view.h"

#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <limits>

#include "hmi/page_support.h"

namespace lcnc::hmi {
namespace {

using dxf::Vec2;

// A vertex closer than this to the last one drawn is skipped (pixels): a
// 1 µm step part has millions of points, a panel a few hundred pixels.
constexpr double kMinPixelStep = 0.75;

struct Frame {  // a box of mm mapped into a panel, aspect kept, y up
  double scale = 1, ox = 0, oy = 0;
  Frame(double x0, double y0, double x1, double y1, const QRectF& panel) {
    const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
    scale = std::min(panel.width() / w, panel.height() / h);
    ox = panel.left() + 0.5 * (panel.width() - w * scale) - x0 * scale;
    oy = panel.bottom() - 0.5 * (panel.height() - h * scale) + y0 * scale;
  }
  [[nodiscard]] QPointF at(const Vec2& p) const { return {ox + p.x() * scale, oy - p.y() * scale}; }
};

template <typename F>
void draw(QPainter& g, std::size_t n, F point, const Frame& f, const QColor& color, double width) {
  QPainterPath path;
  QPointF last(1e300, 1e300);
  for (std::size_t i = 0; i < n; ++i) {
    const QPointF q = f.at(point(i));
    if (i == 0) {
      path.moveTo(q);
    } else if (QLineF(last, q).length() >= kMinPixelStep || i + 1 == n) {
      path.lineTo(q);
    } else {
      continue;
    }
    last = q;
  }
  g.setPen(QPen(color, width));
  g.drawPath(path);
}

}  // namespace

DecompositionView::DecompositionView(QWidget* parent) : QWidget(parent) {
  make_canvas(this, "decompositionView", 400, 240);
}

void DecompositionView::set_result(const decompose::PartResult* part, double half_field_mm) {
  part_ = part;
  half_field_ = half_field_mm;
  update();
}

void DecompositionView::paintEvent(QPaintEvent*) {
  QPainter g(this);
  g.setRenderHint(QPainter::Antialiasing);
  const double pad = 12, label = 18;
  const double panel_w = (width() - 3 * pad) / 2;
  const QRectF left(pad, pad, panel_w, height() - 2 * pad - label);
  const QRectF right(2 * pad + panel_w, pad, panel_w, height() - 2 * pad - label);
  g.setPen(Qt::black);
  if (part_ == nullptr || part_->contours.empty()) {
    g.drawText(rect(), Qt::AlignCenter, tr("Open a DXF drawing and decompose it."));
    return;
  }
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const decompose::ContourResult& c : part_->contours) {
    for (std::size_t i = 0; i < c.table.size(); ++i) {
      for (const Vec2& p : {c.table.beam[i], c.table.main[i]}) {
        x0 = std::min(x0, p.x());
        y0 = std::min(y0, p.y());
        x1 = std::max(x1, p.x());
        y1 = std::max(y1, p.y());
      }
    }
  }
  const Frame fp(x0, y0, x1, y1, left);
  const double f = half_field_;
  const Frame fa(-f, -f, f, f, right);
  g.setPen(QPen(QColor("#999999"), 1, Qt::DashLine));
  g.drawRect(QRectF(fa.at(Vec2(-f, f)), fa.at(Vec2(f, -f))));
  for (const decompose::ContourResult& c : part_->contours) {
    const decompose::KinematicsTable& t = c.table;
    draw(
        g, t.size(), [&](std::size_t i) { return t.beam[i]; }, fp, QColor("green"), 2.0);
    draw(
        g, t.size(), [&](std::size_t i) { return t.main[i]; }, fp, QColor("blue"), 1.5);
    draw(
        g, t.size(), [&](std::size_t i) { return t.aux(i); }, fa, QColor("red"), 1.2);
  }
  g.setPen(Qt::black);
  g.drawText(QRectF(left.left(), left.bottom() + 2, left.width(), label), Qt::AlignLeft,
             tr("S contour (green), S1 main axes X, Y (blue) — mm"));
  g.drawText(QRectF(right.left(), right.bottom() + 2, right.width(), label), Qt::AlignLeft,
             tr("S2 = S − S1 auxiliary axes P, Q (red) in the field ±%1 mm").arg(f));
}

}  // namespace lcnc::hmi
