#include "holes/hole_placement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "path/segment_geometry.h"

namespace lcnc {
namespace {

constexpr double kUm = 0.001;

HoleProcessParams row(HoleProcessId id, double a_deg) {
  HoleProcessParams p;
  p.hole_number = 3;
  p.position << 400.0, 150.0, 60.0, a_deg, 0.0, 120.0;
  p.layer_feed_mm = 0.1;
  p.layer_count = 5;
  p.total_depth_mm = 0.5;
  p.head.start_radius_mm = 0.4;
  p.head.end_radius_mm = 0.4;
  p.head.radius_turns = 1;
  p.process = id;
  return p;
}

// Every placed segment, sampled with the joints as the planner moves them,
// maps back (forward kinematics, then into the hole frame) onto the hole:
// radius within 1 µm and depth within 0 … −total. (Radius for
// all cutting moves: these rows have a single scan radius.)
void expect_on_hole(const HoleProgram& local, const HoleProgram& placed, const FiveAxisKinematics& kin,
                    double radius, double depth) {
  const Eigen::Isometry3d to_local = local.frame.inverse();
  for (std::size_t i = 1; i < placed.segments.size(); ++i) {  // [0] is the approach rapid
    const Segment& s = placed.segments[i];
    const SegmentGeometry g(s);
    for (int k = 0; k <= 50; ++k) {
      const Pose q = g.at(g.length() * k / 50.0);
      const Vec3 p = to_local * kin.forward(q).tip_mm;
      ASSERT_LT(std::abs(std::hypot(p.x(), p.y()) - radius), kUm) << "segment " << i;
      ASSERT_LE(p.z(), kUm);
      ASSERT_GE(p.z(), -depth - kUm);
    }
    ASSERT_LT((s.start - placed.segments[i - 1].end).norm(), 1e-9);
  }
}

TEST(HolePlacement, TableTableKeepsG17Helices) {
  FiveAxisGeometry g;
  g.variant = MachineVariant::TableTable;
  const FiveAxisKinematics kin(g);
  const Result<HoleProgram> local = generate_hole(row(HoleProcessId::Helix, 35.0));
  ASSERT_TRUE(local.ok());
  const Result<HoleProgram> placed = place_hole(*local, kin);
  ASSERT_TRUE(placed.ok()) << placed.error().to_string();
  ASSERT_EQ(placed->segments.size(), local->segments.size());
  EXPECT_EQ(placed->segments[1].kind, MotionKind::Arc);
  EXPECT_EQ(placed->segments[1].plane, Plane::XY);
  EXPECT_NEAR(SegmentGeometry(placed->segments[1]).sweep_rad(), 10.0 * std::numbers::pi, 1e-9);
  expect_on_hole(*local, *placed, kin, 0.4, 0.5);
}

// On a tilted head each arc stays one arc: a Free-plane helix or circle
// about the tilted hole axis with the sweep it has in the hole frame (every
// full turn kept: a circle comes back onto its start only to rounding).
TEST(HolePlacement, TiltedHeadTurnsHelicesAndCirclesIntoFreeArcs) {
  const FiveAxisKinematics kin;  // head-head
  for (const double c_deg : {0.0, 45.0, 120.0, 300.0}) {
    for (const double a_deg : {35.0, -20.0, 30.0}) {
      HoleProcessParams hr = row(HoleProcessId::Helix, a_deg);
      hr.position[index(Axis::C)] = c_deg;
      const Result<HoleProgram> helix = generate_hole(hr);
      ASSERT_TRUE(helix.ok());
      const Result<HoleProgram> placed = place_hole(*helix, kin);
      ASSERT_TRUE(placed.ok());
      ASSERT_EQ(placed->segments.size(), helix->segments.size());
      EXPECT_EQ(placed->events.back().before_segment, placed->segments.size());
      const Segment& h = placed->segments[1];
      EXPECT_EQ(h.kind, MotionKind::Arc);
      EXPECT_EQ(h.plane, Plane::Free);
      const SegmentGeometry hg(h);
      EXPECT_NEAR(hg.sweep_rad(), 10.0 * std::numbers::pi, 1e-9) << "A " << a_deg << " C " << c_deg;
      EXPECT_NEAR(hg.length(), std::hypot(0.4 * 10.0 * std::numbers::pi, 0.5), 1e-9);
      expect_on_hole(*helix, *placed, kin, 0.4, 0.5);

      HoleProcessParams cr = row(HoleProcessId::Circle, a_deg);
      cr.position[index(Axis::C)] = c_deg;
      const Result<HoleProgram> circle = generate_hole(cr);
      ASSERT_TRUE(circle.ok());
      const Result<HoleProgram> pc = place_hole(*circle, kin);
      ASSERT_TRUE(pc.ok());
      ASSERT_EQ(pc->segments.size(), circle->segments.size());
      int free_arcs = 0;
      for (const Segment& s : pc->segments) {
        if (s.kind != MotionKind::Arc) continue;
        ++free_arcs;
        EXPECT_EQ(s.plane, Plane::Free);
        EXPECT_NEAR(SegmentGeometry(s).sweep_rad(), 2.0 * std::numbers::pi, 1e-9)
            << "ring " << free_arcs << " at A " << a_deg << " C " << c_deg;
      }
      EXPECT_EQ(free_arcs, 5);
      expect_on_hole(*circle, *pc, kin, 0.4, 0.5);
    }
  }
}

}  // namespace
}  // namespace lcnc
