#include "measure/workpiece_frame.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Dense>

#include "kinematics/five_axis.h"

namespace lcnc {
namespace {

// Points closer than this are one point; a cross product shorter than this
// (relative) is a degenerate direction.
constexpr double kMinSpanMm = 1e-3;
constexpr double kMinSine = 1e-6;

Diagnostic degenerate(const std::string& why) { return make_error(ErrorCode::MeasureDegenerate, why); }

std::string mm(const Vec3& p) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.4f, %.4f, %.4f)", p.x(), p.y(), p.z());
  return b;
}

void finish(FrameFit& f) {
  double sum2 = 0.0;
  for (double r : f.residuals_mm) {
    f.max_residual_mm = std::max(f.max_residual_mm, r);
    sum2 += r * r;
  }
  f.rms_residual_mm =
      f.residuals_mm.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(f.residuals_mm.size()));
}

}  // namespace

Result<FrameFit> fit_321(const std::array<Vec3, 3>& p, const std::array<Vec3, 2>& q, const Vec3& r) {
  const Vec3 n_raw = (p[1] - p[0]).cross(p[2] - p[0]);
  const double span = std::max({(p[1] - p[0]).norm(), (p[2] - p[0]).norm(), (p[2] - p[1]).norm()});
  if (span < kMinSpanMm || n_raw.norm() < kMinSine * span * span)
    return degenerate("the three primary points " + mm(p[0]) + ", " + mm(p[1]) + ", " + mm(p[2]) +
                      " are collinear or coincide: they do not define the primary face");
  Vec3 z = n_raw.normalized();
  if (z.z() < 0.0) z = -z;  // the face the probe touched from above
  const Vec3 d = q[1] - q[0];
  if (d.norm() < kMinSpanMm)
    return degenerate("the two secondary points " + mm(q[0]) + " and " + mm(q[1]) + " coincide");
  const Vec3 x_raw = d - d.dot(z) * z;
  if (x_raw.norm() < kMinSine * d.norm())
    return degenerate("the secondary points " + mm(q[0]) + " and " + mm(q[1]) +
                      " lie along the primary face's normal: they do not give the secondary direction");
  const Vec3 x = x_raw.normalized();
  const Vec3 y = z.cross(x);
  // origin: on the primary plane, the secondary plane (through q, normal y)
  // and the tertiary plane (through r, normal x)
  Eigen::Matrix3d a;
  a.row(0) = z.transpose();
  a.row(1) = y.transpose();
  a.row(2) = x.transpose();
  const Vec3 b(z.dot(p[0]), y.dot(q[0]), x.dot(r));
  FrameFit f;
  f.work_to_machine.linear().col(0) = x;
  f.work_to_machine.linear().col(1) = y;
  f.work_to_machine.linear().col(2) = z;
  f.work_to_machine.translation() = a.inverse() * b;
  const Eigen::Isometry3d inv = f.work_to_machine.inverse();
  // each point's distance from its face, in the workpiece frame
  for (const Vec3& v : p) f.residuals_mm.push_back(std::abs((inv * v).z()));
  for (const Vec3& v : q) f.residuals_mm.push_back(std::abs((inv * v).y()));
  f.residuals_mm.push_back(std::abs((inv * r).x()));
  finish(f);
  return f;
}

Result<FrameFit> fit_best(const std::vector<Vec3>& nominal, const std::vector<Vec3>& measured) {
  if (nominal.size() != measured.size())
    return degenerate(std::to_string(nominal.size()) + " nominal points for " +
                      std::to_string(measured.size()) + " measured: each measured point needs its nominal");
  if (nominal.size() < 3)
    return degenerate("a best fit needs at least 3 points, " + std::to_string(nominal.size()) + " given");
  // Kabsch on the 3 × 3 moments (fixed-size algebra: the dynamic-size SVD
  // that Eigen::umeyama instantiates costs minutes to compile under the
  // sanitizers, for the same rotation)
  const double n = static_cast<double>(nominal.size());
  Vec3 cs = Vec3::Zero(), cd = Vec3::Zero();
  for (std::size_t i = 0; i < nominal.size(); ++i) {
    cs += nominal[i] / n;
    cd += measured[i] / n;
  }
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero(), cross = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < nominal.size(); ++i) {
    const Vec3 s = nominal[i] - cs;
    spread += s * s.transpose();
    cross += s * (measured[i] - cd).transpose();
  }
  // the nominal points must span a plane (else the rotation about their
  // line is free): the singular values of the centred points are the roots
  // of the spread's eigenvalues (ascending)
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(spread, Eigen::EigenvaluesOnly);
  const double sv0 = std::sqrt(std::max(0.0, eig.eigenvalues()(2)));
  const double sv1 = std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
  if (sv0 < kMinSpanMm || sv1 < kMinSine * sv0 * 1e3)
    return degenerate(
        "the nominal points are collinear or coincide: a rigid fit needs 3 points not on one line");
  // the rotation R minimising Σ|R s + t − d|²: cross = U Σ Vᵀ, R = V D Uᵀ
  // with D flipping the last axis when that would be a reflection
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) d(2, 2) = -1.0;
  FrameFit f;
  f.work_to_machine.linear() = svd.matrixV() * d * svd.matrixU().transpose();
  f.work_to_machine.translation() = cd - f.work_to_machine.linear() * cs;
  for (std::size_t i = 0; i < nominal.size(); ++i)
    f.residuals_mm.push_back((f.work_to_machine * nominal[i] - measured[i]).norm());
  finish(f);
  return f;
}

Result<FrameFit> fit_faces(const std::vector<FacePoint>& points, const Eigen::Isometry3d& initial) {
  if (points.size() < 6)
    return degenerate("a fit on faces needs at least 6 points, " + std::to_string(points.size()) + " given");
  Eigen::Isometry3d t = initial;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  for (int iter = 0; iter < 20; ++iter) {
    Eigen::Matrix<double, 6, 6> jtj = Eigen::Matrix<double, 6, 6>::Zero();
    Vec6 jtr = Vec6::Zero();
    const Eigen::Isometry3d inv = t.inverse();
    for (const FacePoint& p : points) {
      const Vec3 x = inv * p.measured;  // in the workpiece frame
      const double r = p.normal.dot(x) - p.offset;
      // x' = Δ⁻¹x with Δ = (rotation δθ, translation δt) applied in the
      // workpiece frame: r' ≈ r − δθ·(x × n) − δt·n
      Vec6 j;
      j << -x.cross(p.normal), -p.normal;
      jtj += j * j.transpose();
      jtr += j * r;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(jtj);
    if (eig.eigenvalues()(0) < 1e-9 * std::max(1.0, eig.eigenvalues()(5)))
      return degenerate(
          "the probed faces leave the workpiece free to move: points on three faces that are "
          "not parallel, at least 3 on one and 2 on another, pin it");
    const Vec6 d = jtj.ldlt().solve(-jtr);
    const Vec3 dtheta = d.head<3>();
    Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
    if (dtheta.norm() > 0)
      delta.linear() = Eigen::AngleAxisd(dtheta.norm(), dtheta.normalized()).toRotationMatrix();
    delta.translation() = d.tail<3>();
    t = t * delta;
    if (d.norm() < 1e-12) break;
  }
  FrameFit f;
  f.work_to_machine = t;
  const Eigen::Isometry3d inv = t.inverse();
  for (const FacePoint& p : points)
    f.residuals_mm.push_back(std::abs(p.normal.dot(inv * p.measured) - p.offset));
  finish(f);
  return f;
}

Result<Pose> transform_hole(const Eigen::Isometry3d& t, const Pose& hole) {
  Pose out = hole;
  out.head<3>() = t * Vec3(hole.head<3>());
  const RotaryJoints old{hole[index(Axis::A)], hole[index(Axis::C)]};
  const Vec3 axis = t.linear() * tool_axis(old);
  Result<RotaryJoints> j = choose_rotary(axis, old, RotaryLimits{});
  if (!j) return j.error();
  out[index(Axis::A)] = j->a_deg;
  out[index(Axis::C)] = wrap_360(j->c_deg);
  return out;
}

}  // namespace lcnc
