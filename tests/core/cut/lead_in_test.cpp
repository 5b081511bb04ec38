#include "cut/lead_in.h"

#include <gtest/gtest.h>

#include "core/cut/cut_test_util.h"
#include "cut/contour_polygon.h"
#include "cut/kerf_offset.h"

namespace lcnc::cut {
namespace {

std::vector<Vec2> cw(std::vector<Vec2> p) {
  std::reverse(p.begin(), p.end());
  return p;
}

TEST(LeadIn, OutlineIsPiercedOutsideAtACornerNearestTheBeam) {
  const std::vector<Vec2> drawing = test::square(0, 0, 20);
  const std::vector<Vec2> path = cw(offset_polygon(drawing, 0.1).front());
  LeadInRequest req;
  req.lead_in_mm = 2.0;
  req.offset_mm = 0.1;
  const LeadIn li = place_lead_in(path, drawing, Vec2(30, 30), req, {});
  EXPECT_FALSE(li.shortened);
  EXPECT_DOUBLE_EQ(li.lead_in_mm, 2.0);
  EXPECT_NEAR((li.pierce - li.path.front()).norm(), 2.0, 1e-9);
  // on the scrap side: outside the part, 2 mm + kerf/2 from it
  EXPECT_FALSE(inside(li.pierce, drawing));
  EXPECT_NEAR(distance_to(li.pierce, drawing), 2.1, 1e-3);
  // at the corner (20, 20), along its bisector
  EXPECT_NEAR((li.path.front() - Vec2(20, 20)).norm(), 0.1, 1e-3);
  // (the round join's vertex nearest the bisector: within a few degrees)
  EXPECT_NEAR(li.pierce.x() - 20, li.pierce.y() - 20, 0.3);
  // the path keeps its direction and length, starting there
  EXPECT_EQ(li.path.size(), path.size());
  EXPECT_LT(signed_area(li.path), 0.0);
}

TEST(LeadIn, HoleIsPiercedInsideAtTheVertexNearestTheBeam) {
  const std::vector<Vec2> drawing = test::ngon(0, 0, 5, 360);
  const std::vector<Vec2> path = offset_polygon(drawing, -0.1).front();  // ccw
  LeadInRequest req;
  req.hole = true;
  req.lead_in_mm = 2.0;
  req.lead_out_mm = 0.5;
  req.offset_mm = 0.1;
  const LeadIn li = place_lead_in(path, drawing, Vec2(-20, 0), req, {});
  EXPECT_FALSE(li.shortened);
  EXPECT_TRUE(inside(li.pierce, drawing));
  EXPECT_NEAR(li.path.front().x(), -4.9, 1e-3);  // the side facing the beam
  EXPECT_NEAR(li.pierce.norm(), 2.9, 1e-3);      // 2 mm in from the path, towards the centre
  // the lead-out: 0.5 mm on along the path
  ASSERT_FALSE(li.overcut.empty());
  double l = (li.overcut.front() - li.path.front()).norm();
  for (std::size_t i = 1; i < li.overcut.size(); ++i) l += (li.overcut[i] - li.overcut[i - 1]).norm();
  EXPECT_NEAR(l, 0.5, 1e-9);
  for (const Vec2& p : li.overcut) EXPECT_NEAR(distance_to(p, path), 0.0, 1e-9);
}

TEST(LeadIn, SmallHoleGetsAShorterLeadIn) {
  const std::vector<Vec2> drawing = test::ngon(0, 0, 1.0, 180);
  const std::vector<Vec2> path = offset_polygon(drawing, -0.1).front();
  LeadInRequest req;
  req.hole = true;
  req.lead_in_mm = 3.0;  // more than the hole is wide
  req.offset_mm = 0.1;
  const LeadIn li = place_lead_in(path, drawing, Vec2(0, 0), req, {});
  EXPECT_TRUE(li.shortened);
  EXPECT_GT(li.lead_in_mm, 0.0);
  EXPECT_LT(li.lead_in_mm, 1.8);  // inside the 1.8 mm wide path
  EXPECT_TRUE(inside(li.pierce, path));
}

TEST(LeadIn, ALeadInDoesNotCrossAnotherPath) {
  // a hole right next to the outline's corner: the corner's lead-in would
  // cross it, so the next corner is taken
  const std::vector<Vec2> drawing = test::square(0, 0, 20);
  const std::vector<Vec2> path = cw(offset_polygon(drawing, 0.1).front());
  const std::vector<Vec2> other = test::square(20.5, 20.5, 2);
  LeadInRequest req;
  req.offset_mm = 0.1;
  const LeadIn li = place_lead_in(path, drawing, Vec2(30, 30), req, {&other});
  EXPECT_FALSE(li.shortened);
  EXPECT_GT((li.path.front() - Vec2(20, 20)).norm(), 1.0);
}

}  // namespace
}  // namespace lcnc::cut
