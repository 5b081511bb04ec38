// Property: random drawings of closed polylines on a 1 µm grid, some simple,
// some crossing or touching themselves or each other. An exact reference
// (integer orientation tests over every pair of chords) decides which is
// which. `plan_cut` refuses every drawing the reference finds a crossing in,
// at a point on two chords that meet; it cuts every other one completely:
// without a kerf, each contour's cut path is as long as its drawing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "common/error.h"
#include "cut/cut_program.h"
#include "dxf/dxf_reader.h"

namespace lcnc::cut {
namespace {

using IPoint = std::pair<std::int64_t, std::int64_t>;  // µm
using IPoly = std::vector<IPoint>;

std::int64_t orient(const IPoint& a, const IPoint& b, const IPoint& c) {
  const std::int64_t v =
      (b.first - a.first) * (c.second - a.second) - (b.second - a.second) * (c.first - a.first);
  return (v > 0) - (v < 0);
}

bool on_segment(const IPoint& a, const IPoint& b, const IPoint& p) {
  return std::min(a.first, b.first) <= p.first && p.first <= std::max(a.first, b.first) &&
         std::min(a.second, b.second) <= p.second && p.second <= std::max(a.second, b.second);
}

// Closed segments ab and cd share a point.
bool meet(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d) {
  const std::int64_t o1 = orient(a, b, c), o2 = orient(a, b, d);
  const std::int64_t o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

struct Chord {
  IPoint a, b;
};

double distance(const Vec2& p, const Chord& c) {
  const Vec2 a(c.a.first * 1e-3, c.a.second * 1e-3), b(c.b.first * 1e-3, c.b.second * 1e-3);
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Every pair of chords that meet where they should not: non-neighbours that
// share any point, neighbours that fold back onto each other.
std::vector<std::pair<Chord, Chord>> reference_crossings(const std::vector<IPoly>& polys) {
  std::vector<std::pair<Chord, Chord>> out;
  struct Ref {
    std::size_t poly, j;
    Chord c;
  };
  std::vector<Ref> all;
  for (std::size_t p = 0; p < polys.size(); ++p) {
    const IPoly& q = polys[p];
    for (std::size_t j = 0; j < q.size(); ++j) all.push_back({p, j, {q[j], q[(j + 1) % q.size()]}});
  }
  for (std::size_t u = 0; u < all.size(); ++u) {
    for (std::size_t v = u + 1; v < all.size(); ++v) {
      const Ref& r = all[u];
      const Ref& s = all[v];
      const std::size_t n = polys[r.poly].size();
      const bool next = r.poly == s.poly && ((r.j + 1) % n == s.j || (s.j + 1) % n == r.j);
      if (next) {
        // neighbours share one vertex; they meet wrongly only when collinear
        // and turning back (the shared vertex between the other two ends)
        const IPoint& shared = (r.j + 1) % n == s.j ? r.c.b : r.c.a;
        const IPoint& x = (r.j + 1) % n == s.j ? r.c.a : r.c.b;
        const IPoint& y = (r.j + 1) % n == s.j ? s.c.b : s.c.a;
        const bool back =
            orient(x, shared, y) == 0 && (x.first - shared.first) * (y.first - shared.first) +
                                                 (x.second - shared.second) * (y.second - shared.second) >
                                             0;
        if (back) out.push_back({r.c, s.c});
        continue;
      }
      if (meet(r.c.a, r.c.b, s.c.a, s.c.b)) out.push_back({r.c, s.c});
    }
  }
  return out;
}

// A polygon star-shaped about (cx, cy): simple unless rounding to the grid
// folds it (the reference tells).
IPoly star(std::mt19937& rng, double cx, double cy, double r_min, double r_max, int n) {
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), radius(r_min, r_max);
  std::vector<double> a(static_cast<std::size_t>(n));
  for (double& x : a) x = angle(rng);
  std::sort(a.begin(), a.end());
  IPoly p;
  for (double t : a) {
    const double r = radius(rng);
    const IPoint q{std::llround((cx + r * std::cos(t)) * 1e3), std::llround((cy + r * std::sin(t)) * 1e3)};
    if (p.empty() || q != p.back()) p.push_back(q);
  }
  if (p.size() > 1 && p.back() == p.front()) p.pop_back();
  return p;
}

IPoly scatter(std::mt19937& rng, int n) {
  std::uniform_int_distribution<std::int64_t> c(0, 60000);
  IPoly p;
  for (int i = 0; i < n; ++i) {
    const IPoint q{c(rng), c(rng)};
    if (p.empty() || q != p.back()) p.push_back(q);
  }
  if (p.size() > 1 && p.back() == p.front()) p.pop_back();
  return p;
}

std::string dxf_text(const std::vector<IPoly>& polys) {
  std::string s = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
  char buf[64];
  for (const IPoly& p : polys) {
    s += "0\nLWPOLYLINE\n8\nCUT\n90\n" + std::to_string(p.size()) + "\n70\n1\n";
    for (const IPoint& q : p) {
      std::snprintf(buf, sizeof buf, "10\n%.3f\n20\n%.3f\n", q.first * 1e-3, q.second * 1e-3);
      s += buf;
    }
  }
  return s + "0\nENDSEC\n0\nEOF\n";
}

double perimeter(const IPoly& p) {
  double l = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const IPoint& a = p[i];
    const IPoint& b = p[(i + 1) % p.size()];
    l += std::hypot((b.first - a.first) * 1e-3, (b.second - a.second) * 1e-3);
  }
  return l;
}

TEST(CutCrossingProperty, CrossingsAreRefusedWhereTheyAreAndSimpleDrawingsCutWhole) {
  std::mt19937 rng(20261207);
  std::uniform_int_distribution<int> kind(0, 4), count(3, 30);
  std::uniform_real_distribution<double> place(20.0, 80.0);
  int refused = 0, cut = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<IPoly> polys;
    switch (kind(rng)) {
      case 0:  // one star: simple
        polys.push_back(star(rng, 50, 50, 5, 30, count(rng)));
        break;
      case 1:  // scattered points: mostly crossing
        polys.push_back(scatter(rng, count(rng) / 3 + 3));
        break;
      case 2: {  // a star with two vertices swapped
        IPoly p = star(rng, 50, 50, 5, 30, count(rng) + 3);
        std::uniform_int_distribution<std::size_t> at(0, p.size() - 1);
        std::swap(p[at(rng)], p[at(rng)]);
        polys.push_back(p);
        break;
      }
      case 3:  // two or three stars anywhere: apart, nested or overlapping
        for (int k = count(rng) % 2 + 2; k > 0; --k)
          polys.push_back(star(rng, place(rng), place(rng), 3, 15, count(rng)));
        break;
      default: {  // two stars that share a vertex exactly (touching)
        polys.push_back(star(rng, 30, 50, 5, 12, count(rng)));
        IPoly q = star(rng, 60, 50, 5, 12, count(rng));
        q[0] = *std::max_element(polys[0].begin(), polys[0].end());  // the rightmost
        polys.push_back(q);
        break;
      }
    }
    if (std::any_of(polys.begin(), polys.end(), [](const IPoly& p) { return p.size() < 3; })) continue;
    const std::string text = dxf_text(polys);
    Result<dxf::ReadResult> read = dxf::read_dxf_text(text, "random.dxf");
    ASSERT_TRUE(read.ok()) << read.error().to_string() << "\n" << text;
    CutOptions opt;
    opt.process.defaults.kerf_mm = 0.0;
    const Result<CutPlan> plan = plan_cut(read->drawing, opt);
    const std::vector<std::pair<Chord, Chord>> truth = reference_crossings(polys);
    if (!truth.empty()) {
      ++refused;
      ASSERT_FALSE(plan.ok()) << "trial " << trial << ": " << truth.size() << " crossings, yet cut\n" << text;
      // two closed polylines through one point: chaining finds the branch
      // there before the crossing check
      ASSERT_TRUE(plan.error().code == ErrorCode::DxfCrossing ||
                  plan.error().code == ErrorCode::DxfOpenContour)
          << plan.error().to_string();
      std::smatch m;
      const std::regex at(R"(at \((-?[0-9.]+), (-?[0-9.]+)\))");
      ASSERT_TRUE(std::regex_search(plan.error().message, m, at)) << plan.error().message;
      const Vec2 p(std::stod(m[1]), std::stod(m[2]));
      const bool on_a_pair = std::any_of(truth.begin(), truth.end(), [&](const auto& c) {
        return distance(p, c.first) <= 1e-3 && distance(p, c.second) <= 1e-3;
      });
      EXPECT_TRUE(on_a_pair) << "trial " << trial << ": " << plan.error().message << "\n" << text;
      continue;
    }
    ++cut;
    ASSERT_TRUE(plan.ok()) << "trial " << trial << ": " << plan.error().to_string() << "\n" << text;
    ASSERT_EQ(plan->contours.size(), polys.size());
    double drawn_total = 0.0, cut_total = 0.0, perimeters = 0.0;
    for (const IPoly& p : polys) perimeters += perimeter(p);
    for (const CutContour& c : plan->contours) {
      double drawn = 0.0;
      for (std::size_t i = 0; i < c.drawing.size(); ++i)
        drawn += (c.drawing[(i + 1) % c.drawing.size()] - c.drawing[i]).norm();
      EXPECT_NEAR(c.path_mm, drawn, 1e-6) << "trial " << trial << " " << c.name << "\n" << text;
      drawn_total += drawn;
      cut_total += c.path_mm;
    }
    EXPECT_NEAR(drawn_total, perimeters, 1e-6) << "trial " << trial;
    EXPECT_NEAR(cut_total, perimeters, 1e-6) << "trial " << trial;
  }
  // both kinds occur often enough for the property to mean something
  EXPECT_GT(refused, 100);
  EXPECT_GT(cut, 100);
}

}  // namespace
}  // namespace lcnc::cut
