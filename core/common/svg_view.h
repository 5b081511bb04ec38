// What the SVG pictures of the CLI share (decompose's paths, cut's plan):
// numbers at 3 decimals, escaped text, a bounding box, and the view that maps
// drawing millimetres into a panel of the picture keeping the aspect, y up.
#pragma once

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include <Eigen/Core>

namespace lcnc::svg {

inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

inline std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else
      o += c;
  }
  return o;
}

struct Box {
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = -std::numeric_limits<double>::max(), y1 = x1;
  void add(const Eigen::Vector2d& p) {
    x0 = std::min(x0, p.x());
    y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
};

// Maps a box into a panel (px, py, size) keeping the aspect, y up.
struct View {
  double sx, ox, oy, py_bottom;
  View(const Box& b, double px, double py, double w, double h) {
    const double bw = std::max(b.x1 - b.x0, 1e-9), bh = std::max(b.y1 - b.y0, 1e-9);
    sx = std::min(w / bw, h / bh);
    ox = px + 0.5 * (w - bw * sx) - b.x0 * sx;
    oy = b.y0;
    py_bottom = py + h - 0.5 * (h - bh * sx);
  }
  [[nodiscard]] Eigen::Vector2d px(const Eigen::Vector2d& p) const {
    return Eigen::Vector2d(ox + p.x() * sx, py_bottom - (p.y() - oy) * sx);
  }
  [[nodiscard]] std::string pt(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = px(p);
    return num(q.x()) + "," + num(q.y());
  }
};

// The opening of a white picture W × H, sans-serif 13 px.
inline std::string open(double w, double h) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(w) + "\" height=\"" + num(h) +
         "\" font-family=\"sans-serif\" font-size=\"13\">\n"
         "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
}

}  // namespace lcnc::svg
