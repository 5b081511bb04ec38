// The picture of a decomposition (Kondratenko et al. 2015 Fig. 6), drawn with QPainter:
// left, the contour S green and the main-axis path S1 blue in part
// coordinates; right, the auxiliary path S2 = S − S1 red in its field (the
// field dashed). Empty until given a result.
#pragma once

#include <QWidget>

#include "decompose/part_decomposition.h"

namespace lcnc::hmi {

class DecompositionView : public QWidget {
  Q_OBJECT

 public:
  explicit DecompositionView(QWidget* parent = nullptr);
  // The part to draw (kept by the caller; null: nothing) and the field's half
  // width (mm).
  void set_result(const decompose::PartResult* part, double half_field_mm);

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  const decompose::PartResult* part_ = nullptr;
  double half_field_ = 5.0;
};

}  // namespace lcnc::hmi
