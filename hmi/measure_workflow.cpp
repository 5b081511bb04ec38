#include "hmi/measure_workflow.h"

#include <algorithm>
#include <cmath>

#include "drivers/modbus/register_map.h"
#include "kinematics/five_axis.h"

namespace lcnc::hmi {

Result<std::unique_ptr<SerialPointProbe>> SerialPointProbe::open(const std::string& device,
                                                                 std::chrono::milliseconds answer_timeout) {
  Result<drivers::DeviceMap> map = drivers::shipped_device("probe_3d");
  if (!map) return map.error();
  drivers::ProbeClientConfig c;
  c.device = device;
  c.timeout = answer_timeout;
  c.retries = 3;
  auto client = std::make_unique<drivers::ProbeClient>(*map, c);
  if (Status s = client->open(); !s) return s.error();
  return std::unique_ptr<SerialPointProbe>(new SerialPointProbe(std::move(client)));
}

Result<Vec3> SerialPointProbe::measure() {
  Result<drivers::probe::PointReply> r = client_->measure();
  if (!r) return r.error();
  return Vec3(r->x_mm, r->y_mm, r->z_mm);
}

namespace {

// Where the machine stands to probe a face point: the stand-off along the
// face's outward normal, the tool axis along it (the probe looks along −k).
Result<Pose> approach_for(const ProbePoint& p, const Eigen::Isometry3d& frame, double standoff_mm,
                          RotaryJoints& prev) {
  const Vec3 at = frame * Vec3(p.planned_work + standoff_mm * p.normal_work);
  const Vec3 axis = frame.linear() * p.normal_work;
  Result<RotaryJoints> j = choose_rotary(axis, prev, RotaryLimits{});
  if (!j) return make_error(ErrorCode::MeasureDegenerate, p.face + ": " + j.error().message);
  prev = *j;
  Pose out;
  out << at.x(), at.y(), at.z(), j->a_deg, 0.0, wrap_360(j->c_deg);
  return out;
}

// The placement as the points measured so far show it, for planning the
// rest: the three primary points give the top's plane (its normal becomes
// the frame's z, the frame moved onto it); each secondary point moves the
// frame along the front's normal onto it, and the second also turns the
// frame about z so the front runs through both.
Eigen::Isometry3d refined(const Eigen::Isometry3d& frame, const std::vector<ProbePoint>& pts,
                          std::size_t done) {
  Eigen::Isometry3d f = frame;
  if (done == 6) {  // the 3-2-1 fit plans the extra points of a best fit
    Result<FrameFit> fit = fit_321({*pts[0].measured, *pts[1].measured, *pts[2].measured},
                                   {*pts[3].measured, *pts[4].measured}, *pts[5].measured);
    if (fit) f = fit->work_to_machine;
  } else if (done == 3) {
    const Vec3 a = *pts[0].measured, b = *pts[1].measured, c = *pts[2].measured;
    Vec3 n = (b - a).cross(c - a).normalized();
    if (n.dot(f.linear().col(2)) < 0) n = -n;
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(f.linear().col(2), n);
    f.linear() = q.toRotationMatrix() * f.linear();
    const Vec3 centroid = (a + b + c) / 3.0;
    f.translation() += n * n.dot(centroid - f.translation());
  } else if (done == 4 || done == 5) {
    const ProbePoint& p = pts[done - 1];
    const Vec3 n = f.linear() * p.normal_work;
    const Vec3 expected = f * p.planned_work;
    f.translation() += n * n.dot(*p.measured - expected);
    if (done == 5) {
      const Vec3 z = f.linear().col(2);
      Vec3 along = *pts[4].measured - *pts[3].measured;
      along -= z * z.dot(along);
      const Vec3 x = f.linear().col(0);
      const double turn = std::atan2(x.cross(along.normalized()).dot(z), x.dot(along.normalized()));
      const Vec3 pivot = *pts[3].measured;
      f = Eigen::Translation3d(pivot) * Eigen::AngleAxisd(turn, z) * Eigen::Translation3d(-pivot) * f;
    }
  }
  return f;
}

}  // namespace

Result<std::vector<ProbePoint>> plan_321(const MeasurePlan& plan) {
  const double L = plan.block_mm.x(), W = plan.block_mm.y(), H = plan.block_mm.z();
  if (!(L > 0 && W > 0 && H > 0))
    return make_error(ErrorCode::MeasureDegenerate, "the block's length, width and height must be > 0");
  struct Spec {
    const char* face;
    Vec3 p, n;
  };
  const Spec specs[] = {
      {"primary 1", {0.2 * L, 0.25 * W, 0.0}, Vec3::UnitZ()},
      {"primary 2", {0.8 * L, 0.25 * W, 0.0}, Vec3::UnitZ()},
      {"primary 3", {0.5 * L, 0.75 * W, 0.0}, Vec3::UnitZ()},
      {"secondary 1", {0.25 * L, 0.0, -0.5 * H}, -Vec3::UnitY()},
      {"secondary 2", {0.75 * L, 0.0, -0.5 * H}, -Vec3::UnitY()},
      {"tertiary", {0.0, 0.5 * W, -0.5 * H}, -Vec3::UnitX()},
      // best fit: more of each face, at other places and heights
      {"primary 4", {0.5 * L, 0.5 * W, 0.0}, Vec3::UnitZ()},
      {"secondary 3", {0.5 * L, 0.0, -0.25 * H}, -Vec3::UnitY()},
      {"tertiary 2", {0.0, 0.2 * W, -0.75 * H}, -Vec3::UnitX()},
      {"tertiary 3", {0.0, 0.8 * W, -0.25 * H}, -Vec3::UnitX()},
  };
  std::vector<ProbePoint> out;
  RotaryJoints prev{};
  const std::size_t count = plan.best_fit ? std::size(specs) : 6;
  for (std::size_t i = 0; i < count; ++i) {
    const Spec& s = specs[i];
    ProbePoint p;
    p.face = s.face;
    p.planned_work = s.p;
    p.normal_work = s.n;
    Result<Pose> a = approach_for(p, plan.nominal, plan.standoff_mm, prev);
    if (!a) return a.error();
    p.approach = *a;
    out.push_back(p);
  }
  return out;
}

MeasureOutcome run_measurement(const MeasurePlan& plan, MachineMover& mover, PointProbe& probe,
                               const std::function<void(int, int)>& progress,
                               const std::atomic<bool>* cancel) {
  MeasureOutcome o;
  Result<std::vector<ProbePoint>> planned = plan_321(plan);
  if (!planned) {
    o.error = planned.error().message;
    return o;
  }
  o.points = std::move(planned).value();
  // the clearance plane: above the block's highest corner
  double top = -1e300;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? plan.block_mm.x() : 0.0, (c & 2) ? plan.block_mm.y() : 0.0,
                      (c & 4) ? -plan.block_mm.z() : 0.0);
    top = std::max(top, (plan.nominal * corner).z());
  }
  const double safe_z = top + plan.clearance_mm;
  int done = 0;
  Eigen::Isometry3d frame = plan.nominal;
  RotaryJoints prev{};
  for (std::size_t i = 0; i < o.points.size(); ++i) {
    ProbePoint& p = o.points[i];
    // planned again from what the points so far show of the placement
    frame = refined(frame, o.points, i);
    if (Result<Pose> a = approach_for(p, frame, plan.standoff_mm, prev)) p.approach = *a;
    if (cancel != nullptr && cancel->load()) {
      o.error = "cancelled";
      return o;
    }
    Result<Pose> here = mover.position();
    if (!here) {
      p.error = here.error().message;
      o.error = p.face + ": " + p.error;
      return o;
    }
    Pose up = *here;
    up[2] = std::max(up[2], safe_z);
    Pose over = p.approach;
    over[2] = std::max(p.approach[2], safe_z);
    for (const Pose& target : {up, over, p.approach}) {
      if (Status s = mover.move_to(target); !s) {
        p.error = s.error().message;
        o.error = p.face + ": " + p.error;
        return o;
      }
    }
    Result<Vec3> m = probe.measure();
    if (!m) {
      p.error = m.error().message;
      o.error = p.face + ": " + p.error;
      return o;
    }
    p.measured = *m;
    if (progress) progress(++done, static_cast<int>(o.points.size()));
  }
  // away from the part again
  if (Result<Pose> here = mover.position()) {
    Pose up = *here;
    up[2] = std::max(up[2], safe_z);
    up[3] = 0.0;
    if (Status s = mover.move_to(up); !s) o.error = "retract: " + s.error().message;
  }
  const std::array<Vec3, 3> primary{*o.points[0].measured, *o.points[1].measured, *o.points[2].measured};
  const std::array<Vec3, 2> secondary{*o.points[3].measured, *o.points[4].measured};
  Result<FrameFit> fit = fit_321(primary, secondary, *o.points[5].measured);
  if (fit && o.points.size() > 6) {
    std::vector<FacePoint> faces;
    for (const ProbePoint& p : o.points)
      faces.push_back(FacePoint{*p.measured, p.normal_work, p.normal_work.dot(p.planned_work)});
    fit = fit_faces(faces, fit->work_to_machine);
  }
  if (!fit) {
    o.error = fit.error().message;
    return o;
  }
  for (std::size_t i = 0; i < o.points.size() && i < fit->residuals_mm.size(); ++i)
    o.points[i].residual_mm = fit->residuals_mm[i];
  o.fit = *fit;
  return o;
}

Result<std::vector<std::pair<std::uint32_t, Pose>>> placed_holes(const std::vector<HoleRecord>& holes,
                                                                 const Eigen::Isometry3d& t) {
  std::vector<std::pair<std::uint32_t, Pose>> out;
  for (const HoleRecord& h : holes) {
    Result<Pose> p = transform_hole(t, h.params.position);
    if (!p) {
      Diagnostic d = p.error();
      d.message = "hole " + std::to_string(h.params.hole_number) + ": " + d.message;
      return d;
    }
    out.emplace_back(h.params.hole_number, *p);
  }
  return out;
}

}  // namespace lcnc::hmi
