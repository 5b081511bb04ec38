// Canned cycles, as LinuxCNC runs them, in the XY plane (G17: the hole axis
// is Z, the laser's beam axis). On a laser, G81 is a drilled hole (the beam
// on while Z feeds down), G82 a percussion hole (a dwell at the bottom with
// the beam on), G83 and G73 drill in pecks.
//
// For each of L repeats (G91: each from the last hole, X Y incremental; G90:
// the same hole again):
//   1. once, first: when the series' initial Z (where Z stood before the
//      first of these cycle blocks in a row) is below R, Z rapids to R where
//      it stands;
//   2. to the hole: the first one, from a Z above R, at that Z and then
//      down to R; every other at the clear height (below), then down to R;
//   3. the cycle: G81 feed to Z; G82 feed to Z, dwell P; G83 feed down by Q,
//      rapid up to R, rapid down to the last depth + δ, … ; G73 feed down by
//      Q, rapid up δ, … (δ = 0.254 mm, LinuxCNC's 0.010 in); G85 feed to Z,
//      feed back to R; G89 feed to Z, dwell P, feed back to the clear height;
//      G86 (boring: the spindle stops, the tool comes out at rapid) is G82's
//      moves with the beam on — LinuxCNC refuses it with the spindle off;
//   4. rapid to the clear height: R (G99) or, G98, the series' initial Z
//      when that is higher than R.
// R and Z are program coordinates (G91: R from the series' initial Z, Z
// from R).
// R, Z, P and Q stay in effect for the following blocks of the same cycle
// (X Y alone drill the next hole); a new cycle mode needs R and Z again.
#include <cmath>
#include <string>

#include "gcode/gcode_tolerances.h"
#include "gcode/interpreter.h"

namespace lcnc::gcode {
namespace {

// LinuxCNC's G73 and G83 clearance (G83_RAPID_DELTA, 0.010 in), mm.
constexpr double kPeckClearanceMm = 0.254;
// A block's moves at most: a cycle with tiny pecks or many repeats is an
// error, not a million moves held for one line.
constexpr std::size_t kMaxBlockSegments = 100'000;
constexpr double kMaxCycleRepeats = 10'000;

const char* cycle_name(MotionMode m) {
  switch (m) {
    case MotionMode::Cycle73: return "G73";
    case MotionMode::Cycle81: return "G81";
    case MotionMode::Cycle82: return "G82";
    case MotionMode::Cycle83: return "G83";
    case MotionMode::Cycle85: return "G85";
    case MotionMode::Cycle86: return "G86";
    default: return "G89";
  }
}

}  // namespace

void Interpreter::dwell_for(double seconds, SegmentBuffer& out) {
  Segment& s = out.push();
  fill_modal(s);
  s.kind = MotionKind::Dwell;
  s.start = pos_;
  s.end = pos_;
  s.dwell_s = seconds;  // the beam keeps its mode: percussion
}

// R Z P Q of this block or, later in the same cycle, of the one before; mm, s.
bool Interpreter::cycle_words(double& r, double& z, double& p, double& q) {
  const Block& b = *b_;
  const char* name = cycle_name(block_motion_);
  const bool dwells = block_motion_ == MotionMode::Cycle82 || block_motion_ == MotionMode::Cycle86 ||
                      block_motion_ == MotionMode::Cycle89;
  const bool pecks = block_motion_ == MotionMode::Cycle83 || block_motion_ == MotionMode::Cycle73;
  if (!cycle_sticky_) {
    for (const char l : {'R', 'Z'}) {
      if (b.has(l)) continue;
      return fail(ErrorCode::GcodeMissingWord, motion_word_,
                  "found " + quoted_block() + " with no " + std::string(1, l) + " word; expected " + name +
                      " with R (the retract plane) and Z (the hole's bottom) on its first "
                      "block");
    }
    if (dwells && !b.has('P')) {
      return fail(ErrorCode::GcodeMissingWord, motion_word_,
                  "found " + quoted_block() + " with no P word; expected " + name +
                      " P<seconds of dwell at the bottom> on its first block");
    }
    if (pecks && !b.has('Q')) {
      return fail(ErrorCode::GcodeMissingWord, motion_word_,
                  "found " + quoted_block() + " with no Q word; expected " + name +
                      " Q<peck depth> on its first block");
    }
  }
  if (b.has('R')) cycle_r_ = b['R'] * length_scale();
  if (b.has('Z')) cycle_z_ = b['Z'] * length_scale();
  if (b.has('P')) {
    const double v = b['P'];
    if (v < 0.0 || v > kMaxBlockSeconds) {
      return fail(ErrorCode::GcodeBadValue, b.span('P'),
                  "found " + quoted(b.span('P')) + " on " + name + "; expected a dwell P from 0 to " +
                      std::to_string(static_cast<int>(kMaxBlockSeconds)) + " seconds");
    }
    cycle_p_ = v;
  }
  if (b.has('Q')) {
    if (b['Q'] <= 0.0) {
      return fail(ErrorCode::GcodeBadValue, b.span('Q'),
                  "found " + quoted(b.span('Q')) + " on " + name + "; expected a peck depth Q > 0");
    }
    cycle_q_ = b['Q'] * length_scale();
  }
  cycle_sticky_ = true;
  r = cycle_r_;
  z = cycle_z_;
  p = cycle_p_;
  q = cycle_q_;
  return true;
}

bool Interpreter::canned_cycle(SegmentBuffer& out) {
  const Block& b = *b_;
  const MotionMode m = block_motion_;
  const char* name = cycle_name(m);
  if (modal_.plane != Plane::XY) {
    return fail(
        ErrorCode::GcodeUnsupported, motion_word_,
        "found " + quoted_block() + " in the " +
            (modal_.plane == Plane::ZX ? std::string("ZX plane (G18)") : std::string("YZ plane (G19)")) +
            "; expected canned cycles in G17 (holes along Z, the beam's axis)");
  }
  if (b.code(GGroup::NonModal) == 530) {
    return fail(ErrorCode::GcodeSyntax, b.code_word(GGroup::NonModal),
                "found " + quoted_block() + ": G53 with a canned cycle; expected G53 with G0 or G1");
  }
  if (modal_.inverse_time) {
    return fail(ErrorCode::GcodeSyntax, motion_word_,
                "found " + quoted_block() +
                    " in inverse-time mode (G93); expected canned cycles "
                    "in G94 (F per minute)");
  }
  for (int a = 3; a < kAxisCount; ++a) {
    if (((b.axis_mask >> a) & 1u) == 0) continue;
    const char l = kAxisLetters[a];
    return fail(ErrorCode::GcodeSyntax, b.span(l),
                "found " + quoted(b.span(l)) + " on " + name +
                    "; expected X Y (the hole), Z R P Q L on a canned cycle");
  }
  if (m == MotionMode::Cycle86 && modal_.laser == LaserMode::Off) {
    return fail(ErrorCode::GcodeUnsupported, motion_word_,
                "found " + quoted_block() +
                    " with the beam off; expected M3 or M4 before G86 "
                    "(it bores with the beam on and turns it off for the rapid out; LinuxCNC "
                    "refuses it with the spindle off too)");
  }
  double r = 0.0, z = 0.0, p = 0.0, q = 0.0;
  if (!cycle_words(r, z, p, q)) return false;
  if (!check_feed()) return false;
  int repeats = 1;
  if (b.has('L')) {
    const double l = b['L'];
    if (l != std::floor(l) || l < 1.0 || l > kMaxCycleRepeats) {
      return fail(ErrorCode::GcodeBadValue, b.span('L'),
                  "found " + quoted(b.span('L')) + " on " + name +
                      "; expected L, the repeats, a whole number from 1 to " +
                      std::to_string(static_cast<int>(kMaxCycleRepeats)));
    }
    repeats = static_cast<int>(l);
  }
  if (!cycle_series_) {
    cycle_series_ = true;
    cycle_initial_z_ = pos_[2];
  }
  const Pose& offset = offsets_;
  const double r_m = modal_.absolute ? r + offset[2] : cycle_initial_z_ + r;
  const double bottom = modal_.absolute ? z + offset[2] : r_m + z;
  if (bottom > r_m) {
    return fail(ErrorCode::GcodeBadValue, b.has('Z') ? b.span('Z') : motion_word_,
                "found " + quoted_block() +
                    ": the bottom Z is above the retract plane R; "
                    "expected Z at or below R");
  }
  const bool pecks = m == MotionMode::Cycle83 || m == MotionMode::Cycle73;
  const double peck_count = pecks ? std::ceil((r_m - bottom) / q) : 0.0;
  if (static_cast<double>(repeats) * (4.0 + 3.0 * peck_count) > kMaxBlockSegments) {
    return fail(ErrorCode::GcodeBadValue, b.has('Q') ? b.span('Q') : motion_word_,
                "found " + quoted_block() + ": " + std::to_string(repeats) + " holes of " +
                    std::to_string(static_cast<long long>(peck_count)) + " pecks; expected at most " +
                    std::to_string(kMaxBlockSegments) +
                    " moves from one line (a larger Q, fewer "
                    "repeats)");
  }

  // 1. The series' initial Z below R: to R first. The clear height: R, or
  // that initial Z (G98).
  double old_z = cycle_initial_z_;
  if (old_z < r_m) {
    Pose up = pos_;
    up[2] = r_m;
    if (!rapid_to(up, out)) return false;
    old_z = r_m;
  }
  const double clear = modal_.retract_old_z ? old_z : r_m;
  auto z_at = [&](double zz) {
    Pose t = pos_;
    t[2] = zz;
    return t;
  };
  auto feed = [&](double zz) { return line_to(z_at(zz), out); };
  for (int k = 0; k < repeats; ++k) {
    // 2. Over the hole, then down to R.
    Pose hole = pos_;
    if (b.polar != 0) {
      if (!polar_target(pos_, hole)) return false;
    } else {
      for (int a = 0; a < 2; ++a) {
        if (((b.axis_mask >> a) & 1u) == 0) continue;
        hole[a] = modal_.absolute ? axis_value(a) + offset[a] : pos_[a] + axis_value(a);
      }
    }
    if (k == 0 && pos_[2] > r_m) {
      if (!rapid_to(hole, out)) return false;
    } else {  // at the clear height already, or below R
      hole[2] = clear;
      if (!rapid_to(hole, out)) return false;
    }
    if (!rapid_to(z_at(r_m), out)) return false;
    // 3. The cycle.
    if (pecks) {
      for (double depth = r_m - q; depth > bottom; depth -= q) {
        if (!feed(depth)) return false;
        if (m == MotionMode::Cycle83) {
          if (!rapid_to(z_at(r_m), out)) return false;
          if (!rapid_to(z_at(depth + kPeckClearanceMm), out)) return false;
        } else if (!rapid_to(z_at(depth + kPeckClearanceMm), out)) {
          return false;
        }
      }
    }
    if (!feed(bottom)) return false;
    // G86 (boring: the spindle stops at the bottom, the tool comes out at
    // rapid): a laser's is G82's, the beam off for the rapid out as on
    // every rapid
    if (m == MotionMode::Cycle82 || m == MotionMode::Cycle86 || m == MotionMode::Cycle89) {
      dwell_for(p, out);
    }
    if (m == MotionMode::Cycle85 && !feed(r_m)) return false;
    if (m == MotionMode::Cycle89 && !feed(clear)) return false;
    // 4. Out.
    if (!rapid_to(z_at(clear), out)) return false;
  }
  return true;
}

}  // namespace lcnc::gcode
