// Locating the workpiece: the 3-2-1 and the best-fit solvers recover a known
// placement from synthetic probe points — exactly without noise, within the
// noise with it — and reject point sets that do not determine a frame.
#include "measure/workpiece_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kinematics/five_axis.h"

namespace lcnc {
namespace {

// A workpiece placed 1.5° off square, a little tilted, at (312, 148, 25).
Eigen::Isometry3d placement() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(1.5 * M_PI / 180.0, Vec3::UnitZ()) *
                Eigen::AngleAxisd(0.2 * M_PI / 180.0, Vec3::UnitX()) *
                Eigen::AngleAxisd(-0.1 * M_PI / 180.0, Vec3::UnitY()))
                   .toRotationMatrix();
  t.translation() = Vec3(312.0, 148.0, 25.0);
  return t;
}

double rotation_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

// Planned 3-2-1 points on the datum faces (workpiece frame), measured with
// noise of sigma (mm) along each face's normal — what a touch probe sees.
struct Six {
  std::array<Vec3, 3> p;
  std::array<Vec3, 2> q;
  Vec3 r;
};
Six probe(const Eigen::Isometry3d& t, double sigma, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const auto on = [&](const Vec3& w, const Vec3& normal) { return t * (w + noise(rng) * normal); };
  Six s;
  s.p = {on({20, 20, 0}, Vec3::UnitZ()), on({180, 25, 0}, Vec3::UnitZ()), on({100, 110, 0}, Vec3::UnitZ())};
  s.q = {on({30, 0, -5}, Vec3::UnitY()), on({170, 0, -5}, Vec3::UnitY())};
  s.r = on({0, 60, -5}, Vec3::UnitX());
  return s;
}

TEST(WorkpieceFrame, ThreeTwoOneRecoversThePlacementExactly) {
  const Eigen::Isometry3d t = placement();
  const Six s = probe(t, 0.0, 1);
  Result<FrameFit> f = fit_321(s.p, s.q, s.r);
  ASSERT_TRUE(static_cast<bool>(f)) << f.error().to_string();
  EXPECT_LT(rotation_error_deg(f->work_to_machine, t), 1e-9);
  EXPECT_LT((f->work_to_machine.translation() - t.translation()).norm(), 1e-9);
  ASSERT_EQ(f->residuals_mm.size(), 6u);
  EXPECT_LT(f->max_residual_mm, 1e-9);
}

TEST(WorkpieceFrame, ThreeTwoOneWithNoiseStaysWithinTheNoise) {
  const Eigen::Isometry3d t = placement();
  constexpr double kSigma = 0.002;  // 2 µm, a touch probe's repeatability
  for (std::uint32_t seed = 1; seed <= 50; ++seed) {
    const Six s = probe(t, kSigma, seed);
    Result<FrameFit> f = fit_321(s.p, s.q, s.r);
    ASSERT_TRUE(static_cast<bool>(f));
    // a hole 150 mm from the origin lands within ~5σ·(150 / base) of where it is
    const Vec3 hole(150, 80, 0);
    EXPECT_LT((f->work_to_machine * hole - t * hole).norm(), 0.02) << seed;
    EXPECT_LT(rotation_error_deg(f->work_to_machine, t), 0.01) << seed;
  }
}

TEST(WorkpieceFrame, BestFitOfManyPointsRecoversThePlacementWithinTheNoise) {
  const Eigen::Isometry3d t = placement();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 200.0);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<Vec3> nominal, measured;
  for (int i = 0; i < 12; ++i) {
    const Vec3 w(u(rng), u(rng) * 0.6, u(rng) * 0.1);
    nominal.push_back(w);
    measured.push_back(t * w + Vec3(noise(rng), noise(rng), noise(rng)));
  }
  Result<FrameFit> f = fit_best(nominal, measured);
  ASSERT_TRUE(static_cast<bool>(f)) << f.error().to_string();
  EXPECT_LT((f->work_to_machine.translation() - t.translation()).norm(), 0.01);
  EXPECT_LT(rotation_error_deg(f->work_to_machine, t), 0.005);
  EXPECT_EQ(f->residuals_mm.size(), 12u);
  EXPECT_LT(f->rms_residual_mm, 0.006);  // ≈ σ·√3
  EXPECT_GT(f->rms_residual_mm, 0.0005);
  // exact points fit exactly
  for (std::size_t i = 0; i < nominal.size(); ++i) measured[i] = t * nominal[i];
  f = fit_best(nominal, measured);
  ASSERT_TRUE(static_cast<bool>(f));
  EXPECT_LT(f->max_residual_mm, 1e-9);
  // points on one face (a plane): the fit is still a rotation, never the
  // mirror image that fits a plane as well
  for (int round = 0; round < 20; ++round) {
    for (std::size_t i = 0; i < nominal.size(); ++i) {
      nominal[i].z() = 0.0;
      measured[i] =
          t * nominal[i] + (round % 2 == 0 ? Vec3(noise(rng), noise(rng), noise(rng)) : Vec3::Zero());
    }
    f = fit_best(nominal, measured);
    ASSERT_TRUE(static_cast<bool>(f));
    EXPECT_NEAR(f->work_to_machine.linear().determinant(), 1.0, 1e-12) << round;
    EXPECT_LT(rotation_error_deg(f->work_to_machine, t), 0.01) << round;
  }
}

// Best fit on faces: more points than six, each only known to lie on its
// face. From a rough start it finds the placement exactly without noise,
// and with noise places a hole better than the 3-2-1 of the same probe.
std::vector<FacePoint> face_points(const Eigen::Isometry3d& t, double sigma, std::uint32_t seed, bool many) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<FacePoint> out;
  const auto on = [&](const Vec3& w, const Vec3& n) {
    out.push_back(FacePoint{t * (w + noise(rng) * n), n, n.dot(w)});
  };
  // the 3-2-1 points first, then the extra ones
  on({20, 20, 0}, Vec3::UnitZ()), on({180, 25, 0}, Vec3::UnitZ()), on({100, 110, 0}, Vec3::UnitZ());
  on({30, 0, -5}, -Vec3::UnitY()), on({170, 0, -5}, -Vec3::UnitY());
  on({0, 60, -5}, -Vec3::UnitX());
  if (many) {
    on({30, 100, 0}, Vec3::UnitZ()), on({170, 100, 0}, Vec3::UnitZ()), on({100, 60, 0}, Vec3::UnitZ());
    on({100, 0, -15}, -Vec3::UnitY()), on({60, 0, -10}, -Vec3::UnitY());
    on({0, 20, -10}, -Vec3::UnitX()), on({0, 100, -10}, -Vec3::UnitX());
  }
  return out;
}

TEST(WorkpieceFrame, FitOnFacesRecoversThePlacementAndBeatsThreeTwoOneWithMorePoints) {
  const Eigen::Isometry3d t = placement();
  const Eigen::Isometry3d rough = Eigen::Translation3d(310, 150, 25) * Eigen::Isometry3d::Identity();
  Result<FrameFit> exact = fit_faces(face_points(t, 0.0, 1, true), rough);
  ASSERT_TRUE(static_cast<bool>(exact)) << exact.error().to_string();
  EXPECT_LT(rotation_error_deg(exact->work_to_machine, t), 1e-9);
  EXPECT_LT((exact->work_to_machine.translation() - t.translation()).norm(), 1e-9);
  EXPECT_EQ(exact->residuals_mm.size(), 13u);
  EXPECT_LT(exact->max_residual_mm, 1e-9);
  // the six 3-2-1 points alone: the 3-2-1 fit itself
  const std::vector<FacePoint> six = face_points(t, 0.002, 3, false);
  Result<FrameFit> f6 = fit_faces(six, rough);
  Result<FrameFit> f321 = fit_321({six[0].measured, six[1].measured, six[2].measured},
                                  {six[3].measured, six[4].measured}, six[5].measured);
  ASSERT_TRUE(f6 && f321);
  EXPECT_LT((f6->work_to_machine.matrix() - f321->work_to_machine.matrix()).norm(), 1e-6);
  // with noise: the hole's error, 13 points against the 3-2-1 of their first six
  const Vec3 hole(150, 80, 0);
  double e13 = 0, e6 = 0;
  for (std::uint32_t seed = 1; seed <= 50; ++seed) {
    const std::vector<FacePoint> pts = face_points(t, 0.002, seed, true);
    Result<FrameFit> many = fit_faces(pts, rough);
    Result<FrameFit> base = fit_321({pts[0].measured, pts[1].measured, pts[2].measured},
                                    {pts[3].measured, pts[4].measured}, pts[5].measured);
    ASSERT_TRUE(many && base);
    e13 += (many->work_to_machine * hole - t * hole).norm();
    e6 += (base->work_to_machine * hole - t * hole).norm();
  }
  EXPECT_LT(e13, 0.8 * e6) << "mean error 13 points " << e13 / 50 << " mm, 3-2-1 " << e6 / 50 << " mm";
  // points on two faces only: the block could slide along both
  std::vector<FacePoint> two = face_points(t, 0.0, 1, true);
  two.erase(std::remove_if(two.begin(), two.end(), [](const FacePoint& p) { return p.normal.x() != 0.0; }),
            two.end());
  Result<FrameFit> bad = fit_faces(two, rough);
  ASSERT_FALSE(static_cast<bool>(bad));
  EXPECT_EQ(bad.error().code, ErrorCode::MeasureDegenerate);
  EXPECT_NE(bad.error().message.find("free to move"), std::string::npos) << bad.error().message;
}

TEST(WorkpieceFrame, DegenerateSetsAreRejectedSayingWhy) {
  const Vec3 a(0, 0, 0), b(100, 0, 0), c(200, 0, 0);
  Result<FrameFit> f = fit_321({a, b, c}, {Vec3(0, -1, 0), Vec3(50, -1, 0)}, Vec3(-1, 0, 0));
  ASSERT_FALSE(static_cast<bool>(f));
  EXPECT_EQ(f.error().code, ErrorCode::MeasureDegenerate);
  EXPECT_NE(f.error().message.find("collinear"), std::string::npos);
  f = fit_321({a, b, Vec3(0, 100, 0)}, {Vec3(0, -1, 0), Vec3(0, -1, 30)}, Vec3(-1, 0, 0));
  ASSERT_FALSE(static_cast<bool>(f));
  EXPECT_NE(f.error().message.find("along the primary face's normal"), std::string::npos);
  f = fit_321({a, b, Vec3(0, 100, 0)}, {Vec3(5, -1, 0), Vec3(5, -1, 0)}, Vec3(-1, 0, 0));
  ASSERT_FALSE(static_cast<bool>(f));
  EXPECT_NE(f.error().message.find("coincide"), std::string::npos);
  f = fit_best({a, b, c}, {a, b, c});
  ASSERT_FALSE(static_cast<bool>(f));
  EXPECT_NE(f.error().message.find("collinear"), std::string::npos);
  EXPECT_FALSE(static_cast<bool>(fit_best({a, b}, {a, b})));
  EXPECT_FALSE(static_cast<bool>(fit_best({a, b, Vec3(0, 1, 0)}, {a, b})));
}

TEST(WorkpieceFrame, HolesMoveWithTheWorkpieceAndKeepTheirAxis) {
  const Eigen::Isometry3d t = placement();
  Pose hole = Pose::Zero();
  hole << 100, 50, 0, -20, 0, 90;  // tilted hole
  Result<Pose> moved = transform_hole(t, hole);
  ASSERT_TRUE(static_cast<bool>(moved)) << moved.error().to_string();
  EXPECT_LT(((*moved).head<3>() - t * Vec3(100, 50, 0)).norm(), 1e-9);
  const Vec3 want = t.linear() * tool_axis(-20, 90);
  EXPECT_LT((tool_axis((*moved)[3], (*moved)[5]) - want).norm(), 1e-9);
  EXPECT_NEAR((*moved)[3], -20.0, 1.0);  // the same branch, turned a little
  EXPECT_GE((*moved)[5], 0.0);
  EXPECT_LT((*moved)[5], 360.0);
}

}  // namespace
}  // namespace lcnc
