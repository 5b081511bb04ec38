// The toolpath drawn (XY, machine coordinates, y up), framed on the cut:
// cutting moves coloured by path speed from blue (slow) to red (the fastest
// cut) — the blends' slow-downs show — rapids and moves with the laser off
// dashed grey; a speed scale; the machine's position as a cross.
#pragma once

#include <QWidget>

#include <optional>

#include "hmi/toolpath.h"

namespace lcnc::hmi {

class ToolpathView : public QWidget {
  Q_OBJECT

 public:
  explicit ToolpathView(QWidget* parent = nullptr);
  void set_toolpath(const Toolpath* path);  // kept by the caller; null: none
  void set_position(std::optional<Vec3> at);

  // The colour of a speed on the scale (0 … peak).
  [[nodiscard]] static QColor speed_color(double speed, double peak);

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  const Toolpath* path_ = nullptr;
  std::optional<Vec3> at_;
};

}  // namespace lcnc::hmi
