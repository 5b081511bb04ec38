// Discretization into n equal steps down to 1 µm.
#include "dxf/discretize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error.h"
#include "core/dxf/dxf_test_util.h"
#include "dxf/contour_chain.h"

namespace lcnc::dxf {
namespace {

std::vector<Contour> contours(const std::string& file) {
  Result<std::vector<Contour>> cs = chain_contours(test::read_ok(file));
  EXPECT_TRUE(cs.ok());
  return cs.ok() ? *cs : std::vector<Contour>{};
}

TEST(Discretize, EqualStepsNoLongerThanAsked) {
  const std::vector<Contour> cs = contours(test::dxf_data("arc_slot.dxf"));
  const double len = 40 + 10 * std::numbers::pi;
  const Polyline p = discretize(cs[0], 0.01);
  EXPECT_EQ(p.size(), static_cast<std::size_t>(std::ceil(len / 0.01)));
  EXPECT_NEAR(p.length_mm, len, 1e-9);
  EXPECT_LE(p.step_mm, 0.01);
  EXPECT_NEAR(p.step_mm * static_cast<double>(p.size()), len, 1e-9);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double chord = (p.pts[(i + 1) % p.size()] - p.pts[i]).norm();
    // Equal along the curve; a chord of an r 5 arc is shorter by ≤ Δ³/(24 r²).
    EXPECT_LE(chord, p.step_mm + 1e-12);
    EXPECT_GE(chord, p.step_mm - std::pow(p.step_mm, 3) / (24 * 25) - 1e-12);
  }
}

TEST(Discretize, PointsLieOnTheCircle) {
  const std::vector<Contour> cs = contours(test::dxf_data("circle.dxf"));
  const Polyline p = discretize(cs[0], 0.001);  // 1 µm
  EXPECT_EQ(p.size(), static_cast<std::size_t>(std::ceil(8 * std::numbers::pi / 0.001)));
  for (const Vec2& q : p.pts) EXPECT_NEAR((q - Vec2(5, 5)).norm(), 4.0, 1e-12);
  EXPECT_EQ(p.src_line.front(), 19u);
}

TEST(Discretize, StepBelowOneMicronIsRejected) {
  const std::vector<Contour> cs = contours(test::dxf_data("circle.dxf"));
  Result<std::vector<Polyline>> r = discretize_all(cs, 0.0005, "c.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DecomposeBadOption);
  EXPECT_MENTIONS(r.error(), "expected at least 0.001000 mm (1 µm)");
}

TEST(Discretize, TinyContoursKeepAFewPoints) {
  const std::vector<Contour> cs = contours(test::dxf_data("circle.dxf"));
  const Polyline p = discretize(cs[0], 100.0);
  EXPECT_EQ(p.size(), 8u);
}

}  // namespace
}  // namespace lcnc::dxf
