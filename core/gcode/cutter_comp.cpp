// Cutter (kerf) compensation, by LinuxCNC 2.9's rules (its rs274ngc
// convert_cutter_compensation, convert_straight_comp1/2, convert_arc_comp1/2
// and the move queue of interp_queue): the tool centre runs one radius to
// the left (G41) or right (G42) of the programmed path, in G17 (X Y) or G18
// (Z X). On a laser the "tool" is the beam and its diameter the kerf, so a
// part comes out at its drawn size.
//
//   G41 / G42 [D n]     radius: half the diameter of tool n (default: the
//                       tool in the spindle; a negative diameter swaps sides)
//   G41.1 / G42.1 D d   radius d/2, d in program units
//   G40                 off: the next move (straight) leaves the path
//
// The first move after G41/G42 is the entry: it ends one radius beside its
// programmed end, square to its own direction (an arc: beside its end, on
// the arc's offset circle). After that each move ends one radius beside its
// programmed end, square to the path there. Where two moves meet:
//   - a convex corner (the tool outside it, turning more than
//     kCornerTolRad): an arc of the tool radius about the programmed corner
//     joins the two offset moves (a G0 goes straight to the next start);
//   - a concave corner: the move before is cut short where the two offset
//     paths cross: its end is fixed only when the next move is known, so a
//     move is held until then (with any dwell or Z move after it) — and an
//     offset path that would have to run backwards is an error (E313: the
//     tool does not fit, it would gouge the part);
//   - tangent moves (within kCornerTolRad): nothing between them.
// Whatever the moves' count and order, no compensated feed move may come
// nearer to the programmed path of the run than the tool radius (less the
// corner tolerance's chord), nor run against its programmed direction:
// comp_gouge.h measures each against the run's window of moves.
// While compensation is on, what would move the path under it — another
// plane, tool, tool offset, coordinate system, path mode, G28/G30, G92/G52,
// canned cycles, M62/M63/M67 and M66 — is an error at its word, as in
// LinuxCNC (and G53 and G93 here too). G40, M0/M1/M60, M2/M30 and the program's end let the held moves
// go where they stand.
#include <cmath>
#include <numbers>
#include <string>

#include "gcode/arc_geometry.h"
#include "gcode/interpreter.h"

namespace lcnc::gcode {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = kPi / 2.0;
// A corner turning less than this (rad) either way is taken as tangent
// (LinuxCNC TOLERANCE_CONCAVE_CORNER).
constexpr double kCornerTolRad = 0.05;
// |cos| below this: the entry arc's new centre is undefined (LinuxCNC
// TOLERANCE_EQUAL).
constexpr double kPerpendicularCos = 0.0001;
// How much a compensated arc's two radii may differ, program units
// (LinuxCNC: the centre-arc tolerance, 0.028 mm or 0.0028 in).
constexpr double kCompRadiusTolMm = 2.0 * 0.01 * std::numbers::sqrt2;
constexpr double kCompRadiusTolIn = 2.0 * 0.001 * std::numbers::sqrt2;
constexpr int kLeft = 1;

// The signed sweep (rad, counter-clockwise positive) of an arc of `turn`
// (±1 for one turn or less, ±n for G2/G3 P n) from (x1, y1) to (x2, y2)
// about (cx, cy) (LinuxCNC find_turn).
double find_turn(double x1, double y1, double cx, double cy, int turn, double x2, double y2) {
  if (turn == 0) return 0.0;
  double alpha = std::atan2(y1 - cy, x1 - cx);
  double beta = std::atan2(y2 - cy, x2 - cx);
  if (turn > 0) {
    if (beta <= alpha) beta += 2.0 * kPi;
    return (beta - alpha) + (turn - 1) * (2.0 * kPi);
  }
  if (alpha <= beta) alpha += 2.0 * kPi;
  return (beta - alpha) + (turn + 1) * (2.0 * kPi);
}

// LinuxCNC's turn of an arc segment: +n counter-clockwise, −n clockwise.
int turn_of(const Segment& s) {
  const int n = static_cast<int>(s.extra_turns) + 1;
  return s.clockwise ? -n : n;
}

// The tool runs inside the arc: left of a counter-clockwise one, right of a
// clockwise one.
bool tool_inside_arc(int side, int turn) {
  return (side == kLeft && turn > 0) || (side != kLeft && turn < 0);
}

}  // namespace

Segment& Interpreter::push_segment(SegmentBuffer& out) {
  if (holding_ || !held_.empty()) {
    held_.emplace_back();
    return held_.back().s;
  }
  return out.push();
}

bool Interpreter::comp_fail(std::string message) {
  return fail(ErrorCode::GcodeCutterComp, motion_word_,
              "found " + quoted_block() + " with cutter compensation (" +
                  (comp_side_ == kLeft ? "left" : "right") + ", tool radius " +
                  num(comp_radius_mm_ / length_scale()) + (modal_.inch ? " in" : " mm") +
                  "): " + std::move(message));
}

namespace {

// How near the tool may come to the programmed path: its radius, less what
// a corner taken as tangent (kCornerTolRad) leaves of it and a micrometre.
double gouge_distance(double r) { return r - (1e-3 + r * (1.0 - std::cos(kCornerTolRad))); }

}  // namespace

bool Interpreter::comp_gouge_fail(const GougeWindow::Gouge& g) {
  const double s = length_scale();
  const char* unit = modal_.inch ? " in" : " mm";
  return comp_fail("the compensated path of line " + std::to_string(g.cut.line) + " comes within " +
                   num(g.distance / s) + unit + " of the programmed path of line " +
                   std::to_string(g.programmed.line) +
                   ", nearer than the tool radius: the beam "
                   "would cut into the part there; expected a path whose features are wider "
                   "than the tool");
}

bool Interpreter::comp_check_programmed(const PlanePiece& p) {
  const double r = comp_radius_mm_;
  if (auto g = gouge_.add_programmed(p, gouge_distance(r), (r - gouge_distance(r)) / 4.0))
    return comp_gouge_fail(*g);
  return true;
}

// A compensated move as it goes: the beam's part of it (not the entry, not a
// rapid) must stay the tool radius from the programmed path, and a straight
// one must run the way it was programmed.
bool Interpreter::comp_check_cut(const HeldMove& h) {
  const Segment& s = h.s;
  if (h.tag.entry || s.kind == MotionKind::Rapid || s.kind == MotionKind::Dwell) return true;
  const int a = comp_a_, b = comp_b_;
  const Eigen::Vector2d from(s.start[a], s.start[b]), to(s.end[a], s.end[b]);
  PlanePiece p;
  if (s.kind == MotionKind::Arc) {
    const Eigen::Vector2d c(s.center[a], s.center[b]);
    p = PlanePiece::circular(from, to, c,
                             find_turn(from.x(), from.y(), c.x(), c.y(), turn_of(s), to.x(), to.y()), s.line);
  } else {
    const Eigen::Vector2d dir(h.dx, h.dy);
    if (dir.squaredNorm() > 0.0 && (to - from).dot(dir.normalized()) < -1e-6) {
      return comp_fail("the straight move of line " + std::to_string(s.line) +
                       " would run backwards under compensation (the moves around it leave "
                       "the tool no room): the beam would cut into the part; expected a path "
                       "whose features are wider than the tool");
    }
    p = PlanePiece::straight(from, to, s.line);
  }
  for (int i = 0; i < h.tag.anchors; ++i) p.anchor[i] = h.tag.anchor[i];
  p.anchors = h.tag.anchors;
  const double r = comp_radius_mm_;
  if (auto g = gouge_.add_cut(p, gouge_distance(r), (r - gouge_distance(r)) / 4.0))
    return comp_gouge_fail(*g);
  return true;
}

// What may not change under compensation, and what it cannot run (LinuxCNC
// refuses each of these while it is on). A G40 in the block turns it off
// before the codes after it in LinuxCNC's order run (not before a plane or
// tool change).
bool Interpreter::check_comp_conflicts() {
  const Block& b = *b_;
  const bool turning_off = b.code(GGroup::CutterComp) == 400;
  auto refuse = [&](Span at, const char* what) {
    return fail(ErrorCode::GcodeModalConflict, at,
                "found " + quoted(at) + " with cutter compensation on (G41/G42): " + what +
                    " under it; expected G40 (compensation off) before it");
  };
  if (b.m_tool >= 0) return refuse(b.m_tool_word, "a tool change would change the radius");
  const int plane = b.code(GGroup::Plane);
  if (plane >= 0 && plane != (modal_.plane == Plane::XY ? 170 : modal_.plane == Plane::ZX ? 180 : 190)) {
    return refuse(b.code_word(GGroup::Plane), "the plane cannot change");
  }
  if (turning_off) return true;
  if (b.code(GGroup::ToolLength) >= 0) {
    return refuse(b.code_word(GGroup::ToolLength), "the tool offset cannot change");
  }
  if (b.code(GGroup::CoordSystem) >= 0) {
    return refuse(b.code_word(GGroup::CoordSystem), "the coordinate system cannot change");
  }
  if (b.code(GGroup::PathControl) >= 0) {
    return refuse(b.code_word(GGroup::PathControl), "the path control mode cannot change");
  }
  if (b.code(GGroup::RetractMode) >= 0) {
    return refuse(b.code_word(GGroup::RetractMode), "the canned cycle return mode cannot change");
  }
  if (b.code(GGroup::FeedMode) == 930) {
    return refuse(b.code_word(GGroup::FeedMode), "inverse time feed (G93) is not supported");
  }
  switch (b.code(GGroup::NonModal)) {
    case 280:
    case 281:
    case 300:
    case 301: return refuse(b.code_word(GGroup::NonModal), "reference points cannot be used or set");
    case 520:
    case 920:
    case 921:
    case 922:
    case 923: return refuse(b.code_word(GGroup::NonModal), "the axis offsets cannot change");
    case 530: return refuse(b.code_word(GGroup::NonModal), "machine coordinates (G53) cannot be used");
    case 100:
      if (b.has('L') && (b['L'] == 2.0 || b['L'] == 20.0) && b.has('P') &&
          (b['P'] == 0.0 || b['P'] == modal_.coord_system + 1)) {
        return refuse(b.code_word(GGroup::NonModal), "the coordinate system in effect cannot change");
      }
      break;
    default: break;
  }
  if (is_cycle(block_motion_)) return refuse(motion_word_, "canned cycles cannot run");
  // (LinuxCNC: outputs synchronized with a move it holds, or a wait)
  if (b.m_io == 62 || b.m_io == 63 || b.m_io == 66 || b.m_io == 67) {
    return refuse(b.m_io_word, "outputs synchronized with motion and input waits cannot run");
  }
  return true;
}

bool Interpreter::set_cutter_comp(SegmentBuffer& out) {
  const Block& b = *b_;
  const int code = b.code(GGroup::CutterComp);
  if (code < 0) return true;
  const Span at = b.code_word(GGroup::CutterComp);
  if (code == 400) {
    if (comp_active() && !comp_first_move_) {
      // The held moves end where they stand; the next move leaves the
      // path from there, to a point programmed from the last programmed one.
      if (!comp_move_endpoint_and_flush(pos_[comp_a_], pos_[comp_b_], out)) return false;
      if (!comp_dequeue(out)) return false;
      comp_exited_ = true;
    }
    gouge_.clear();
    comp_side_ = 0;
    comp_first_move_ = true;
    return true;
  }
  if (comp_side_ != 0) {
    return fail(ErrorCode::GcodeModalConflict, at,
                "found " + quoted(at) +
                    " with cutter compensation already on; expected G40 "
                    "before turning it on again");
  }
  const int plane_code = b.code(GGroup::Plane);
  const Plane plane = plane_code == 180   ? Plane::ZX
                      : plane_code == 190 ? Plane::YZ
                      : plane_code == 170 ? Plane::XY
                                          : modal_.plane;
  if (plane == Plane::YZ) {
    return fail(ErrorCode::GcodeUnsupported, at,
                "found " + quoted(at) +
                    " in the YZ plane (G19); expected cutter compensation "
                    "in G17 (XY) or G18 (ZX)");
  }
  const int fm = b.code(GGroup::FeedMode);
  if (fm == 930 || (fm < 0 && modal_.inverse_time)) {
    return fail(ErrorCode::GcodeUnsupported, at,
                "found " + quoted(at) +
                    " in inverse time feed (G93); expected G94 (units per "
                    "minute) with cutter compensation");
  }
  int side = code < 420 ? kLeft : -kLeft;
  double radius = 0.0;
  if (code == 411 || code == 421) {
    if (!b.has('D')) {
      return fail(ErrorCode::GcodeMissingWord, at,
                  "found " + quoted(at) + " with no D word; expected " + quoted(at) +
                      " D<diameter>, the diameter of the tool (the laser's kerf width)");
    }
    const int units = b.code(GGroup::Units);
    const bool inch = units >= 0 ? units == 200 : modal_.inch;
    radius = b['D'] * (inch ? kMmPerInch : 1.0) / 2.0;
  } else {
    int tool = 0;
    if (b.has('D') && !tool_number('D', tool)) return false;
    // D0 or no D: the tool in the spindle (LinuxCNC: its table's index 0)
    const ToolConfig* t = find_tool(tool == 0 ? current_tool_ : tool);
    radius = t != nullptr ? t->diameter_mm / 2.0 : 0.0;
  }
  if (std::fabs(radius) > kMaxToolOffsetMm) {
    return fail(ErrorCode::GcodeBadValue, b.has('D') ? b.span('D') : at,
                "found " + quoted(at) + " with a tool radius of " + gnum(radius) +
                    " mm; expected a diameter of at most " + gnum(2.0 * kMaxToolOffsetMm) + " mm");
  }
  if (radius < 0.0) {  // a negative diameter: the other side
    radius = -radius;
    side = -side;
  }
  comp_side_ = side;
  comp_radius_mm_ = radius;
  comp_first_move_ = true;
  gouge_.clear();
  const auto axes = arc_plane_axes(plane);
  comp_a_ = axes[0];
  comp_b_ = axes[1];
  return true;
}

// --- the held moves ---------------------------------------------------------

bool Interpreter::comp_held_straight(const Pose& end, double dx, double dy, SegmentBuffer& out,
                                     const HeldTag& tag) {
  holding_ = true;
  const std::size_t n = held_.size();
  const bool ok = block_motion_ == MotionMode::Rapid ? rapid_to(end, out) : line_to(end, out);
  holding_ = false;
  if (ok && held_.size() > n) {
    held_.back().dx = dx;
    held_.back().dy = dy;
    held_.back().tag = tag;
  }
  return ok;
}

bool Interpreter::comp_held_arc(const Pose& end, const Vec3& c, int turn, double turns, SegmentBuffer& out,
                                const HeldTag& tag) {
  holding_ = true;
  const std::size_t n = held_.size();
  const bool ok = arc_to(end, c, turn < 0, static_cast<std::uint32_t>(std::abs(turn) - 1), out);
  holding_ = false;
  if (ok && held_.size() > n) {
    held_.back().turns = turns;
    held_.back().tag = tag;
  }
  return ok;
}

// Round a convex corner: an arc of the tool radius about the programmed
// corner from where the tool stands to (mx, my) (a G0: straight there), Z
// where it is, the rotary axes at the move's `end`; then it goes.
bool Interpreter::comp_round_corner(double mx, double my, const Pose& end, bool rapid, SegmentBuffer& out) {
  Pose m = pos_;
  m[comp_a_] = mx;
  m[comp_b_] = my;
  for (int k = 3; k < kAxisCount; ++k) m[k] = end[k];
  if (rapid) {
    if (!comp_held_straight(m, 0.0, 0.0, out, HeldTag{})) return false;
  } else {
    Vec3 c = linear_part(pos_);
    c[comp_a_] = programmed_[comp_a_];
    c[comp_b_] = programmed_[comp_b_];
    if (!comp_held_arc(m, c, comp_side_ == kLeft ? -1 : 1, 0.0, out, HeldTag::at({c[comp_a_], c[comp_b_]}))) {
      return false;
    }
  }
  if (!comp_dequeue(out)) return false;
  comp_set_endpoint(mx, my);
  return true;
}

// Every held move now ends at (x, y) of the plane; then they go (LinuxCNC
// move_endpoint_and_flush). A straight move that would now run against its
// programmed direction, or an arc that would now turn further than it was
// programmed to, cannot be cut without gouging.
bool Interpreter::comp_move_endpoint_and_flush(double x, double y, SegmentBuffer& out) {
  if (held_.empty()) return true;
  const int a = comp_a_, b = comp_b_;
  const double ex = comp_endpoint_[0], ey = comp_endpoint_[1];
  for (HeldMove& h : held_) {
    Segment& s = h.s;
    switch (s.kind) {
      case MotionKind::Arc: {
        const double c1 = s.center[a], c2 = s.center[b];
        const double r1 = std::hypot(s.end[a] - c1, s.end[b] - c2);
        const double r2 = std::hypot(x - c1, y - c2);
        const double l2 = find_turn(ex, ey, c1, c2, turn_of(s), x, y);
        if (std::fabs(r1 - r2) > 0.01 * length_scale()) {
          return comp_fail("the compensated arc of line " + std::to_string(s.line) +
                           " would end off its circle (radius " + num(r1) + " mm, end at " + num(r2) +
                           " mm); expected a path whose moves meet where the tool "
                           "fits");
        }
        if (h.turns != 0.0 && comp_endpoint_valid_ &&
            std::fabs(l2) > std::fabs(h.turns) + (modal_.inch ? 0.001 : 0.0254)) {
          return comp_fail("the arc of line " + std::to_string(s.line) +
                           " runs into a concave corner the tool cannot reach without gouging "
                           "the part; expected a corner the tool radius fits");
        }
        s.end[a] = x;
        s.end[b] = y;
        break;
      }
      case MotionKind::Rapid:
      case MotionKind::Linear: {
        const double dot = h.dx * (x - ex) + h.dy * (y - ey);
        if (comp_endpoint_valid_ && dot < 0.0) {
          return comp_fail(std::string("the ") + (s.kind == MotionKind::Rapid ? "rapid" : "straight") +
                           " move of line " + std::to_string(s.line) +
                           " runs into a concave corner the tool cannot reach without gouging "
                           "the part (its compensated path would run backwards); expected a "
                           "longer move or a smaller tool");
        }
        s.end[a] = x;
        s.end[b] = y;
        break;
      }
      case MotionKind::Dwell: break;
    }
  }
  if (!comp_dequeue(out)) return false;
  comp_set_endpoint(x, y);
  pos_[a] = x;
  pos_[b] = y;
  return true;
}

// The held moves go as they stand, each from where the one before ends; a
// straight move left with no length goes not at all.
bool Interpreter::comp_dequeue(SegmentBuffer& out) {
  comp_endpoint_valid_ = false;
  if (held_.empty()) return true;
  Pose at = held_.front().s.start;
  for (HeldMove& h : held_) {
    Segment& s = h.s;
    s.start = at;
    if (s.kind == MotionKind::Dwell) s.end = at;
    if (s.kind != MotionKind::Dwell && s.kind != MotionKind::Arc && s.end == s.start) continue;
    if (!comp_check_cut(h)) return false;
    if (s.kind == MotionKind::Arc) {  // its end moved along its circle: the travel again
      Vec3 lo3, hi3;
      arc_bounds(s, lo3, hi3);
      Pose lo = s.end.cwiseMin(s.start), hi = s.end.cwiseMax(s.start);
      lo.head<3>() = lo3;
      hi.head<3>() = hi3;
      for (int k = 3; k < kAxisCount; ++k) lo[k] = hi[k] = s.end[k];
      if (!check_travel(lo, hi, s.end)) return false;
    }
    out.push() = s;
    at = s.end;
  }
  held_.clear();
  return true;
}

bool Interpreter::finish(SegmentBuffer& out) { return comp_dequeue(out); }

// --- straight moves -----------------------------------------------------------

bool Interpreter::comp_straight(const Pose& end, SegmentBuffer& out) {
  const bool rapid = block_motion_ == MotionMode::Rapid;
  if (!rapid && !check_feed()) return false;
  const int a = comp_a_, b = comp_b_;
  const bool left = comp_side_ == kLeft;
  const double r = comp_radius_mm_;
  const double px = end[a], py = end[b];
  const double cx = pos_[a], cy = pos_[b];
  if (comp_first_move_) {
    // The entry: to one radius beside the end, square to this move.
    const double distance = std::hypot(px - cx, py - cy);
    if (distance <= r) {
      return comp_fail("its entry move is " + num(distance / length_scale()) + (modal_.inch ? " in" : " mm") +
                       " long in the plane; expected an entry move (the first after G41/G42) "
                       "longer than the tool radius");
    }
    const double alpha = std::atan2(py - cy, px - cx) + (left ? kHalfPi : -kHalfPi);
    Pose e = end;
    e[a] = px + r * std::cos(alpha);
    e[b] = py + r * std::sin(alpha);
    comp_set_endpoint(cx, cy);
    if (!comp_held_straight(e, std::cos(alpha), std::sin(alpha), out, HeldTag::entry_move())) return false;
    comp_first_move_ = false;
    programmed_ = end;
    return true;
  }
  const double opx = programmed_[a], opy = programmed_[b];
  Pose e = end;
  if (py == opy && px == opx) {  // no motion in the plane: the tool stays beside it
    e[a] = cx;
    e[b] = cy;
    if (!comp_held_straight(e, 0.0, 0.0, out, HeldTag::at({px, py}))) return false;
    programmed_ = end;
    return true;
  }
  double theta = std::atan2(cy - opy, cx - opx);  // from the programmed point to the tool
  double alpha = std::atan2(py - opy, px - opx);  // this move's direction
  double beta = 0.0;                              // how far the path turns, less 90°
  double gamma = 0.0;
  if (left) {
    if (theta < alpha) theta += 2.0 * kPi;
    beta = (theta - alpha) - kHalfPi;
    gamma = kHalfPi;
  } else {
    if (alpha < theta) alpha += 2.0 * kPi;
    beta = (alpha - theta) - kHalfPi;
    gamma = -kHalfPi;
  }
  const double ex = px + r * std::cos(alpha + gamma);
  const double ey = py + r * std::sin(alpha + gamma);
  const double mid_x = opx + r * std::cos(alpha + gamma);
  const double mid_y = opy + r * std::sin(alpha + gamma);
  const bool front_arc = !held_.empty() && held_.front().s.kind == MotionKind::Arc;
  const int front_turn = front_arc ? turn_of(held_.front().s) : 0;
  bool concave = beta < -kCornerTolRad || beta > kPi + kCornerTolRad;
  // An "h": over a round top (the tool on its outside), then down beside a
  // straight: stay outside, above the corner, not round it from below.
  if (!concave && beta > kPi - kCornerTolRad && front_arc &&
      ((!left && front_turn > 0) || (left && front_turn < 0))) {
    concave = true;
  }
  if (!concave && beta > kCornerTolRad) {
    // Convex: round the corner about it (a G0 goes straight there).
    if (!comp_move_endpoint_and_flush(cx, cy, out) || !comp_round_corner(mid_x, mid_y, end, rapid, out)) {
      return false;
    }
  } else if (concave) {
    double x = 0.0, y = 0.0;
    if (!front_arc) {
      // line → line: back along the offset path to where the two cross
      const double halfcorner = (beta + kPi) / 2.0;
      if (halfcorner == 0.0) return comp_fail("a zero-degree inside corner; expected a corner");
      const double retreat = r / std::tan(halfcorner);
      x = cx + retreat * std::cos(theta + gamma);
      y = cy + retreat * std::sin(theta + gamma);
    } else {
      // arc → line: where the new offset line meets the arc's offset circle
      const Segment& prev = held_.front().s;
      const double pc1 = prev.center[a], pc2 = prev.center[b];
      const double oldrad = std::hypot(pc2 - prev.end[b], pc1 - prev.end[a]);
      const int pturn = turn_of(prev);
      const double base_dir = std::atan2(py - opy, px - opx);
      const double th = pturn > 0 ? base_dir + kHalfPi : base_dir - kHalfPi;
      const double phi = std::atan2(pc2 - opy, pc1 - opx);
      const bool inside = tool_inside_arc(comp_side_, pturn);
      const double oldrad_uncomp = inside ? oldrad + r : oldrad - r;
      const double d = oldrad_uncomp * std::cos(th - phi);  // old centre to the new line
      const double l = (inside ? d - r : d + r) / oldrad;
      if (l > 1.0 || l < -1.0) {
        return comp_fail(
            "the arc before and this straight move make a corner the tool "
            "cannot fit without gouging the part; expected a corner the tool "
            "radius fits");
      }
      const double angle = ((pturn > 0) == inside ? -std::acos(l) : std::acos(l)) + th + kPi;
      x = pc1 + oldrad * std::cos(angle);
      y = pc2 + oldrad * std::sin(angle);
    }
    if (!comp_move_endpoint_and_flush(x, y, out)) return false;
  } else {
    // Tangent (or straight on): nothing between.
    if (!comp_dequeue(out)) return false;
    comp_set_endpoint(cx, cy);
  }
  e[a] = ex;
  e[b] = ey;
  if (!comp_held_straight(e, px - opx, py - opy, out, HeldTag::between({opx, opy}, {px, py}))) return false;
  programmed_ = end;
  if (!rapid && !comp_check_programmed(PlanePiece::straight({opx, opy}, {px, py}, line_))) return false;
  return true;
}

// --- arcs ---------------------------------------------------------------------

bool Interpreter::comp_arc(const Pose& end_in, SegmentBuffer& out) {
  const Block& blk = *b_;
  const bool cw = block_motion_ == MotionMode::ArcCw;
  const int a = comp_a_, b = comp_b_;
  const bool left = comp_side_ == kLeft;
  const double r = comp_radius_mm_;
  const double cx = pos_[a], cy = pos_[b];
  const double abs_tol = modal_.inch ? kCompRadiusTolIn * kMmPerInch : kCompRadiusTolMm;
  Pose e = end_in;
  Vec3 c;
  std::uint32_t extra = 0;
  if (comp_first_move_) {
    // The entry arc: its end one radius beside the programmed end, its
    // centre moved to keep it an arc from where the tool stands.
    if (std::hypot(e[a] - cx, e[b] - cy) <= r) {
      return comp_fail(
          "its entry arc ends within the tool radius of its start; expected an "
          "entry move (the first after G41/G42) longer than the tool radius");
    }
    if (!arc_centre(pos_, e, c, extra)) return false;
    const int turn = cw ? -static_cast<int>(extra + 1) : static_cast<int>(extra + 1);
    const double arc_r =
        blk.has('R') ? std::fabs(blk['R']) * length_scale() : std::hypot(c[a] - cx, c[b] - cy);
    if (tool_inside_arc(comp_side_, turn) && arc_r <= r) {
      return comp_fail("the arc's radius " + num(arc_r) +
                       " mm is not larger than the tool radius; expected arcs the tool fits "
                       "inside");
    }
    const double gamma = tool_inside_arc(comp_side_, turn) ? std::atan2(c[b] - e[b], c[a] - e[a])
                                                           : std::atan2(e[b] - c[b], e[a] - c[a]);
    comp_first_move_ = false;
    programmed_ = e;
    e[a] += r * std::cos(gamma);
    e[b] += r * std::sin(gamma);
    const double b_len = std::hypot(cy - e[b], cx - e[a]) / 2.0;
    const double ab_ang = std::atan2(c[b] - e[b], c[a] - e[a]);
    const double a_ang = std::atan2(cy - e[b], cx - e[a]) - ab_ang;
    if (std::fabs(std::cos(a_ang)) < kPerpendicularCos) {
      return comp_fail(
          "the tool radius is not less than the entry arc's; expected arcs the "
          "tool fits inside");
    }
    const double c_len = b_len / std::cos(a_ang);
    c[a] = e[a] + c_len * std::cos(ab_ang);
    c[b] = e[b] + c_len * std::sin(ab_ang);
    if (std::fabs(std::hypot(c[a] - e[a], c[b] - e[b]) - std::hypot(c[a] - cx, c[b] - cy)) > abs_tol) {
      return comp_fail(
          "the entry arc cannot be compensated (its radii differ); expected a "
          "straight entry move");
    }
    return comp_held_arc(e, c, turn, find_turn(cx, cy, c[a], c[b], turn, e[a], e[b]), out,
                         HeldTag::entry_move());
  }
  const double opx = programmed_[a], opy = programmed_[b];
  const bool full_circle = !blk.has('R') && std::hypot(e[a] - opx, e[b] - opy) <= kSamePointMm;
  if (!arc_centre(programmed_, e, c, extra)) return false;
  c[3 - a - b] = pos_[3 - a - b];
  const int turn = cw ? -static_cast<int>(extra + 1) : static_cast<int>(extra + 1);
  const double ccx = c[a], ccy = c[b];
  const double arc_radius = std::hypot(ccx - e[a], ccy - e[b]);
  double theta = std::atan2(cy - opy, cx - opx);
  theta = left ? theta - kHalfPi : theta + kHalfPi;  // the path's direction at the corner
  double delta = std::atan2(ccy - opy, ccx - opx);
  const double alpha = cw ? delta + kHalfPi : delta - kHalfPi;  // the arc's, at its start
  double beta = left ? theta - alpha : alpha - theta;
  beta = beta > 1.5 * kPi ? beta - 2.0 * kPi : beta < -kHalfPi ? beta + 2.0 * kPi : beta;
  const bool inside = tool_inside_arc(comp_side_, turn);
  double gamma = 0.0;
  if (inside) {
    gamma = std::atan2(ccy - e[b], ccx - e[a]);
    if (arc_radius <= r) {
      return comp_fail("the arc's radius " + num(arc_radius) +
                       " mm is not larger than the tool radius; expected arcs the tool fits "
                       "inside");
    }
  } else {
    gamma = std::atan2(e[b] - ccy, e[a] - ccx);
    delta += kPi;
  }
  Pose ne = e;
  ne[a] = e[a] + r * std::cos(gamma);
  ne[b] = e[b] + r * std::sin(gamma);
  const double turns = find_turn(opx, opy, ccx, ccy, turn, e[a], e[b]);
  if (beta < -kCornerTolRad || beta > kPi + kCornerTolRad ||
      (std::fabs(beta - kPi) < kCornerTolRad && !inside)) {
    // Concave: the move before ends where this arc's offset circle meets it.
    double x = 0.0, y = 0.0;
    if (held_.empty() || held_.front().s.kind != MotionKind::Arc) {
      // line → arc
      const double cy2 = arc_radius * std::sin(beta - kHalfPi);
      const double dist = inside ? arc_radius - r : arc_radius + r;
      const double l = (inside ? cy2 + r : cy2 - r) / dist;
      if (l > 1.0 || l < -1.0) {
        return comp_fail(
            "this arc makes a concave corner the tool cannot reach without "
            "gouging the part; expected a corner the tool radius fits");
      }
      const double angle = inside ? (turn > 0 ? theta + std::asin(l) : theta - std::asin(l))
                                  : (turn > 0 ? theta + kPi - std::asin(l) : theta + kPi + std::asin(l));
      x = ccx + dist * std::cos(angle);
      y = ccy + dist * std::sin(angle);
    } else {
      // arc → arc: where the two offset circles cross
      const Segment& prev = held_.front().s;
      const double pc1 = prev.center[a], pc2 = prev.center[b];
      const double oldrad = std::hypot(pc2 - prev.end[b], pc1 - prev.end[a]);
      const double newrad = inside ? arc_radius - r : arc_radius + r;
      const double arc_cc = std::hypot(pc2 - ccy, pc1 - ccx);
      if (oldrad == 0.0 || arc_cc == 0.0) {
        return comp_fail(
            "this arc and the one before have the same centre; expected arcs "
            "that meet at a corner");
      }
      const double cos_a = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2.0 * oldrad * arc_cc);
      if (cos_a > 1.0 || cos_a < -1.0) {
        return comp_fail(
            "this arc and the one before make a corner the tool cannot fit "
            "without gouging the part; expected a corner the tool radius fits");
      }
      const double pullback = std::acos(cos_a);
      const double cc_dir = std::atan2(ccy - pc2, ccx - pc1);
      const bool prev_inside = tool_inside_arc(comp_side_, turn_of(prev));
      const double dir = (prev_inside == (turn > 0)) ? cc_dir + pullback : cc_dir - pullback;
      x = pc1 + oldrad * std::cos(dir);
      y = pc2 + oldrad * std::sin(dir);
    }
    if (!comp_move_endpoint_and_flush(x, y, out)) return false;
  } else if (beta > kCornerTolRad) {
    // Convex: round the corner about it first.
    const double mid_x = opx + r * std::cos(delta);
    const double mid_y = opy + r * std::sin(delta);
    if (!comp_dequeue(out) || !comp_round_corner(mid_x, mid_y, e, false, out)) return false;
  } else {
    if (!comp_dequeue(out)) return false;
    comp_set_endpoint(cx, cy);
  }
  // A full circle stays one: it ends where it starts, exactly.
  if (full_circle && std::hypot(ne[a] - pos_[a], ne[b] - pos_[b]) <= 1e-6) {
    ne[a] = pos_[a];
    ne[b] = pos_[b];
  }
  if (!comp_held_arc(ne, c, turn, turns, out, HeldTag::between({opx, opy}, {e[a], e[b]}))) return false;
  programmed_ = e;
  return comp_check_programmed(PlanePiece::circular({opx, opy}, {e[a], e[b]}, {ccx, ccy}, turns, line_));
}

}  // namespace lcnc::gcode
