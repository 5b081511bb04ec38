#include "holes/hole_processes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "kinematics/five_axis.h"
#include "path/segment_geometry.h"

namespace lcnc {
namespace {

constexpr double kGeometryTol = 0.001;  // 1 µm: the drilling geometry's tolerance
constexpr double kTwoPi = 2.0 * std::numbers::pi;

HoleProcessParams row_hole_processes(HoleProcessId id) {
  HoleProcessParams p;
  p.hole_number = 7;
  p.position << 500.0, 200.0, 100.0, 30.0, 0.0, 45.0;
  p.feed_mm_min = 600.0;
  p.layer_feed_mm = 0.1;
  p.layer_count = 10;
  p.total_depth_mm = 1.0;
  p.power_pct = 80.0;
  p.head.start_radius_mm = 0.5;
  p.head.end_radius_mm = 0.5;
  p.process = id;
  return p;
}

HoleProgram generate(const HoleProcessParams& p) {
  Result<HoleProgram> r = generate_hole(p);
  EXPECT_TRUE(r.ok()) << r.error().to_string();
  return std::move(r).value();
}

// Largest |radius − r| and the z range over densely sampled cutting segments.
struct Sampled {
  double min_r = 1e9, max_r = 0.0, min_z = 1e9, max_z = -1e9;
};
Sampled sample(const HoleProgram& prog) {
  Sampled s;
  for (const Segment& seg : prog.segments) {
    if (seg.kind == MotionKind::Rapid) continue;
    const SegmentGeometry g(seg);
    for (int k = 0; k <= 400; ++k) {
      const Pose p = g.at(g.length() * k / 400.0);
      const double r = std::hypot(p[0], p[1]);
      s.min_r = std::min(s.min_r, r);
      s.max_r = std::max(s.max_r, r);
      s.min_z = std::min(s.min_z, p[2]);
      s.max_z = std::max(s.max_z, p[2]);
    }
  }
  return s;
}

TEST(HoleProcesses, HelixIsOneHelixOfLayerCountTurns) {
  const HoleProgram prog = generate(row_hole_processes(HoleProcessId::Helix));
  ASSERT_EQ(prog.segments.size(), 2u);  // approach rapid + helix
  EXPECT_EQ(prog.segments[0].kind, MotionKind::Rapid);
  const Segment& h = prog.segments[1];
  ASSERT_EQ(h.kind, MotionKind::Arc);
  const SegmentGeometry g(h);
  EXPECT_NEAR(g.radius(), 0.5, kGeometryTol);
  EXPECT_NEAR(g.sweep_rad(), 10 * kTwoPi, 1e-9);  // 10 turns
  EXPECT_NEAR(h.end[2], -1.0, kGeometryTol);      // total depth
  const Sampled s = sample(prog);
  EXPECT_NEAR(s.min_r, 0.5, kGeometryTol);
  EXPECT_NEAR(s.max_r, 0.5, kGeometryTol);
  EXPECT_NEAR(s.max_z, 0.0, kGeometryTol);
  EXPECT_NEAR(s.min_z, -1.0, kGeometryTol);
  // Depth per turn = single-layer feed: after 3.5 turns the helix is at −0.35.
  EXPECT_NEAR(g.at(g.length() * 0.35)[2], -0.35, kGeometryTol);
  // The row's A and C ride along.
  EXPECT_EQ(h.start[index(Axis::A)], 30.0);
  EXPECT_EQ(h.end[index(Axis::C)], 45.0);
  EXPECT_NEAR(h.feed_mm_s, 10.0, 1e-12);
}

TEST(HoleProcesses, TaperedHelixStepsTheRadiusPerLayer) {
  HoleProcessParams p = row_hole_processes(HoleProcessId::Helix);
  p.layer_count = 5;
  p.layer_feed_mm = 0.2;
  p.head.start_radius_mm = 0.6;
  p.head.end_radius_mm = 0.4;
  const HoleProgram prog = generate(p);
  int turns = 0;
  for (const Segment& seg : prog.segments) {
    if (seg.kind != MotionKind::Arc) continue;
    const SegmentGeometry g(seg);
    EXPECT_NEAR(g.radius(), 0.6 - 0.05 * turns, kGeometryTol);
    EXPECT_NEAR(g.sweep_rad(), kTwoPi, 1e-9);
    EXPECT_NEAR(seg.start[2] - seg.end[2], 0.2, kGeometryTol);
    ++turns;
  }
  EXPECT_EQ(turns, 5);
  EXPECT_NEAR(prog.segments.back().end[2], -1.0, kGeometryTol);
  EXPECT_NEAR(std::hypot(prog.segments.back().end[0], prog.segments.back().end[1]), 0.4, kGeometryTol);
}

TEST(HoleProcesses, CircleScanCutsRingsPerLayer) {
  HoleProcessParams p = row_hole_processes(HoleProcessId::Circle);
  p.layer_count = 4;
  p.layer_feed_mm = 0.25;
  p.head.start_radius_mm = 0.3;
  p.head.end_radius_mm = 0.5;
  p.head.radius_turns = 3;
  const HoleProgram prog = generate(p);
  int arcs = 0;
  for (const Segment& seg : prog.segments) {
    if (seg.kind != MotionKind::Arc) continue;
    const SegmentGeometry g(seg);
    const int layer = arcs / 3 + 1, ring = arcs % 3;
    EXPECT_NEAR(g.radius(), 0.3 + 0.1 * ring, kGeometryTol);
    EXPECT_NEAR(g.sweep_rad(), kTwoPi, 1e-9);  // one full circle, flat
    EXPECT_EQ(seg.start[2], seg.end[2]);
    EXPECT_NEAR(seg.start[2], -0.25 * layer, kGeometryTol);
    ++arcs;
  }
  EXPECT_EQ(arcs, 12);
  const Sampled s = sample(prog);
  EXPECT_NEAR(s.min_r, 0.3, kGeometryTol);
  EXPECT_NEAR(s.max_r, 0.5, kGeometryTol);
  EXPECT_NEAR(s.min_z, -1.0, kGeometryTol);
}

TEST(HoleProcesses, FreeShapeFollowsThePolarPolygon) {
  HoleProcessParams p = row_hole_processes(HoleProcessId::FreeShape);
  p.layer_count = 3;
  p.layer_feed_mm = 0.1;
  p.total_depth_mm = 0.3;
  p.shape = {{1.0, 0.0}, {0.5, 90.0}, {1.0, 180.0}, {0.5, 270.0}};
  const HoleProgram prog = generate(p);
  // rapid + per layer (1 step down + 4 edges)
  ASSERT_EQ(prog.segments.size(), 1u + 3u * 5u);
  for (std::uint32_t layer = 0; layer < 3; ++layer) {
    const double z = -0.1 * (layer + 1);
    for (int e = 0; e < 4; ++e) {
      const Segment& s = prog.segments[1 + layer * 5 + 1 + e];
      const PolarVertex& v = p.shape[(e + 1) % 4];
      const double ang = v.angle_deg * std::numbers::pi / 180.0;
      EXPECT_NEAR(s.end[0], v.radius_mm * std::cos(ang), kGeometryTol);
      EXPECT_NEAR(s.end[1], v.radius_mm * std::sin(ang), kGeometryTol);
      EXPECT_NEAR(s.end[2], z, kGeometryTol);
    }
  }
  EXPECT_NEAR(prog.segments.back().end[2], -0.3, kGeometryTol);
}

TEST(HoleProcesses, EventsAtTheRightMoments) {
  const HoleProgram prog = generate(row_hole_processes(HoleProcessId::Circle));
  ASSERT_EQ(prog.events.size(), 3u);
  EXPECT_EQ(prog.events[0].kind, HoleEventKind::HeadParameters);
  EXPECT_EQ(prog.events[0].before_segment, 0u);
  EXPECT_EQ(prog.events[0].head.start_radius_mm, 0.5);
  EXPECT_EQ(prog.events[1].kind, HoleEventKind::LaserOn);
  EXPECT_EQ(prog.events[1].before_segment, 1u);
  EXPECT_EQ(prog.events[1].power_pct, 80.0);
  EXPECT_EQ(prog.events[2].kind, HoleEventKind::LaserOff);
  EXPECT_EQ(prog.events[2].before_segment, prog.segments.size());
  EXPECT_EQ(prog.segments[0].laser, LaserMode::Off);
  for (std::size_t i = 1; i < prog.segments.size(); ++i) {
    EXPECT_EQ(prog.segments[i].laser, LaserMode::Constant);
    EXPECT_EQ(prog.segments[i].power_pct, 80.0);
    EXPECT_EQ(prog.segments[i].start, prog.segments[i - 1].end);  // continuous
  }
}

TEST(HoleProcesses, FramePutsTheHoleOnTheToolAxis) {
  const HoleProcessParams p = row_hole_processes(HoleProcessId::Helix);
  const HoleProgram prog = generate(p);
  EXPECT_LT((prog.frame * Vec3::Zero() - Vec3(500.0, 200.0, 100.0)).norm(), 1e-12);
  EXPECT_LT((prog.frame.linear() * Vec3::UnitZ() - tool_axis(30.0, 45.0)).norm(), 1e-12);
  // On a table-table machine the hole axis becomes machine Z: G17 arcs stay G17 arcs.
  FiveAxisGeometry g;
  g.variant = MachineVariant::TableTable;
  const FiveAxisKinematics kin(g);
  const Eigen::Isometry3d to_joints = kin.tip_to_joints({30.0, 45.0}) * prog.frame;
  EXPECT_LT((to_joints.linear() * Vec3::UnitZ() - Vec3::UnitZ()).norm(), 1e-12);
}

void expect_error(const HoleProcessParams& p, const std::string& needle) {
  const Status s = validate(p);
  ASSERT_FALSE(s.ok()) << needle;
  EXPECT_EQ(s.error().code, ErrorCode::GcodeBadValue);
  EXPECT_NE(s.error().message.find(needle), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("hole 7"), std::string::npos) << s.error().message;
  EXPECT_FALSE(generate_hole(p).ok());
}

TEST(HoleProcesses, RejectsBadParameters) {
  HoleProcessParams p = row_hole_processes(HoleProcessId::Helix);
  p.layer_feed_mm = 1.5;
  expect_error(p, "field 8 single-layer feed = 1.5 mm");
  p = row_hole_processes(HoleProcessId::Helix);
  p.total_depth_mm = 1.2;
  expect_error(p, "field 10 total depth = 1.2 mm; must equal layer count");
  p = row_hole_processes(HoleProcessId::Helix);
  p.feed_mm_min = 0.0;
  expect_error(p, "field 7 feed rate = 0");
  p = row_hole_processes(HoleProcessId::Helix);
  p.position[index(Axis::A)] = 100.0;
  expect_error(p, "field 5 A = 100 deg");
  p = row_hole_processes(HoleProcessId::Helix);
  p.position[index(Axis::C)] = 360.0;
  expect_error(p, "field 6 C = 360");
  p = row_hole_processes(HoleProcessId::Helix);
  p.power_pct = 101.0;
  expect_error(p, "field 11 laser power");
  p = row_hole_processes(HoleProcessId::Helix);
  p.layer_count = 0;
  expect_error(p, "field 9 layer count = 0");
  p = row_hole_processes(HoleProcessId::Helix);
  p.head.start_radius_mm = 0.0;
  expect_error(p, "field 12 start radius = 0");
  p = row_hole_processes(HoleProcessId::Circle);
  p.head.end_radius_mm = 0.7;
  expect_error(p, "field 14 radius turns = 1");
  p = row_hole_processes(HoleProcessId::Helix);
  p.process = static_cast<HoleProcessId>(5);
  expect_error(p, "field 18 process id = 5");

  p = row_hole_processes(HoleProcessId::FreeShape);
  p.shape = {{1.0, 0.0}, {1.0, 120.0}};
  expect_error(p, "free shape has 2 vertices");
  p.shape = {{1.0, 0.0}, {1.0, 120.0}, {1.0, 90.0}};
  expect_error(p, "angles must increase");
  p.shape = {{1.0, 0.0}, {1.0, 10.0}, {1.0, 200.0}};
  expect_error(p, "gap of 190");
  p.shape = {{1.0, 0.0}, {-1.0, 120.0}, {1.0, 240.0}};
  expect_error(p, "vertex 2: radius = -1");
}

TEST(HoleProcesses, HolesAreValidAtTheRangeEnds) {
  HoleProcessParams p = row_hole_processes(HoleProcessId::Helix);
  p.hole_number = 10000;
  p.position << 1000.0, 450.0, 500.0, -95.0, 0.0, 359.999;
  p.feed_mm_min = 2000.0;
  p.layer_feed_mm = 1.0;
  p.layer_count = 3;
  p.total_depth_mm = 3.0;
  p.power_pct = 100.0;
  EXPECT_TRUE(validate(p).ok());
  EXPECT_STREQ(process_name(HoleProcessId::FreeShape), "free shape");
}

}  // namespace
}  // namespace lcnc
