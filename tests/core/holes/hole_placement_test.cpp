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
// radius within 1 µm (+ chord sag) and depth within 0 … −total. (Radius for
// all cutting moves: these rows have a single scan radius.)
void expect_on_hole(const HoleProgram& local, const HoleProgram& placed,
                    const FiveAxisKinematics& kin, double radius, double depth, double sag) {
  const Eigen::Isometry3d to_local = local.frame.inverse();
  for (std::size_t i = 1; i < placed.segments.size(); ++i) {  // [0] is the approach rapid
    const Segment& s = placed.segments[i];
    const SegmentGeometry g(s);
    for (int k = 0; k <= 50; ++k) {
      const Pose q = g.at(g.length() * k / 50.0);
      const Vec3 p = to_local * kin.forward(q).tip_mm;
      ASSERT_LT(std::abs(std::hypot(p.x(), p.y()) - radius), kUm + sag) << "segment " << i;
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
  const Result<HoleProgram> placed = place_hole(*local, kin, 0.0005);
  ASSERT_TRUE(placed.ok()) << placed.error().to_string();
  ASSERT_EQ(placed->segments.size(), local->segments.size());
  EXPECT_EQ(placed->segments[1].kind, MotionKind::Arc);
  EXPECT_EQ(placed->segments[1].plane, Plane::XY);
  EXPECT_NEAR(SegmentGeometry(placed->segments[1]).sweep_rad(), 10.0 * std::numbers::pi, 1e-9);
  expect_on_hole(*local, *placed, kin, 0.4, 0.5, 0.0);
}

TEST(HolePlacement, TiltedHeadTurnsHelicesIntoChordsAndCirclesIntoFreeArcs) {
  const FiveAxisKinematics kin;  // head-head
  const Result<HoleProgram> helix = generate_hole(row(HoleProcessId::Helix, 35.0));
  ASSERT_TRUE(helix.ok());
  const Result<HoleProgram> placed = place_hole(*helix, kin, 0.0005);
  ASSERT_TRUE(placed.ok());
  EXPECT_GT(placed->segments.size(), 100u);
  EXPECT_EQ(placed->events.back().before_segment, placed->segments.size());
  expect_on_hole(*helix, *placed, kin, 0.4, 0.5, 0.0005);

  const Result<HoleProgram> circle = generate_hole(row(HoleProcessId::Circle, 35.0));
  ASSERT_TRUE(circle.ok());
  const Result<HoleProgram> pc = place_hole(*circle, kin, 0.0005);
  ASSERT_TRUE(pc.ok());
  ASSERT_EQ(pc->segments.size(), circle->segments.size());
  int free_arcs = 0;
  for (const Segment& s : pc->segments)
    free_arcs += s.kind == MotionKind::Arc && s.plane == Plane::Free;
  EXPECT_EQ(free_arcs, 5);
  expect_on_hole(*circle, *pc, kin, 0.4, 0.5, 0.0);
}

TEST(HolePlacement, RejectsZeroChordTolerance) {
  const Result<HoleProgram> local = generate_hole(row(HoleProcessId::Helix, 0.0));
  ASSERT_TRUE(local.ok());
  EXPECT_FALSE(place_hole(*local, FiveAxisKinematics{}, 0.0).ok());
}

}  // namespace
}  // namespace lcnc
