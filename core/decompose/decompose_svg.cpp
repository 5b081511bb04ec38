#include "decompose/decompose_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/svg_view.h"

namespace lcnc::decompose {
namespace {

// A vertex closer than this to the last one drawn is skipped (pixels).
constexpr double kMinPixelStep = 0.75;

using svg::Box;
using svg::escape;
using svg::num;
using svg::View;

template <typename F>
std::string polyline(std::size_t n, F point, const View& v, const char* color, double width) {
  std::string s = "<polyline fill=\"none\" stroke=\"" + std::string(color) + "\" stroke-width=\"" +
                  num(width) + "\" points=\"";
  Vec2 last(1e300, 1e300);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 q = v.px(point(i));
    if ((q - last).norm() < kMinPixelStep && i + 1 < n) continue;
    s += num(q.x()) + "," + num(q.y()) + " ";
    last = q;
  }
  return s + "\"/>\n";
}

}  // namespace

std::string paths_svg(const PartResult& r, const Options& opt, const std::string& title) {
  constexpr double W = 1200, H = 640, pad = 40;
  Box part, aux;
  for (const ContourResult& c : r.contours) {
    for (std::size_t i = 0; i < c.table.size(); ++i) {
      part.add(c.table.beam[i]);
      part.add(c.table.main[i]);
      aux.add(c.table.aux(i));
    }
  }
  const double f = opt.aux_half_field_mm;
  aux.add(Vec2(-f, -f));
  aux.add(Vec2(f, f));
  const double panel = (W - 3 * pad) / 2;
  const View vp(part, pad, pad + 20, panel, H - 2 * pad - 40);
  const View va(aux, 2 * pad + panel, pad + 20, panel, H - 2 * pad - 40);
  std::string s = svg::open(W, H);
  s += "<text x=\"" + num(pad) + "\" y=\"22\">" + escape(title) + "</text>\n";
  s += "<text x=\"" + num(pad) + "\" y=\"" + num(H - 12) +
       "\"><tspan fill=\"green\">S contour</tspan>, <tspan fill=\"blue\">S1 main axes "
       "(X, Y)</tspan> — part coordinates, mm</text>\n";
  s += "<text x=\"" + num(2 * pad + panel) + "\" y=\"" + num(H - 12) +
       "\"><tspan fill=\"red\">S2 = S − S1 auxiliary axes (P, Q)</tspan> in the field ±" + num(f) +
       " mm</text>\n";
  // The field.
  s += "<polygon fill=\"none\" stroke=\"#999\" stroke-dasharray=\"4 3\" points=\"" + va.pt(Vec2(-f, -f)) +
       " " + va.pt(Vec2(f, -f)) + " " + va.pt(Vec2(f, f)) + " " + va.pt(Vec2(-f, f)) + "\"/>\n";
  for (const ContourResult& c : r.contours) {
    const KinematicsTable& t = c.table;
    s += polyline(
        t.size(), [&](std::size_t i) { return t.beam[i]; }, vp, "green", 2.0);
    s += polyline(
        t.size(), [&](std::size_t i) { return t.main[i]; }, vp, "blue", 1.0);
    s += polyline(
        t.size(), [&](std::size_t i) { return t.aux(i); }, va, "red", 1.0);
  }
  return s + "</svg>\n";
}

std::string accel_svg(const PartResult& r, const Options& opt, const std::string& title) {
  constexpr double W = 1200, H = 480, left = 70, right = 20, top = 40, bottom = 50;
  const double pw = W - left - right, ph = H - top - bottom;
  double t_total = 0, a_top = opt.main_accel_mm_s2;
  for (const ContourResult& c : r.contours) {
    t_total += c.peaks.duration_s;
    a_top = std::max({a_top, c.peaks.a_eff, c.peaks.a_main});
  }
  t_total = std::max(t_total, 1e-9);
  a_top *= 1.1;
  // Per pixel column: the peak of each curve (m/s²).
  const auto cols = static_cast<std::size_t>(pw);
  std::vector<double> eff(cols, -1.0), mainc(cols, -1.0);
  double t0 = 0;
  for (const ContourResult& c : r.contours) {
    const KinematicsTable& t = c.table;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const auto k = std::min(cols - 1, static_cast<std::size_t>((t0 + t.t_s[i]) / t_total * pw));
      eff[k] = std::max(eff[k], t.a_eff[i]);
      mainc[k] = std::max(mainc[k], t.a_main[i]);
    }
    t0 += c.peaks.duration_s;
  }
  auto y = [&](double a) { return top + ph - a / a_top * ph; };
  auto curve = [&](const std::vector<double>& v, const char* color) {
    std::string s =
        "<polyline fill=\"none\" stroke=\"" + std::string(color) + "\" stroke-width=\"1\" points=\"";
    for (std::size_t k = 0; k < cols; ++k) {
      if (v[k] < 0) continue;
      s += num(left + static_cast<double>(k)) + "," + num(y(v[k])) + " ";
    }
    return s + "\"/>\n";
  };
  std::string s = svg::open(W, H);
  s += "<text x=\"" + num(left) + "\" y=\"22\">" + escape(title) + "</text>\n";
  s += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(pw) + "\" height=\"" + num(ph) +
       "\" fill=\"none\" stroke=\"black\"/>\n";
  for (int k = 0; k <= 5; ++k) {  // axis labels
    const double a = a_top * k / 5.0;
    s += "<text x=\"" + num(left - 6) + "\" y=\"" + num(y(a) + 4) + "\" text-anchor=\"end\">" +
         num(a / 1000.0).substr(0, 6) + "</text>\n";
    const double tt = t_total * k / 5.0;
    s += "<text x=\"" + num(left + pw * k / 5.0) + "\" y=\"" + num(top + ph + 18) +
         "\" text-anchor=\"middle\">" + num(tt).substr(0, 7) + "</text>\n";
  }
  s += "<text x=\"" + num(left + pw / 2) + "\" y=\"" + num(H - 8) +
       "\" text-anchor=\"middle\">time, s</text>\n";
  s += "<text x=\"14\" y=\"" + num(top + ph / 2) + "\" transform=\"rotate(-90 14 " + num(top + ph / 2) +
       ")\" text-anchor=\"middle\">acceleration, m/s²</text>\n";
  s += curve(eff, "green") + curve(mainc, "blue");
  const double yl = y(opt.main_accel_mm_s2);
  s += "<line x1=\"" + num(left) + "\" y1=\"" + num(yl) + "\" x2=\"" + num(left + pw) + "\" y2=\"" + num(yl) +
       "\" stroke=\"blue\" stroke-dasharray=\"6 4\"/>\n";
  s += "<text x=\"" + num(left + pw - 4) + "\" y=\"" + num(top + 16) +
       "\" text-anchor=\"end\"><tspan fill=\"green\">effective (beam)</tspan>  <tspan "
       "fill=\"blue\">main axes; dashed: main-axis limit</tspan></text>\n";
  return s + "</svg>\n";
}

std::string axes_svg(const AxisCurves& c, const std::string& title) {
  constexpr double W = 1200, H = 520, left = 70, right = 70, top = 40, bottom = 50;
  const double pw = W - left - right, ph = H - top - bottom;
  const std::size_t n = c.t_s.size();
  const double t_end = n > 0 ? std::max(c.t_s.back(), 1e-9) : 1.0;
  // value ranges of each group, both coordinates on one scale
  double m0 = std::numeric_limits<double>::max(), m1 = -m0, a0 = m0, a1 = -m0;
  for (std::size_t i = 0; i < n; ++i) {
    m0 = std::min({m0, c.main[i].x(), c.main[i].y()});
    m1 = std::max({m1, c.main[i].x(), c.main[i].y()});
    a0 = std::min({a0, c.aux[i].x(), c.aux[i].y()});
    a1 = std::max({a1, c.aux[i].x(), c.aux[i].y()});
  }
  for (double* r : {&m0, &a0}) {
    double& lo = r[0];
    double& hi = r == &m0 ? m1 : a1;
    if (!(hi - lo >= 1e-6)) {
      const double mid = n > 0 ? 0.5 * (lo + hi) : 0.0;
      lo = mid - 0.5;
      hi = mid + 0.5;
    }
  }
  const auto px = [&](double t) { return left + t / t_end * pw; };
  const auto ym = [&](double v) { return top + ph - (v - m0) / (m1 - m0) * ph; };
  const auto ya = [&](double v) { return top + ph - (v - a0) / (a1 - a0) * ph; };
  std::string s = svg::open(W, H);
  s += "<text x=\"" + num(left) + "\" y=\"22\">" + escape(title) + "</text>\n";
  // laser-on spans
  for (std::size_t i = 0; i < n;) {
    if (!c.laser[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < n && c.laser[j + 1]) ++j;
    const double x0 = px(i > 0 ? c.t_s[i - 1] : c.t_s[i]), x1 = px(c.t_s[j]);
    s += "<rect x=\"" + num(x0) + "\" y=\"" + num(top) + "\" width=\"" + num(std::max(x1 - x0, 0.5)) +
         "\" height=\"" + num(ph) + "\" fill=\"#fff2cc\"/>\n";
    i = j + 1;
  }
  s += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(pw) + "\" height=\"" + num(ph) +
       "\" fill=\"none\" stroke=\"black\"/>\n";
  for (int k = 0; k <= 5; ++k) {
    const double f = k / 5.0;
    s += "<text x=\"" + num(left - 6) + "\" y=\"" + num(top + ph - f * ph + 4) +
         "\" text-anchor=\"end\" fill=\"#1f4e9c\">" + num(m0 + f * (m1 - m0)).substr(0, 7) + "</text>\n";
    s += "<text x=\"" + num(left + pw + 6) + "\" y=\"" + num(top + ph - f * ph + 4) + "\" fill=\"#b22222\">" +
         num(a0 + f * (a1 - a0)).substr(0, 7) + "</text>\n";
    s += "<text x=\"" + num(left + pw * f) + "\" y=\"" + num(top + ph + 18) + "\" text-anchor=\"middle\">" +
         num(t_end * f).substr(0, 7) + "</text>\n";
  }
  s += "<text x=\"" + num(left + pw / 2) + "\" y=\"" + num(H - 8) +
       "\" text-anchor=\"middle\">time, s (shaded: laser on)</text>\n";
  const auto curve = [&](auto value, auto y, const char* color, const char* dash) {
    std::string o = "<polyline fill=\"none\" stroke=\"" + std::string(color) + "\" stroke-width=\"1.2\"" +
                    dash + " points=\"";
    double last_x = -1e9;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = px(c.t_s[i]);
      if (x - last_x < kMinPixelStep && i + 1 < n) continue;
      o += num(x) + "," + num(y(value(i))) + " ";
      last_x = x;
    }
    return o + "\"/>\n";
  };
  s += curve([&](std::size_t i) { return c.main[i].x(); }, ym, "#1f4e9c", "");
  s += curve([&](std::size_t i) { return c.main[i].y(); }, ym, "#1f4e9c", " stroke-dasharray=\"6 3\"");
  s += curve([&](std::size_t i) { return c.aux[i].x(); }, ya, "#b22222", "");
  s += curve([&](std::size_t i) { return c.aux[i].y(); }, ya, "#b22222", " stroke-dasharray=\"6 3\"");
  s += "<text x=\"" + num(left + pw) +
       "\" y=\"22\" text-anchor=\"end\"><tspan fill=\"#1f4e9c\">main X "
       "(solid), Y (dashed), mm, left scale</tspan>  <tspan fill=\"#b22222\">auxiliary P (solid), Q "
       "(dashed), mm, right scale</tspan></text>\n";
  return s + "</svg>\n";
}

}  // namespace lcnc::decompose
