// Locating the workpiece on the machine from probed points (docs/design.md §7,
// Shao (2022) §4 "six-point positioning"): the rigid transform T from the
// workpiece's own (drawing) frame to machine coordinates, machine = T·work.
//
// 3-2-1. The drawing's three datum faces are the planes z = 0 (primary),
// y = 0 (secondary) and x = 0 (tertiary) of the workpiece frame. The probe
// touches the primary face at three points, the secondary at two and the
// tertiary at one (machine coordinates). Then
//   ẑ' = unit normal of the plane through the three primary points,
//        oriented like the machine's +Z side the planned points are on;
//   x̂' = the two secondary points' direction projected into that plane;
//   ŷ' = ẑ' × x̂';  T's rotation R = [x̂' ŷ' ẑ'];
//   the origin o solves  ẑ'·(p − o) = 0 on the primary face,
//   ŷ'·(q − o) = 0 on the secondary, x̂'·(r − o) = 0 on the tertiary.
// The secondary points' offset from the secondary face's plane is along ŷ';
// that is why the secondary line needs only two points.
//
// Best fit. With N ≥ 3 points whose drawing coordinates are known (not on
// faces: targets, bores), T is the least-squares rigid fit (Kabsch/Umeyama,
// no scaling) of the measured to the nominal points.
//
// Both report residuals: for 3-2-1 each point's distance from its face after
// the fit (the three primary points always fit exactly, so their residual
// is the spread of the others only through a warped face); for the best fit
// each point's distance from its transformed nominal. Degenerate sets
// (collinear primary points, a secondary direction along the normal,
// coincident points, fewer than 3 non-collinear points for the best fit)
// are errors that say which points and why.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "common/result.h"
#include "geom/pose.h"

namespace lcnc {

struct FrameFit {
  Eigen::Isometry3d work_to_machine = Eigen::Isometry3d::Identity();
  std::vector<double> residuals_mm;  // per point, in the order given
  double max_residual_mm = 0.0;
  double rms_residual_mm = 0.0;
};

// The six points: primary[3], secondary[2], tertiary, machine coordinates.
[[nodiscard]] Result<FrameFit> fit_321(const std::array<Vec3, 3>& primary,
                                       const std::array<Vec3, 2>& secondary, const Vec3& tertiary);

// nominal[i] (workpiece frame) measured at measured[i] (machine), N ≥ 3.
[[nodiscard]] Result<FrameFit> fit_best(const std::vector<Vec3>& nominal, const std::vector<Vec3>& measured);

// A point probed on a face of the drawing: the face is the plane
// normal·x = offset of the workpiece frame (normal a unit vector).
struct FacePoint {
  Vec3 measured = Vec3::Zero();  // machine
  Vec3 normal = Vec3::UnitZ();   // workpiece frame
  double offset = 0.0;           // mm
};

// Best fit on faces: the T minimising Σ (normal·(T⁻¹·measured) − offset)²
// over any number (≥ 6) of points on planes that pin all six degrees of
// freedom (Gauss–Newton from `initial`, e.g. the 3-2-1 fit; with exactly the
// six 3-2-1 points it is that fit). Residuals: each point's distance from
// its face. Degenerate when the faces leave a motion free (e.g. all points
// on two faces): the error says so.
[[nodiscard]] Result<FrameFit> fit_faces(const std::vector<FacePoint>& points,
                                         const Eigen::Isometry3d& initial);

// A hole of the process database moved by the fit: its centre and its axis
// (tool_axis(A, C)) through T; A and C the solution of the new axis nearest
// the old joints within the A range. Error GcodeBeyondTravel when no A
// within ±95° reaches the axis.
[[nodiscard]] Result<Pose> transform_hole(const Eigen::Isometry3d& work_to_machine, const Pose& hole);

}  // namespace lcnc
