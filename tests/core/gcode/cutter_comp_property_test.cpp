// Property: random notches, slots with a narrow mouth and steps under G41.1 /
// G42.1, each straight side split into 1–4 collinear moves. Every program
// is either refused with E313, or its compensated path keeps the tool
// radius from the programmed path everywhere (within the corner tolerance's
// chord and a micrometre; sampled every 5 µm) and no straight move runs
// against its programmed direction. Where the tool cannot fit (a notch or a
// mouth narrower than its diameter) the program is refused whatever the
// split; where it fits and nothing is split, it is accepted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using Vec2 = Eigen::Vector2d;

double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

struct Case {
  std::string text;
  std::vector<Vec2> corners;              // the programmed contour, from (10, 100)
  std::vector<std::uint32_t> first_line;  // the first program line of each side
  std::vector<std::uint32_t> lines;       // side of each program line (index into corners)
  int fits = 1;                           // the tool fits every feature (1), not (-1), too near to tell (0)
  bool split = false;
  double r = 0.0;
};

// Whether a feature w wide takes a tool d in diameter: within the check's
// tolerance of d, either answer is right.
int verdict(double w, double d, double r) {
  const double tol = 2.0 * (1e-3 + r * (1.0 - std::cos(0.05)));
  return w >= d + tol ? 1 : w <= d - tol ? -1 : 0;
}

Case make_case(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Case c;
  c.r = 0.3 + 1.2 * u(rng);
  const double d = 2.0 * c.r;
  const bool right = u(rng) < 0.5;  // G42.1: the drawing mirrored in Y
  const int kind = static_cast<int>(u(rng) * 3.0);
  // the contour in "tool above" form (G41 moving +x); y measured down from 100
  std::vector<Vec2> pts{{10, 0}};
  const double x0 = 20.0, h = 3.0 + 7.0 * u(rng);
  if (kind == 0) {  // a notch w wide
    const double w = d * (0.6 + 0.9 * u(rng));
    c.fits = verdict(w, d, c.r);
    pts.insert(pts.end(), {{x0, 0}, {x0, h}, {x0 + w, h}, {x0 + w, 0}, {x0 + w + 10, 0}});
  } else if (kind == 1) {  // a slot: a mouth m wide, below it 2.5 d wide
    const double m = d * (0.6 + 0.9 * u(rng)), wide = 2.5 * d, neck = 1.0 + 3.0 * u(rng);
    c.fits = verdict(m, d, c.r);
    const double l = x0 - (wide - m) / 2.0;
    pts.insert(pts.end(), {{x0, 0},
                           {x0, neck},
                           {l, neck},
                           {l, neck + h},
                           {l + wide, neck + h},
                           {l + wide, neck},
                           {x0 + m, neck},
                           {x0 + m, 0},
                           {x0 + m + 10, 0}});
  } else {  // a step down
    pts.insert(pts.end(), {{x0, 0}, {x0, h}, {x0 + 10, h}});
  }
  for (Vec2& p : pts) p = Vec2(p.x(), right ? 100.0 + p.y() : 100.0 - p.y());
  c.corners = pts;
  std::ostringstream g;
  g.setf(std::ios::fixed);
  g.precision(4);
  const double away = right ? 90.0 : 110.0;
  g << "G21 G90 G17\nG0 X5 Y" << away << "\n"
    << (right ? "G42.1" : "G41.1") << " D" << d << "\nG1 X10 Y100 F600\n";
  std::uint32_t line = 5;
  c.lines.assign(line, 0);
  std::uniform_int_distribution<int> pieces(1, 4);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const int k = u(rng) < 0.5 ? 1 : pieces(rng);
    c.split = c.split || k > 1;
    std::vector<double> at;
    for (int j = 1; j < k; ++j) at.push_back(0.05 + 0.9 * u(rng));
    std::sort(at.begin(), at.end());
    at.push_back(1.0);
    c.first_line.push_back(line);
    for (double t : at) {
      const Vec2 p = pts[i - 1] + t * (pts[i] - pts[i - 1]);
      g << "G1 X" << p.x() << " Y" << p.y() << "\n";
      c.lines.push_back(static_cast<std::uint32_t>(i));
      ++line;
    }
  }
  g << "G40\nG0 X" << pts.back().x() + 5 << " Y" << away << "\nM2\n";
  c.text = g.str();
  return c;
}

TEST(CutterCompProperty, RefusedOrTheToolRadiusFromThePathNeverReversed) {
  std::mt19937 rng(20261207);
  int refused = 0, accepted = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Case c = make_case(rng);
    const test::Run run = test::run(c.text, test::start_at(5, 100, 10));
    if (run.last == ProgramReader::Next::Error) {
      ++refused;
      EXPECT_EQ(run.error.code, ErrorCode::GcodeCutterComp) << run.error.to_string() << "\n" << c.text;
      EXPECT_FALSE(c.fits == 1 && !c.split)
          << "a feature the tool fits, refused: " << run.error.to_string() << "\n"
          << c.text;
      continue;
    }
    ++accepted;
    EXPECT_NE(c.fits, -1) << "the tool does not fit, yet accepted:\n" << c.text;
    // the contour's compensated moves: sampled, the distance to the
    // programmed path within tol of the radius; straights never backwards
    const double tol = 1e-3 + c.r * (1.0 - std::cos(0.05)) + 1e-9;
    auto to_path = [&](const Vec2& p) {
      double best = 1e300;
      for (std::size_t i = 1; i < c.corners.size(); ++i)
        best = std::min(best, point_segment(p, c.corners[i - 1], c.corners[i]));
      return best;
    };
    for (const Segment& s : run.segments) {
      if (s.line < 5 || s.line >= c.lines.size() || s.kind == MotionKind::Rapid) continue;
      const Vec2 a(s.start[0], s.start[1]), b(s.end[0], s.end[1]);
      std::vector<Vec2> samples;
      if (s.kind == MotionKind::Arc) {
        const Vec2 ctr(s.center[0], s.center[1]);
        const double a0 = std::atan2(a.y() - ctr.y(), a.x() - ctr.x());
        double sweep = std::atan2(b.y() - ctr.y(), b.x() - ctr.x()) - a0;
        if (s.clockwise && sweep > 0) sweep -= 2 * M_PI;
        if (!s.clockwise && sweep < 0) sweep += 2 * M_PI;
        const double rad = (a - ctr).norm();
        const int n = std::max(2, static_cast<int>(std::abs(sweep) * rad / 0.005));
        for (int k = 0; k <= n; ++k) {
          const double t = a0 + sweep * k / n;
          samples.push_back(ctr + rad * Vec2(std::cos(t), std::sin(t)));
        }
      } else {
        const int n = std::max(2, static_cast<int>((b - a).norm() / 0.005));
        for (int k = 0; k <= n; ++k) samples.push_back(a + (b - a) * (static_cast<double>(k) / n));
        const std::uint32_t side = c.lines[s.line];
        const Vec2 dir = c.corners[side] - c.corners[side - 1];
        EXPECT_GE((b - a).dot(dir.normalized()), -1e-6) << "line " << s.line << " runs backwards\n" << c.text;
      }
      for (const Vec2& p : samples) {
        const double dist = to_path(p);
        ASSERT_GE(dist, c.r - tol) << "trial " << trial << ": line " << s.line << " at (" << p.x() << ", "
                                   << p.y() << ") gouges\n"
                                   << c.text;
        ASSERT_LE(dist, c.r + tol) << "trial " << trial << ": line " << s.line << " strays\n" << c.text;
      }
    }
  }
  EXPECT_GT(refused, 100);
  EXPECT_GT(accepted, 100);
}

}  // namespace
}  // namespace lcnc
