// Hole-process generators; the geometry is described in hole_processes.h.
#include "holes/hole_processes.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace lcnc {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Builds segments in the hole frame, carrying the row's A and C.
class Builder {
 public:
  explicit Builder(const HoleProcessParams& p) : p_(p) {
    pos_ = Pose::Zero();
    pos_[index(Axis::A)] = p.position[index(Axis::A)];
    pos_[index(Axis::C)] = p.position[index(Axis::C)];
  }

  void rapid_to(const Vec3& q) { add(MotionKind::Rapid, q); }
  void line_to(const Vec3& q) { add(MotionKind::Linear, q); }
  // Counter-clockwise G17 arc (helix when z changes) about the hole axis
  // from the current point to q; turns = full turns when q is above or below
  // the start (1 + extra_turns).
  void arc_to(const Vec3& q, std::uint32_t turns) {
    Segment& s = add(MotionKind::Arc, q);
    s.plane = Plane::XY;
    s.center = Vec3(0.0, 0.0, s.start[2]);
    s.clockwise = false;
    s.extra_turns = turns > 0 ? turns - 1 : 0;
  }

  [[nodiscard]] Vec3 at() const { return pos_.head<3>(); }
  HoleProgram take() { return std::move(prog_); }
  HoleProgram& program() { return prog_; }

 private:
  Segment& add(MotionKind kind, const Vec3& q) {
    Segment s;
    s.kind = kind;
    s.start = pos_;
    pos_.head<3>() = q;
    s.end = pos_;
    if (kind != MotionKind::Rapid) {
      s.feed_mm_s = p_.feed_mm_min / 60.0;
      s.laser = LaserMode::Constant;
      s.power_pct = p_.power_pct;
    }
    s.line = p_.hole_number;  // the DB row stands in for the source line
    prog_.segments.push_back(s);
    return prog_.segments.back();
  }

  const HoleProcessParams& p_;
  Pose pos_;
  HoleProgram prog_;
};

Vec3 polar(double r, double angle_deg, double z) {
  return {r * std::cos(angle_deg * kDeg), r * std::sin(angle_deg * kDeg), z};
}

}  // namespace

const char* process_name(HoleProcessId id) noexcept {
  switch (id) {
    case HoleProcessId::Helix: return "helix";
    case HoleProcessId::Circle: return "circle";
    case HoleProcessId::FreeShape: return "free shape";
  }
  return "unknown";
}

Status validate(const HoleProcessParams& p) {
  const std::string hole = "hole " + std::to_string(p.hole_number) + ": ";
  auto bad = [&](std::string msg) {
    return Status(make_error(ErrorCode::GcodeBadValue, hole + std::move(msg)));
  };
  // One range check: `lo_open` excludes the lower end.
  auto in = [](double v, double lo, double hi, bool lo_open = false) {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi;
  };
  if (p.hole_number < 1 || p.hole_number > kMaxHoleNumber)
    return bad("field 1 hole number = " + std::to_string(p.hole_number) + "; allowed 1 … " +
               std::to_string(kMaxHoleNumber));
  static constexpr struct {
    int field;
    const char* name;
    double lo, hi;
    const char* unit;
  } kPos[] = {{2, "X", 0.0, 1000.0, "mm"}, {3, "Y", 0.0, 450.0, "mm"}, {4, "Z", 0.0, 500.0, "mm"},
              {5, "A", -95.0, 95.0, "deg"}, {6, "C", 0.0, 359.999, "deg"}};
  static constexpr Axis kPosAxes[] = {Axis::X, Axis::Y, Axis::Z, Axis::A, Axis::C};
  for (int i = 0; i < 5; ++i) {
    const double v = p.position[index(kPosAxes[i])];
    if (!in(v, kPos[i].lo, kPos[i].hi))
      return bad("field " + std::to_string(kPos[i].field) + " " + kPos[i].name + " = " + fmt(v) +
                 " " + kPos[i].unit + "; allowed " + fmt(kPos[i].lo) + " … " + fmt(kPos[i].hi) +
                 " " + kPos[i].unit);
  }
  if (!in(p.feed_mm_min, 0.0, kMaxHoleFeedMmMin, true))
    return bad("field 7 feed rate = " + fmt(p.feed_mm_min) + " mm/min; allowed > 0 … " +
               fmt(kMaxHoleFeedMmMin) + " mm/min (a hole needs a feed)");
  if (!in(p.layer_feed_mm, 0.0, kMaxLayerFeedMm, true))
    return bad("field 8 single-layer feed = " + fmt(p.layer_feed_mm) + " mm; allowed > 0 … " +
               fmt(kMaxLayerFeedMm) + " mm");
  if (p.layer_count < 1 || p.layer_count > kMaxLayerCount)
    return bad("field 9 layer count = " + std::to_string(p.layer_count) + "; allowed 1 … " +
               std::to_string(kMaxLayerCount));
  const double depth = p.layer_count * p.layer_feed_mm;
  if (!(std::isfinite(p.total_depth_mm) && std::abs(p.total_depth_mm - depth) <= kDepthTolerance))
    return bad("field 10 total depth = " + fmt(p.total_depth_mm) +
               " mm; must equal layer count × single-layer feed = " +
               std::to_string(p.layer_count) + " × " + fmt(p.layer_feed_mm) + " = " + fmt(depth) +
               " mm (within " + fmt(kDepthTolerance) + " mm)");
  if (!in(p.power_pct, 0.0, 100.0))
    return bad("field 11 laser power = " + fmt(p.power_pct) + " %; allowed 0 … 100 %");
  const ScanHeadParams& h = p.head;
  if (p.process != HoleProcessId::FreeShape) {
    if (!in(h.start_radius_mm, 0.0, kMaxScanRadiusMm, true))
      return bad("field 12 start radius = " + fmt(h.start_radius_mm) + " mm; allowed > 0 … " +
                 fmt(kMaxScanRadiusMm) + " mm");
    if (!in(h.end_radius_mm, 0.0, kMaxScanRadiusMm, true))
      return bad("field 13 end radius = " + fmt(h.end_radius_mm) + " mm; allowed > 0 … " +
                 fmt(kMaxScanRadiusMm) + " mm");
  }
  if (h.radius_turns < 1 || h.radius_turns > kMaxRadiusTurns)
    return bad("field 14 radius turns = " + std::to_string(h.radius_turns) + "; allowed 1 … " +
               std::to_string(kMaxRadiusTurns));
  if (p.process == HoleProcessId::Circle && h.radius_turns == 1 &&
      h.end_radius_mm != h.start_radius_mm)
    return bad("field 14 radius turns = 1 with start radius " + fmt(h.start_radius_mm) +
               " mm ≠ end radius " + fmt(h.end_radius_mm) +
               " mm; a circle scan from one radius to another needs 2 or more turns");
  if (!in(h.scan_speed_mm_s, 0.0, 1e5))
    return bad("field 15 scan speed = " + fmt(h.scan_speed_mm_s) + " mm/s; allowed 0 … 100000");
  if (!in(h.wedge_speed_rpm, 0.0, 1e5))
    return bad("field 16 wedge speed = " + fmt(h.wedge_speed_rpm) + " rpm; allowed 0 … 100000");
  if (!in(h.beam_offset_mm, -kMaxScanRadiusMm, kMaxScanRadiusMm))
    return bad("field 17 beam offset = " + fmt(h.beam_offset_mm) + " mm; allowed " +
               fmt(-kMaxScanRadiusMm) + " … " + fmt(kMaxScanRadiusMm) + " mm");
  if (p.process != HoleProcessId::Helix && p.process != HoleProcessId::Circle &&
      p.process != HoleProcessId::FreeShape)
    return bad("field 18 process id = " + std::to_string(static_cast<int>(p.process)) +
               "; allowed 0 helix, 1 circle, 2 free shape");
  if (p.process == HoleProcessId::FreeShape) {
    const std::size_t n = p.shape.size();
    if (n < 3 || n > kMaxShapeVertices)
      return bad("free shape has " + std::to_string(n) + " vertices; allowed 3 … " +
                 std::to_string(kMaxShapeVertices));
    for (std::size_t i = 0; i < n; ++i) {
      const PolarVertex& v = p.shape[i];
      const std::string at = "free shape vertex " + std::to_string(i + 1) + ": ";
      if (!in(v.radius_mm, 0.0, kMaxScanRadiusMm, true))
        return bad(at + "radius = " + fmt(v.radius_mm) + " mm; allowed > 0 … " +
                   fmt(kMaxScanRadiusMm) + " mm");
      if (!(std::isfinite(v.angle_deg) && v.angle_deg >= 0.0 && v.angle_deg < 360.0))
        return bad(at + "angle = " + fmt(v.angle_deg) + "°; allowed 0 … <360°");
      const double next = i + 1 < n ? p.shape[i + 1].angle_deg : p.shape[0].angle_deg + 360.0;
      if (i + 1 < n && !(next > v.angle_deg))
        return bad(at + "angle " + fmt(v.angle_deg) + "° then " + fmt(next) +
                   "°; angles must increase (counter-clockwise order)");
      if (next - v.angle_deg >= 180.0)
        return bad(at + "gap of " + fmt(next - v.angle_deg) +
                   "° to the next vertex; allowed < 180° (the centre must lie inside)");
    }
  }
  return {};
}

Eigen::Isometry3d hole_frame(const HoleProcessParams& p) {
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.translation() = p.position.head<3>();
  f.linear() = (Eigen::AngleAxisd(p.position[index(Axis::C)] * kDeg, Vec3::UnitZ()) *
                Eigen::AngleAxisd(p.position[index(Axis::A)] * kDeg, Vec3::UnitX()))
                   .toRotationMatrix();
  return f;
}

Result<HoleProgram> generate_hole(const HoleProcessParams& p) {
  if (Status s = validate(p); !s) return s.error();
  Builder b(p);
  const ScanHeadParams& h = p.head;
  const std::uint32_t layers = p.layer_count;
  const double f = p.layer_feed_mm;
  const double depth = p.total_depth_mm;
  // Depth of layer k (1-based); the last is the programmed total depth exactly.
  auto z_of = [&](std::uint32_t k) { return k == layers ? -depth : -(k * f); };
  // Radius k of n (0-based) from start to end in equal steps.
  auto ring = [&](std::uint32_t k, std::uint32_t n) {
    return n < 2 ? h.start_radius_mm
                 : h.start_radius_mm + (h.end_radius_mm - h.start_radius_mm) * k / (n - 1);
  };

  switch (p.process) {
    case HoleProcessId::Helix:
      b.rapid_to({h.start_radius_mm, 0.0, 0.0});
      if (h.start_radius_mm == h.end_radius_mm) {
        b.arc_to({h.start_radius_mm, 0.0, -depth}, layers);
      } else {
        for (std::uint32_t k = 1; k <= layers; ++k) {
          const double r = ring(k - 1, layers);
          if (b.at().x() != r) b.line_to({r, 0.0, b.at().z()});
          b.arc_to({r, 0.0, z_of(k)}, 1);
        }
      }
      break;
    case HoleProcessId::Circle:
      b.rapid_to({ring(0, h.radius_turns), 0.0, 0.0});
      for (std::uint32_t k = 1; k <= layers; ++k) {
        b.line_to({ring(0, h.radius_turns), 0.0, z_of(k)});
        for (std::uint32_t j = 0; j < h.radius_turns; ++j) {
          const Vec3 q(ring(j, h.radius_turns), 0.0, z_of(k));
          if (j > 0) b.line_to(q);
          b.arc_to(q, 1);
        }
      }
      break;
    case HoleProcessId::FreeShape: {
      const PolarVertex& v0 = p.shape.front();
      b.rapid_to(polar(v0.radius_mm, v0.angle_deg, 0.0));
      for (std::uint32_t k = 1; k <= layers; ++k) {
        const double z = z_of(k);
        b.line_to(polar(v0.radius_mm, v0.angle_deg, z));
        for (std::size_t i = 1; i < p.shape.size(); ++i)
          b.line_to(polar(p.shape[i].radius_mm, p.shape[i].angle_deg, z));
        b.line_to(polar(v0.radius_mm, v0.angle_deg, z));
      }
      break;
    }
  }

  HoleProgram& prog = b.program();
  prog.frame = hole_frame(p);
  HoleEvent head;
  head.kind = HoleEventKind::HeadParameters;
  head.before_segment = 0;
  head.head = h;
  HoleEvent on;
  on.kind = HoleEventKind::LaserOn;
  on.before_segment = 1;  // after the approach rapid
  on.power_pct = p.power_pct;
  HoleEvent off;
  off.kind = HoleEventKind::LaserOff;
  off.before_segment = prog.segments.size();
  prog.events = {head, on, off};
  return b.take();
}

}  // namespace lcnc
