// Hole-process generators; the geometry is described in hole_processes.h.
#include "holes/hole_processes.h"

#include "common/number_text.h"
#include "holes/hole_fields.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace lcnc {

namespace {

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
  return {r * std::cos(angle_deg * kRadPerDeg), r * std::sin(angle_deg * kRadPerDeg), z};
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
  // Each field alone, in field order (hole_fields.h); a free shape does not
  // use the scan radii of fields 12–13.
  for (const HoleField& f : kHoleFields) {
    if (f.scan_radius && p.process == HoleProcessId::FreeShape) continue;
    const double v = f.get(p);
    if (!hole_field_in_range(f, v)) return bad(hole_field_range_message(f, v));
  }
  // Then what the fields must satisfy together.
  const double depth = p.layer_count * p.layer_feed_mm;
  if (!(std::abs(p.total_depth_mm - depth) <= kDepthTolerance))
    return bad("field 10 total depth = " + six_digits(p.total_depth_mm) +
               " mm; must equal layer count × single-layer feed = " + std::to_string(p.layer_count) + " × " +
               six_digits(p.layer_feed_mm) + " = " + six_digits(depth) + " mm (within " +
               six_digits(kDepthTolerance) + " mm)");
  const ScanHeadParams& h = p.head;
  if (p.process == HoleProcessId::Circle && h.radius_turns == 1 && h.end_radius_mm != h.start_radius_mm)
    return bad("field 14 radius turns = 1 with start radius " + six_digits(h.start_radius_mm) +
               " mm ≠ end radius " + six_digits(h.end_radius_mm) +
               " mm; a circle scan from one radius to another needs 2 or more turns");
  if (p.process == HoleProcessId::FreeShape) {
    const std::size_t n = p.shape.size();
    if (n < 3 || n > kMaxShapeVertices)
      return bad("free shape has " + std::to_string(n) + " vertices; allowed 3 … " +
                 std::to_string(kMaxShapeVertices));
    for (std::size_t i = 0; i < n; ++i) {
      const PolarVertex& v = p.shape[i];
      const std::string at = "free shape vertex " + std::to_string(i + 1) + ": ";
      if (!(std::isfinite(v.radius_mm) && v.radius_mm > 0.0 && v.radius_mm <= kMaxShapeRadiusMm))
        return bad(at + "radius = " + six_digits(v.radius_mm) + " mm; allowed > 0 … " +
                   six_digits(kMaxShapeRadiusMm) + " mm");
      if (!(std::isfinite(v.angle_deg) && v.angle_deg >= 0.0 && v.angle_deg < 360.0))
        return bad(at + "angle = " + six_digits(v.angle_deg) + "°; allowed 0 … <360°");
      const double next = i + 1 < n ? p.shape[i + 1].angle_deg : p.shape[0].angle_deg + 360.0;
      if (i + 1 < n && !(next > v.angle_deg))
        return bad(at + "angle " + six_digits(v.angle_deg) + "° then " + six_digits(next) +
                   "°; angles must increase (counter-clockwise order)");
      if (next - v.angle_deg >= 180.0)
        return bad(at + "gap of " + six_digits(next - v.angle_deg) +
                   "° to the next vertex; allowed < 180° (the centre must lie inside)");
    }
  }
  return {};
}

Eigen::Isometry3d hole_frame(const HoleProcessParams& p) {
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.translation() = p.position.head<3>();
  f.linear() = (Eigen::AngleAxisd(p.position[index(Axis::C)] * kRadPerDeg, Vec3::UnitZ()) *
                Eigen::AngleAxisd(p.position[index(Axis::A)] * kRadPerDeg, Vec3::UnitX()))
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
