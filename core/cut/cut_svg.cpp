#include "cut/cut_svg.h"

#include <algorithm>

#include "common/svg_view.h"

namespace lcnc::cut {

std::string plan_svg(const CutPlan& plan, const std::string& title) {
  constexpr double W = 1000, H = 760, pad = 40, top = 50, bottom = 60;
  svg::Box box;
  for (const CutContour& c : plan.contours) {
    for (const Vec2& p : c.entry.path) box.add(p);
    box.add(c.entry.pierce);
  }
  const svg::View v(box, pad, top, W - 2 * pad, H - top - bottom);
  using svg::num;
  // Text size and dots scale with the picture, not the part.
  const double dot = 3.0;
  std::string s = svg::open(W, H);
  s += "<text x=\"" + num(pad) + "\" y=\"24\">" + svg::escape(title) + "</text>\n";
  s += "<text x=\"" + num(pad) + "\" y=\"" + num(H - 30) +
       "\">drawing (black), <tspan fill=\"blue\">kerf-offset cut path</tspan>, "
       "<tspan fill=\"red\">pierce point and lead-in</tspan>, <tspan fill=\"darkorange\">lead-out"
       "</tspan>, <tspan fill=\"grey\">rapids</tspan>; numbers: cutting order</text>\n";
  s += "<text x=\"" + num(pad) + "\" y=\"" + num(H - 12) + "\">" + std::to_string(plan.contours.size()) +
       " contours (" + std::to_string(plan.parts) + " outlines, " + std::to_string(plan.holes) +
       " holes), cut " + num(plan.cut_mm) + " mm, rapids " + num(plan.rapid_mm) + " mm, about " +
       num(plan.time_s) + " s</text>\n";
  auto poly = [&](const std::vector<Vec2>& p, bool closed, const char* color, double width,
                  const char* extra = "") {
    std::string o = std::string("<") + (closed ? "polygon" : "polyline") + " fill=\"none\" stroke=\"" +
                    color + "\" stroke-width=\"" + num(width) + "\"" + extra + " points=\"";
    for (const Vec2& q : p) o += v.pt(q) + " ";
    return o + "\"/>\n";
  };
  Vec2 at = plan.contours.empty() ? Vec2::Zero() : plan.contours.front().entry.pierce;
  for (const CutContour& c : plan.contours) {
    s += poly(c.drawing, true, "black", 0.6);
  }
  for (std::size_t k = 0; k < plan.contours.size(); ++k) {
    const CutContour& c = plan.contours[k];
    if (k > 0) s += poly({at, c.entry.pierce}, false, "grey", 0.8, " stroke-dasharray=\"4 3\"");
    s += poly(c.entry.path, true, "blue", 1.2);
    s += poly({c.entry.pierce, c.entry.path.front()}, false, "red", 1.6);
    if (!c.entry.overcut.empty()) {
      std::vector<Vec2> out{c.entry.path.front()};
      out.insert(out.end(), c.entry.overcut.begin(), c.entry.overcut.end());
      s += poly(out, false, "darkorange", 2.0);
      at = c.entry.overcut.back();
    } else {
      at = c.entry.path.front();
    }
    const Vec2 p = v.px(c.entry.pierce);
    s +=
        "<circle cx=\"" + num(p.x()) + "\" cy=\"" + num(p.y()) + "\" r=\"" + num(dot) + "\" fill=\"red\"/>\n";
    s += "<text x=\"" + num(p.x() + 5) + "\" y=\"" + num(p.y() - 5) +
         "\" fill=\"red\" font-weight=\"bold\">" + std::to_string(k + 1) + "</text>\n";
  }
  return s + "</svg>\n";
}

}  // namespace lcnc::cut
