// The toolpath drawn in 3D (hmi/view_projection.h: from above, or turned
// and tipped), framed on the cut: cutting moves coloured by path speed from
// blue (slow) to red (the fastest cut) — the blends' slow-downs show — feed
// moves with the laser off solid brown, rapids dashed grey; on a 5-axis
// program the tool axis as purple strokes along the cut; a grid on the
// lowest cut's plane, the extents, the axes, a speed scale and a legend;
// the machine's position as a cross. Drag with the left button turns the
// view, with the right pans it; the wheel zooms.
#pragma once

#include <QPoint>
#include <QWidget>

#include <optional>

#include "hmi/toolpath.h"
#include "hmi/view_projection.h"

namespace lcnc::hmi {

class ToolpathView : public QWidget {
  Q_OBJECT

 public:
  explicit ToolpathView(QWidget* parent = nullptr);
  void set_toolpath(const Toolpath* path);  // kept by the caller; null: none
  void set_position(const std::optional<Vec3>& at);
  // The view's angles; zoom and pan back to the framed cut.
  void set_view(const ViewAngles& v);
  [[nodiscard]] const ViewAngles& view() const noexcept { return view_; }
  [[nodiscard]] double zoom() const noexcept { return zoom_; }

  // The colour of a speed on the scale (0 … peak).
  [[nodiscard]] static QColor speed_color(double speed, double peak);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  const Toolpath* path_ = nullptr;
  std::optional<Vec3> at_;
  ViewAngles view_ = kTopView;
  double zoom_ = 1.0;
  QPointF pan_;  // px
  QPoint drag_from_;
};

}  // namespace lcnc::hmi
