#include "plan/path_blender.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/plan/test_machine.h"
#include "kinematics/five_axis.h"

namespace lcnc {
namespace {

Segment g1_xyz(const Vec3& a, const Vec3& b, double p, double q) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.start.head<3>() = a;
  s.end.head<3>() = b;
  s.feed_mm_s = 100.0;
  s.path_mode = PathMode::Blend;
  s.blend_tolerance_mm = p;
  s.naive_cam_tolerance_mm = q;
  return s;
}

std::vector<IndexedSegment> blend(const std::vector<Segment>& segs,
                                  const MachineConfig& m = testing::test_machine()) {
  std::size_t i = 0;
  PathBlender b(m, [&](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  });
  std::vector<IndexedSegment> out;
  const IndexedSegment* s = nullptr;
  while (b.next(s) == SourceStatus::Item) out.push_back(*s);
  return out;
}

// A noisy straight run: points within ±noise of the X axis.
std::vector<Segment> noisy_run(int n, double noise, double p, double q) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-noise, noise);
  std::vector<Segment> segs;
  Vec3 at(10, 10, 5);
  for (int k = 1; k <= n; ++k) {
    const Vec3 to(10 + 0.5 * k, 10 + (k == n ? 0.0 : u(rng)), 5);
    segs.push_back(g1_xyz(at, to, p, q));
    at = to;
  }
  return segs;
}

TEST(PathBlender, NaiveCamMergesNearCollinearLines) {
  // noise 0.002 mm < q = min(Q, P)/2 = 0.005: runs of up to 16 lines merge
  const auto out = blend(noisy_run(64, 0.002, 0.01, 0.01));
  EXPECT_LE(out.size(), 2u * (64 / 15 + 1));
  EXPECT_GE(out.size(), 64u / 16);
  // the merged path still ends where the program ends
  EXPECT_NEAR(out.back().seg.end[0], 10 + 32.0, 1e-12);
  // a merged line carries the index of the last program line it covers
  EXPECT_EQ(out.back().index, 63u);
}

TEST(PathBlender, QZeroKeepsEveryLine) {
  const auto out = blend(noisy_run(64, 0.002, 0.01, 0.0));
  // every line kept (each corner blended: a line and an arc per corner)
  EXPECT_GE(out.size(), 64u);
}

TEST(PathBlender, NoiseBeyondQIsNotMerged) {
  const auto merged = blend(noisy_run(64, 0.002, 0.01, 0.01));
  const auto kept = blend(noisy_run(64, 0.05, 0.01, 0.01));  // 0.05 mm ≫ q
  EXPECT_GT(kept.size(), 2 * merged.size());
}

TEST(PathBlender, RotaryMotionIsNeverMerged) {
  auto segs = noisy_run(32, 0.001, 0.01, 0.01);
  for (std::size_t k = 0; k < segs.size(); ++k) {
    segs[k].start[5] = static_cast<double>(k);
    segs[k].end[5] = static_cast<double>(k + 1);
  }
  const auto out = blend(segs);
  // every program line still has its own pieces (index), none merged away
  std::vector<bool> seen(segs.size(), false);
  for (const auto& s : out) seen[s.index] = true;
  for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_TRUE(seen[k]) << k;
}

// What the blender hands out carries its geometry — for a blend arc the one
// it was built with, which is SegmentGeometry(arc) up to rounding — and
// marks the joins that are tangent by construction.
TEST(PathBlender, BlendArcsCarryTheirGeometryAndTangentJoins) {
  const std::vector<Segment> segs = {g1_xyz({10, 10, 5}, {20, 10, 6}, 0.05, 0.0),
                                     g1_xyz({20, 10, 6}, {22, 19, 4}, 0.05, 0.0),
                                     g1_xyz({22, 19, 4}, {22.5, 19.2, 4}, 0.05, 0.0)};
  const auto out = blend(segs);
  ASSERT_EQ(out.size(), 5u);  // line, arc, line, arc, line
  for (std::size_t k = 0; k < out.size(); ++k) {
    const SegmentGeometry want(out[k].seg);
    const SegmentGeometry& got = out[k].geo;
    EXPECT_EQ(got.is_arc(), k % 2 == 1) << k;
    EXPECT_NEAR(got.length(), want.length(), 1e-12) << k;
    EXPECT_NEAR(got.sweep_rad(), want.sweep_rad(), 1e-12) << k;
    for (int j = 0; j <= 8; ++j) {
      const double f = j / 8.0;
      EXPECT_LT((got.at(f * got.length()) - want.at(f * want.length())).norm(), 1e-12) << k << " " << f;
    }
    EXPECT_LT((got.start_tangent() - want.start_tangent()).norm(), 1e-12) << k;
    EXPECT_LT((got.end_tangent() - want.end_tangent()).norm(), 1e-12) << k;
    // each arc and the line after it start along what comes before them
    EXPECT_EQ(out[k].tangent_in, k > 0) << k;
    if (k > 0) {
      EXPECT_LT((got.start_tangent() - out[k - 1].geo.end_tangent()).norm(), 1e-12) << k;
    }
  }
}

TEST(PathBlender, JoinsWithRotaryAxesMovingAreNotMarkedTangent) {
  // X Y Z stay tangent, but the rotary axis's rate per mm jumps at the
  // blend's ends: the look-ahead must look at those joins
  std::vector<Segment> segs = {g1_xyz({10, 10, 5}, {20, 10, 5}, 0.05, 0.0),
                               g1_xyz({20, 10, 5}, {20, 20, 5}, 0.05, 0.0)};
  segs[0].end[5] = 30.0;
  segs[1].start[5] = 30.0;
  segs[1].end[5] = 40.0;
  const auto out = blend(segs);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_TRUE(out[1].seg.kind == MotionKind::Arc);
  for (const auto& s : out) EXPECT_FALSE(s.tangent_in);
}

// Under tool-centre-point control the rotary axes turn the tip: a blend that
// runs them linearly across a corner where their rate per mm jumps moves the
// tip by the lever × trim × jump / 2. The trim is held so that this and the
// X Y Z arc together keep P (a blend with the full trim took the tip 21 µm
// past a 10 µm P).
TEST(PathBlender, UnderToolCentrePointControlTheRotaryRateJumpBoundsTheTrim) {
  std::vector<Segment> segs = {g1_xyz({10, 10, 5}, {20, 10, 5}, 0.05, 0.0),
                               g1_xyz({20, 10, 5}, {20, 20, 5}, 0.05, 0.0)};
  segs[0].end[5] = 30.0;  // C: 3 deg/mm, then 1 deg/mm
  segs[1].start[5] = 30.0;
  segs[1].end[5] = 40.0;
  MachineConfig m = testing::test_machine();
  const double plain_trim = 20.0 - blend(segs, m)[0].seg.end[0];
  m.tcp.enabled = true;
  const auto out = blend(segs, m);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_EQ(out[1].seg.kind, MotionKind::Arc);
  const double trim = 20.0 - out[0].seg.end[0];
  const double jump = 3.0 - 1.0;  // deg/mm of C
  const double tip_per_deg = tip_lever_mm(m.kinematics) * std::numbers::pi / 180.0;
  EXPECT_GT(trim, 0.0);
  EXPECT_LT(trim, plain_trim);
  // the rotary share: at most half of P
  EXPECT_LE(tip_per_deg * trim * jump / 2.0, 0.05 / 2.0 + 1e-12);
  // the rotary axes at the blend's middle, off the lines' by trim·jump/2
  const Pose mid = 0.5 * (out[1].seg.start + out[1].seg.end);
  const double c_on_lines = 30.0;  // at the corner
  EXPECT_NEAR(std::abs(mid[5] - c_on_lines), trim * jump / 2.0, 1e-9);
}

}  // namespace
}  // namespace lcnc
