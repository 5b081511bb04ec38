#include "dxf/spline_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/dxf/dxf_test_util.h"

namespace lcnc::dxf {
namespace {

const std::vector<Vec2> kFit = {{0, 0}, {10, 5}, {20, 0}, {35, 8}, {40, 20}};

// The nearest the curve comes to q, sampled every 1 µm of its length.
double distance_spline_fit(const SplineCurve& c, const Vec2& q) {
  double d = 1e300;
  for (double s = 0; s <= c.length(); s += 1e-3) d = std::min(d, (c.at_length(s) - q).norm());
  return std::min(d, (c.at_length(c.length()) - q).norm());
}

TEST(SplineFit, PassesThroughEveryFitPointAtItsChordLengthParameter) {
  SplineData s;
  s.fit = kFit;
  ASSERT_TRUE(interpolate_fit_points(s, nullptr));
  EXPECT_EQ(s.control.size(), 3 * (kFit.size() - 1) + 1);
  EXPECT_EQ(s.knots.size(), s.control.size() + 4);
  std::string why;
  const auto c = SplineCurve::make(s, &why);
  ASSERT_TRUE(c) << why;
  double t = 0;
  for (std::size_t i = 0; i < kFit.size(); ++i) {
    if (i > 0) t += (kFit[i] - kFit[i - 1]).norm();
    EXPECT_LT((c->at_param(t) - kFit[i]).norm(), 1e-9) << i;
  }
}

TEST(SplineFit, NaturalEndsHaveNoCurvatureAndTangentsAreHonoured) {
  SplineData s;
  s.fit = kFit;
  ASSERT_TRUE(interpolate_fit_points(s, nullptr));
  // natural: C''(0) = 6·(P0 − 2·P1 + P2)/h² = 0
  EXPECT_LT((s.control[0] - 2 * s.control[1] + s.control[2]).norm(), 1e-9);
  const std::size_t m = s.control.size() - 1;
  EXPECT_LT((s.control[m] - 2 * s.control[m - 1] + s.control[m - 2]).norm(), 1e-9);

  SplineData t;
  t.fit = kFit;
  t.start_tangent = Vec2(0, 3);  // straight up (any length: a direction)
  t.end_tangent = Vec2(-1, 0);   // arriving leftwards
  ASSERT_TRUE(interpolate_fit_points(t, nullptr));
  const Vec2 d0 = (t.control[1] - t.control[0]).normalized();
  const Vec2 d1 = (t.control[m] - t.control[m - 1]).normalized();
  EXPECT_NEAR(d0.x(), 0.0, 1e-12);
  EXPECT_NEAR(d0.y(), 1.0, 1e-12);
  EXPECT_NEAR(d1.x(), -1.0, 1e-12);
  EXPECT_NEAR(d1.y(), 0.0, 1e-12);
}

TEST(SplineFit, TwoPointsAreAStraightLineAndOneIsRefused) {
  SplineData s;
  s.fit = {{0, 0}, {3, 4}};
  ASSERT_TRUE(interpolate_fit_points(s, nullptr));
  const auto c = SplineCurve::make(s, nullptr);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->length(), 5.0, 1e-9);
  std::string why;
  s = SplineData{};
  s.fit = {{1, 1}, {1, 1}};
  EXPECT_FALSE(interpolate_fit_points(s, &why));
  EXPECT_NE(why.find("fewer than 2"), std::string::npos);
}

TEST(SplineFit, AFitPointSplineInADxfIsReadThroughItsPointsWithItsTangents) {
  // SPLINE of fit points only (73 = 0 control points), start tangent 12/22
  // up, end tangent 13/23 to the right
  std::string sp = "0\nSPLINE\n8\nCUT\n70\n8\n71\n3\n72\n0\n73\n0\n74\n" + std::to_string(kFit.size()) +
                   "\n12\n0.0\n22\n1.0\n32\n0.0\n13\n1.0\n23\n0.0\n33\n0.0\n";
  for (const Vec2& p : kFit)
    sp += "11\n" + std::to_string(p.x()) + "\n21\n" + std::to_string(p.y()) + "\n31\n0.0\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(sp), "fit.dxf");
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  ASSERT_EQ(r->drawing.entities.size(), 1u);
  const Edge& e = r->drawing.entities[0].edges.at(0);
  ASSERT_EQ(e.kind, EdgeKind::Spline);
  for (const Vec2& q : kFit) EXPECT_LT(distance_spline_fit(*e.spline, q), 1e-3) << q.transpose();
  // leaves straight up, arrives heading right
  const Vec2 a = e.spline->at_length(0.01) - e.spline->start();
  EXPECT_NEAR(a.normalized().y(), 1.0, 1e-4);
  const Vec2 b = e.spline->end() - e.spline->at_length(e.spline->length() - 0.01);
  EXPECT_NEAR(b.normalized().x(), 1.0, 1e-4);
}

}  // namespace
}  // namespace lcnc::dxf
