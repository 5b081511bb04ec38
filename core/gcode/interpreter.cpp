#include "gcode/interpreter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "gcode/arc_geometry.h"
#include "gcode/gcode_tolerances.h"
#include "path/path_tolerances.h"

namespace lcnc::gcode {
namespace {

// Whether a move's feed is over its linear axes (RS274NGC: they move) or
// its rotary ones. Linear travel the planner takes as none is none here too,
// so the feed and the move's length (SegmentGeometry) measure the same.
bool moves_linear(double linear_mm) { return linear_mm > path::kMinSegmentLength; }

constexpr char kCentreLetter[3] = {'I', 'J', 'K'};  // centre word of X, Y, Z
constexpr std::size_t kQuoteMaxChars = 60;

// The G code ×10 of each motion mode, in MotionMode's order (None: G80).
constexpr std::array<int, 12> kMotionCode = {800, 0, 10, 20, 30, 730, 810, 820, 830, 850, 860, 890};

// The motion mode of a motion-group code ×10 (one the block parser took).
MotionMode motion_of(int g) {
  std::size_t i = 0;
  while (i + 1 < kMotionCode.size() && kMotionCode[i] != g) ++i;
  return static_cast<MotionMode>(i);
}

const char* plane_name(Plane p) {
  switch (p) {
    case Plane::ZX: return "ZX plane (G18)";
    case Plane::YZ: return "YZ plane (G19)";
    case Plane::XY:
    default: return "XY plane (G17)";
  }
}

}  // namespace

// A number for a message: up to 4 decimals, trailing zeros dropped.
std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

// A number for a bound or a value of any size: 6 significant digits.
std::string gnum(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

Interpreter::Interpreter(const MachineConfig& machine, const Pose& start, std::vector<double>& numbered)
    : machine_(machine), pos_(start), numbered_(numbered) {
  for (int a = 0; a < kAxisCount; ++a) {
    const AxisConfig& ax = machine.axes[a];
    if (ax.present && (ax.wrap || (machine.tcp.enabled && a < 3))) {
      untraveled_axes_ = static_cast<std::uint8_t>(untraveled_axes_ | (1u << a));
    }
    if (ax.present && ax.wrap) wrapping_axes_ = static_cast<std::uint8_t>(wrapping_axes_ | (1u << a));
  }
}

// --- messages -------------------------------------------------------------

bool Interpreter::fail_at(ErrorCode code, std::uint32_t byte_pos, std::string message) {
  fault_.code = code;
  fault_.byte_pos = byte_pos;
  fault_.message = std::move(message);
  return false;
}

bool Interpreter::fail(ErrorCode code, Span at, std::string message) {
  return fail_at(code, t_->byte_pos(at), std::move(message));
}

std::string Interpreter::quoted(Span s) const { return quote(t_->text(s)); }

// The line as written, trimmed (and shortened when long).
std::string Interpreter::quoted_block() const {
  std::string_view l = t_->original;
  while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
  while (!l.empty() && (l.back() == ' ' || l.back() == '\t')) l.remove_suffix(1);
  if (l.size() <= kQuoteMaxChars) return quote(l);
  std::string q = quote(l.substr(0, kQuoteMaxChars));
  q.insert(q.size() - 1, "...");
  return q;
}

const char* Interpreter::feed_unit() const noexcept { return modal_.inch ? "in/min" : "mm/min"; }

// --- the block ------------------------------------------------------------

bool Interpreter::execute(const Block& block, const LineText& text, std::uint32_t line, SegmentBuffer& out) {
  b_ = &block;
  t_ = &text;
  line_ = line;
  // (The rare steps are tested for here: a dense CAM line of G1 X Y Z F
  // pays for no call it does not need.)
  const int non_modal = block.code(GGroup::NonModal);
  if (!resolve_motion()) return false;
  if (comp_side_ != 0 && !check_comp_conflicts()) return false;
  if ((block.letters & kDataLetters) != 0 && !check_word_use()) return false;
  if (!set_feed_and_power()) return false;                                    // G93/G94, F, S, M3-M5, M7-M9
  if ((block.has('T') || block.m_tool >= 0) && !change_tool()) return false;  // T, M6, M61
  if (block.m_io >= 0 && !(block.m_io == 66 ? wait_input(out) : set_outputs())) return false;  // M62 … M68
  if (block.m_override >= 0 && !set_override_switches()) return false;                         // M48 … M53
  if (block.m_context >= 0 && !run_context()) return false;                        // M70 M71 M72 M73
  if (non_modal == 40 && !dwell(out)) return false;                                // G4
  if (block.code(GGroup::CutterComp) >= 0 && !set_cutter_comp(out)) return false;  // G40 G41 G42
  set_modes();  // plane, units, coordinate system
  if (block.code(GGroup::ToolLength) >= 0 && !set_tool_length()) return false;  // G43 … G49
  if (!set_path_control()) return false;                                        // G61 G61.1 G64
  if (non_modal > 40 && non_modal != 530 && !run_non_modal(out)) return false;  // G10 G28 G30 G52 G92
  if (block_motion_ != MotionMode::None && !move(out)) return false;
  if (block.m_stop >= 0 && comp_active() && !comp_first_move_) {
    // a stop lets the moves compensation holds go as they stand (LinuxCNC)
    if (!comp_move_endpoint_and_flush(pos_[comp_a_], pos_[comp_b_], out) || !comp_dequeue(out)) {
      return false;
    }
  }
  if (block.m_stop == 2 || block.m_stop == 30) {  // M2 M30: back in G54, G40 (LinuxCNC)
    ended_ = true;
    select_coord_system(0);
    comp_side_ = 0;
    comp_first_move_ = true;
  } else if (block.m_stop >= 0 && (block.m_stop != 1 || machine_.optional_stop)) {
    return pause(out);  // M0 M60, M1 with the optional stop on
  }
  return true;
}

// A new motion mode ends a canned cycle's sticky words (another mode needs
// R and Z again) and, unless a cycle, the cycle series (its initial Z).
void Interpreter::set_motion_mode(MotionMode m) {
  if (m != motion_) cycle_sticky_ = false;
  if (!is_cycle(m)) cycle_series_ = false;
  motion_ = m;
}

// The motion this block runs: its G0..G3, or the modal one when it has axis
// words only (LinuxCNC enhance_block).
bool Interpreter::resolve_motion() {
  const Block& b = *b_;
  block_motion_ = MotionMode::None;
  const int g = b.code(GGroup::Motion);
  // G10 G28 G30 G52 G92 and G43.1 take the block's axis words as their data:
  // no motion mode uses them then (LinuxCNC: two codes may not both).
  const int nm = b.code(GGroup::NonModal);
  const int tl = b.code(GGroup::ToolLength);
  const bool axis_words_used =
      (nm > 40 || tl >= 0) && (nm == 100 || nm == 280 || nm == 300 || nm == 520 || nm == 920 || tl == 431);
  if (b.polar != 0) {
    if (b.has('X') || b.has('Y')) {
      return fail(ErrorCode::GcodeSyntax, b.polar_word,
                  "found " + quoted(b.polar_word) + " with " + (b.has('X') ? "X" : "Y") +
                      "; expected polar words (@ radius, ^ angle) in place of X and Y, not with "
                      "them");
    }
    if (axis_words_used || nm == 530) {
      return fail(ErrorCode::GcodeSyntax, b.polar_word,
                  "found " + quoted(b.polar_word) + " with " +
                      quoted(b.code_word(nm == 530 || nm > 40 ? GGroup::NonModal : GGroup::ToolLength)) +
                      "; expected polar words only on moves in the program's coordinates");
    }
  }
  if (axis_words_used) {
    if (g >= 0 && g != 800 && b.axis_mask != 0) {
      const Span at =
          b.code(GGroup::ToolLength) == 431 ? b.code_word(GGroup::ToolLength) : b.code_word(GGroup::NonModal);
      return fail(ErrorCode::GcodeModalConflict, b.code_word(GGroup::Motion),
                  "found " + quoted(b.code_word(GGroup::Motion)) + " and " + quoted(at) +
                      " in one block, both using its axis words; expected them on two lines");
    }
    if (g >= 0) set_motion_mode(motion_of(g));
    return true;
  }
  if (g == 800) {
    // G80: no motion mode (LinuxCNC: axis words with it are an error)
    set_motion_mode(MotionMode::None);
    if (b.axis_mask != 0) {
      return fail(ErrorCode::GcodeSyntax, b.first_axis_word,
                  "found " + quoted(b.first_axis_word) +
                      " with G80 (cancel motion mode); expected no axis words with G80, or "
                      "G0/G1/G2/G3 instead of it");
    }
    return true;
  }
  if (g >= 0) {
    motion_word_ = b.code_word(GGroup::Motion);
    const MotionMode m = motion_of(g);
    set_motion_mode(m);
    // G0 / G1 alone only set the mode; G2 / G3 with no axis words are a full
    // circle at the current point (LinuxCNC 2.9), and need a centre
    if (b.axis_mask == 0 && m != MotionMode::ArcCw && m != MotionMode::ArcCcw) return true;
    block_motion_ = m;
    return true;
  }
  if (b.axis_mask != 0) {
    motion_word_ = b.first_axis_word;
    if (motion_ == MotionMode::None) {
      return fail(ErrorCode::GcodeNoMotionMode, b.first_axis_word,
                  "found " + quoted(b.first_axis_word) +
                      " with no motion mode in effect; expected G0, G1, G2 or G3 on this or "
                      "an earlier line");
    }
    block_motion_ = motion_;
  }
  return true;
}

// Words that only some codes use: refuse them where nothing uses them
// (LinuxCNC check_other_codes), naming what would.
bool Interpreter::check_word_use() {
  const Block& b = *b_;
  const bool is_arc = block_motion_ == MotionMode::ArcCw || block_motion_ == MotionMode::ArcCcw;
  const bool has_g4 = b.code(GGroup::NonModal) == 40;
  const bool has_g10 = b.code(GGroup::NonModal) == 100;
  const bool has_g64 = b.code(GGroup::PathControl) == 640;
  const bool has_m61 = b.m_tool == 61;
  const int tl = b.code(GGroup::ToolLength);
  const bool cycle = is_cycle(block_motion_);
  const bool dwell_cycle = block_motion_ == MotionMode::Cycle82 || block_motion_ == MotionMode::Cycle86 ||
                           block_motion_ == MotionMode::Cycle89;
  const bool peck_cycle = block_motion_ == MotionMode::Cycle83 || block_motion_ == MotionMode::Cycle73;
  if (b.has('P') && !has_g4 && !has_g64 && !is_arc && !has_g10 && !dwell_cycle &&
      !(b.m_io >= 62 && b.m_io <= 66) && b.m_override < 50) {
    return fail(ErrorCode::GcodeUnsupported, b.span('P'),
                "found " + quoted(b.span('P')) +
                    " with no G4, G10, G64, G2, G3, G82, G89, M50–M53 or M62–M66 to use it; P "
                    "is supported only as G4/G82/G89 dwell seconds, G10 system or tool, G64 "
                    "blend tolerance, G2/G3 turns, the M50–M53 switch and the M62–M66 I/O");
  }
  const bool analog_io = b.m_io == 67 || b.m_io == 68;
  const bool wait_io = b.m_io == 66;
  if (b.has('Q') && !has_g64 && !has_m61 && !peck_cycle && !analog_io && !wait_io) {
    return fail(ErrorCode::GcodeUnsupported, b.span('Q'),
                "found " + quoted(b.span('Q')) +
                    " with no G64, M61, G73, G83, M67 or M68; Q is supported only as the G64 "
                    "naive-CAM tolerance, M61's tool, the G73/G83 peck depth and the M67/M68 "
                    "analog value");
  }
  if (b.has('E') && !analog_io && !wait_io) {
    return fail(ErrorCode::GcodeUnsupported, b.span('E'),
                "found " + quoted(b.span('E')) +
                    " with no M67 or M68 to use it; expected E only as the analog output of "
                    "M67/M68 (and no exponents in numbers: 1e3 is 1 and E3)");
  }
  if (b.has('H') && tl != 430 && tl != 432) {
    return fail(ErrorCode::GcodeUnsupported, b.span('H'),
                "found " + quoted(b.span('H')) +
                    " with no G43 or G43.2 to use it; expected H only as the tool whose offset "
                    "G43 H / G43.2 H applies");
  }
  if (b.has('D') && b.code(GGroup::CutterComp) <= 400) {
    return fail(ErrorCode::GcodeUnsupported, b.span('D'),
                "found " + quoted(b.span('D')) +
                    " with no G41, G42, G41.1 or G42.1 to use it; expected D only as the tool "
                    "(G41/G42 D) or the diameter (G41.1/G42.1 D) of cutter compensation");
  }
  if (b.has('L') && !has_g10 && !cycle && b.m_io != 66) {
    return fail(ErrorCode::GcodeUnsupported, b.span('L'),
                "found " + quoted(b.span('L')) +
                    " with no G10 or canned cycle to use it; expected L only on G10 and as a "
                    "canned cycle's repeats");
  }
  if (!is_arc) {
    for (char l : {'I', 'J', 'K', 'R'}) {
      if (l == 'R' && (has_g10 || cycle)) continue;
      if (b.has(l)) {
        return fail(ErrorCode::GcodeUnsupported, b.span(l),
                    "found " + quoted(b.span(l)) +
                        " with no G2 or G3 arc move in the block; I J K R are supported only "
                        "on arcs");
      }
    }
  }
  return true;
}

bool Interpreter::set_feed_and_power() {
  const Block& b = *b_;
  // Feed mode (G93/G94): a change forgets the F in effect.
  const int fm = b.code(GGroup::FeedMode);
  if (fm >= 0) {
    const bool inverse = fm == 930;
    if (inverse != modal_.inverse_time) {
      modal_.inverse_time = inverse;
      modal_.feed_set = false;
      modal_.feed_mm_min = modal_.feed_raw = 0.0;
    }
  }
  // F, in the units in effect after this block's G20/G21.
  block_has_f_ = false;
  if (b.has('F')) {
    const double f = b['F'];
    if (f < 0.0) {
      return fail(ErrorCode::GcodeBadValue, b.span('F'),
                  "found " + quoted(b.span('F')) + "; expected a feed rate F >= 0");
    }
    const int units = b.code(GGroup::Units);
    const bool inch = units >= 0 ? units == 200 : modal_.inch;
    if (modal_.inverse_time) {
      block_has_f_ = true;
      block_f_ = f;
    } else {
      // F0 stays "no feed" (refused on a feed move); others must be a speed.
      const double scale = inch ? kMmPerInch : 1.0;
      const double f_mm_min = f * scale;
      if (f > 0.0 && (f_mm_min < kMinFeedPerMin || f_mm_min > kMaxFeedPerMin)) {
        const char* unit = inch ? "in/min" : "mm/min";
        return fail(ErrorCode::GcodeBadValue, b.span('F'),
                    "found " + quoted(b.span('F')) + " (" + gnum(f) + " " + unit +
                        "); expected a feed rate F from " + gnum(kMinFeedPerMin / scale) + " to " +
                        gnum(kMaxFeedPerMin / scale) + " " + unit +
                        " (or deg/min for rotary-only moves): slower never finishes a move, "
                        "faster is no feed");
      }
      modal_.feed_set = true;
      modal_.feed_raw = f;
      modal_.feed_mm_min = f * (inch ? kMmPerInch : 1.0);
    }
  }
  // S: power as a share of s_max.
  if (b.has('S')) {
    const double s = b['S'];
    const double s_max = machine_.laser.s_max;
    if (s < 0.0 || s > s_max) {
      return fail(ErrorCode::GcodeBadValue, b.span('S'),
                  "found " + quoted(b.span('S')) + "; expected S from 0 to " + num(s_max) +
                      " (laser.s_max, which means 100 % power)");
    }
    modal_.power_pct = s_max > 0.0 ? 100.0 * s / s_max : 0.0;
  }
  switch (b.m_laser) {
    case 3: modal_.laser = LaserMode::Constant; break;
    case 4: modal_.laser = LaserMode::Dynamic; break;
    case 5: modal_.laser = LaserMode::Off; break;
    default: break;
  }
  if (b.m7) modal_.mist = true;
  if (b.m8) modal_.flood = true;
  if (b.m9) modal_.mist = modal_.flood = false;
  return true;
}

bool Interpreter::dwell(SegmentBuffer& out) {
  const Block& b = *b_;
  if (b.code(GGroup::NonModal) != 40) return true;
  if (!b.has('P')) {
    return fail(ErrorCode::GcodeMissingWord, b.code_word(GGroup::NonModal),
                "found " + quoted_block() + " with no P word; expected G4 P<seconds>, e.g. G4 P0.5");
  }
  const double p = b['P'];
  if (p < 0.0) {
    return fail(ErrorCode::GcodeBadValue, b.span('P'),
                "found " + quoted(b.span('P')) + " on G4; expected a dwell time P >= 0 seconds");
  }
  if (p > kMaxBlockSeconds) {
    return fail(ErrorCode::GcodeBadValue, b.span('P'),
                "found " + quoted(b.span('P')) + " on G4 (" + gnum(p / 3600.0) +
                    " hours); expected a dwell time P from 0 to " + gnum(kMaxBlockSeconds) +
                    " seconds (one day)");
  }
  Segment& s = push_segment(out);  // after the moves compensation holds, if any
  fill_modal(s);
  s.kind = MotionKind::Dwell;
  s.start = pos_;
  s.end = pos_;
  s.dwell_s = p;  // the laser keeps its mode: M3 + G4 is percussion drilling
  return true;
}

void Interpreter::set_modes() {
  const Block& b = *b_;
  switch (b.code(GGroup::Plane)) {
    case 170: modal_.plane = Plane::XY; break;
    case 180: modal_.plane = Plane::ZX; break;
    case 190: modal_.plane = Plane::YZ; break;
    default: break;
  }
  const int units = b.code(GGroup::Units);
  if (units >= 0) modal_.inch = units == 200;
  const int wcs = b.code(GGroup::CoordSystem);
  if (wcs >= 0) select_coord_system(wcs < 590 ? (wcs - 540) / 10 : 5 + (wcs - 590));
  const int dist = b.code(GGroup::Distance);
  if (dist >= 0) modal_.absolute = dist == 900;
  const int arc_dist = b.code(GGroup::ArcDistance);
  if (arc_dist >= 0) modal_.arc_absolute = arc_dist == 901;
  const int retract = b.code(GGroup::RetractMode);
  if (retract >= 0) modal_.retract_old_z = retract == 980;
}

// " mm", or " in (N mm)" in G20, after the largest path tolerance.
std::string Interpreter::tolerance_unit() const {
  return modal_.inch ? " in (" + gnum(kMaxPathToleranceMm) + " mm)" : std::string(" mm");
}

bool Interpreter::set_path_control() {
  const Block& b = *b_;
  switch (b.code(GGroup::PathControl)) {
    case 610:
      modal_.path_mode = PathMode::ExactPath;
      modal_.blend_tolerance_mm = modal_.naive_cam_tolerance_mm = 0.0;
      return true;
    case 611:
      modal_.path_mode = PathMode::ExactStop;
      modal_.blend_tolerance_mm = modal_.naive_cam_tolerance_mm = 0.0;
      return true;
    case 640: break;
    default: return true;
  }
  // G64 [P blend tolerance] [Q naive-CAM tolerance]: no P -> the machine's
  // path tolerance; no Q -> no line merging. (LinuxCNC merges with Q = P by
  // default; our blends handle dense CAM chords as they are and keep all of P
  // for the corners, which is faster at the same tolerance — see the planner
  // benchmark. Merging is there for who asks for it with Q.)
  double p_mm = machine_.path_tolerance_mm;
  if (b.has('P')) {
    if (b['P'] < 0.0) {
      return fail(ErrorCode::GcodeBadValue, b.span('P'),
                  "found " + quoted(b.span('P')) + " on G64; expected a blend tolerance P >= 0");
    }
    p_mm = b['P'] * length_scale();
    if (p_mm > kMaxPathToleranceMm) {
      return fail(ErrorCode::GcodeBadValue, b.span('P'),
                  "found " + quoted(b.span('P')) +
                      " on G64; expected a blend tolerance P from "
                      "0 to " +
                      gnum(kMaxPathToleranceMm / length_scale()) + tolerance_unit());
    }
  }
  double q_mm = 0.0;
  if (b.has('Q')) {
    if (b['Q'] < 0.0) {
      return fail(ErrorCode::GcodeBadValue, b.span('Q'),
                  "found " + quoted(b.span('Q')) + " on G64; expected a naive-CAM tolerance Q >= 0");
    }
    q_mm = b['Q'] * length_scale();
    if (q_mm > kMaxPathToleranceMm) {
      return fail(ErrorCode::GcodeBadValue, b.span('Q'),
                  "found " + quoted(b.span('Q')) +
                      " on G64; expected a naive-CAM tolerance Q "
                      "from 0 to " +
                      gnum(kMaxPathToleranceMm / length_scale()) + tolerance_unit());
    }
  }
  modal_.path_mode = PathMode::Blend;
  modal_.blend_tolerance_mm = p_mm;
  modal_.naive_cam_tolerance_mm = q_mm;
  return true;
}

// --- motion ---------------------------------------------------------------

// Where the RT holds the job at rest, the beam off (M0, M66): a dwell of
// two periods, so a period's sample falls inside it whatever the phase.
Segment& Interpreter::hold_segment(SegmentBuffer& out) {
  Segment& s = push_segment(out);
  fill_modal(s);
  s.kind = MotionKind::Dwell;
  s.start = pos_;
  s.end = pos_;
  s.dwell_s = 2.0 * machine_.period_s();
  s.laser = LaserMode::Off;
  return s;
}

// M0 (M1, M60): the machine stops here until the operator resumes.
bool Interpreter::pause(SegmentBuffer& out) {
  hold_segment(out).pause = true;
  return true;
}

void Interpreter::fill_modal(Segment& s) const {
  s = Segment{};
  s.digital_out = digital_out_;
  s.analog_out = analog_out_;
  s.feed_control = modal_.feed_control;
  s.plane = modal_.plane;
  s.path_mode = modal_.path_mode;
  s.blend_tolerance_mm = modal_.blend_tolerance_mm;
  s.naive_cam_tolerance_mm = modal_.naive_cam_tolerance_mm;
  s.laser = modal_.laser;
  s.power_pct = modal_.power_pct;
  s.mist = modal_.mist;
  s.flood = modal_.flood;
  s.line = line_;
}

bool Interpreter::check_feed() {
  if (modal_.inverse_time) {
    if (!block_has_f_) {
      return fail(ErrorCode::GcodeNoFeed, motion_word_,
                  "found " + quoted_block() +
                      " in inverse-time mode (G93) with no F word; expected an F word on "
                      "every G1/G2/G3 line (F = 1 / minutes the move takes)");
    }
    if (block_f_ <= 0.0) {
      return fail(ErrorCode::GcodeNoFeed, motion_word_,
                  "found " + quoted_block() +
                      " in inverse-time mode (G93) with F0; expected a positive F word (F = "
                      "1 / minutes the move takes)");
    }
    if (block_f_ < kMinInverseTimeF || block_f_ > kMaxFeedPerMin) {
      return fail(ErrorCode::GcodeBadValue, b_->span('F'),
                  "found " + quoted(b_->span('F')) + " in inverse-time mode (G93): a move of " +
                      gnum(1.0 / block_f_) + " minutes; expected F from " + gnum(kMinInverseTimeF) + " to " +
                      gnum(kMaxFeedPerMin) + " (F = 1 / minutes the move takes: at most " +
                      gnum(kMaxBlockSeconds / 60.0) + " minutes, one day)");
    }
    return true;
  }
  if (!modal_.feed_set) {
    return fail(ErrorCode::GcodeNoFeed, motion_word_,
                "found " + quoted_block() + " with no feed rate in effect; expected an F word (feed in " +
                    feed_unit() + ") before or on this line");
  }
  if (modal_.feed_raw <= 0.0) {
    return fail(ErrorCode::GcodeNoFeed, motion_word_,
                "found " + quoted_block() +
                    " with feed rate F0 in effect; expected a positive F "
                    "word (feed in " +
                    feed_unit() + ") before or on this line");
  }
  return true;
}

// G94: the move at its feed must end within kMaxBlockSeconds (G93's F bound
// says the same for inverse time). A product, not a quotient, on the path
// every feed move takes; the message is built apart.
bool Interpreter::check_duration(double linear_mm, double rotary_deg) {
  if (modal_.inverse_time) return true;
  constexpr double kMaxMinutes = kMaxBlockSeconds / 60.0;
  if (moves_linear(linear_mm) ? linear_mm <= modal_.feed_mm_min * kMaxMinutes
                              : rotary_deg <= modal_.feed_raw * kMaxMinutes) {
    return true;
  }
  return fail_duration(linear_mm, rotary_deg);
}

bool Interpreter::fail_duration(double linear_mm, double rotary_deg) {
  const bool rotary_only = !moves_linear(linear_mm);
  const double length = rotary_only ? rotary_deg : linear_mm;
  const double minutes = length / (rotary_only ? modal_.feed_raw : modal_.feed_mm_min);
  const double scale = rotary_only ? 1.0 : length_scale();
  const char* unit = rotary_only ? "deg" : (modal_.inch ? "in" : "mm");
  return fail(ErrorCode::GcodeBadValue, b_->has('F') ? b_->span('F') : motion_word_,
              "found " + quoted_block() + ": a move of " + gnum(length / scale) + " " + unit + " at F" +
                  gnum(modal_.feed_raw) + " takes " + gnum(minutes) +
                  " minutes; expected a move of at most " + gnum(kMaxBlockSeconds / 60.0) +
                  " minutes (one day): a higher F");
}

// Axes no travel check covers (continuous rotary axes; X Y Z under
// tool-centre-point control, checked on the joints later) must still stay
// within sane magnitudes.
bool Interpreter::check_magnitude(const Pose& end) {
  const unsigned mask = b_->axis_mask & untraveled_axes_;
  for (int a = 0; a < kAxisCount; ++a) {
    if (((mask >> a) & 1u) == 0) continue;
    const double bound = a < 3 ? kMaxLinearPositionMm : kMaxRotaryPositionDeg;
    if (std::fabs(end[a]) <= bound) continue;
    const char l = kAxisLetters[a];
    const char* unit = a < 3 ? "mm" : "deg";
    return fail(ErrorCode::GcodeBadValue, b_->span(l),
                "found " + quoted(b_->span(l)) + " moving " + std::string(1, l) + " to " + gnum(end[a]) +
                    " " + unit + " in machine coordinates; expected |" + std::string(1, l) +
                    "| <= " + gnum(bound) + " " + unit);
  }
  return true;
}

void Interpreter::set_segment_feed(Segment& s, double linear_mm, double rotary_deg) const {
  if (modal_.inverse_time) {
    s.duration_s = 60.0 / block_f_;
    s.feed_mm_s = (moves_linear(linear_mm) ? linear_mm : rotary_deg) / s.duration_s;
  } else {
    s.feed_mm_s = (moves_linear(linear_mm) ? modal_.feed_mm_min : modal_.feed_raw) / 60.0;
  }
}

// Every present axis without wrap must stay in [min, max] over [lo, hi].
// Under tool-centre-point control X Y Z are the tool tip, not the joints:
// their travel is checked on the joints the program becomes
// (plan/program_source.h: check_job_program).
bool Interpreter::check_travel(const Pose& lo, const Pose& hi, const Pose& end) {
  for (int a = 0; a < kAxisCount; ++a) {
    const AxisConfig& ax = machine_.axes[a];
    if (!ax.present || ax.wrap || (machine_.tcp.enabled && a < 3)) continue;
    double bad = 0.0;
    if (lo[a] < ax.min - kTravelTolMm) {
      bad = lo[a];
    } else if (hi[a] > ax.max + kTravelTolMm) {
      bad = hi[a];
    } else {
      continue;
    }
    const char l = kAxisLetters[a];
    const char* unit = a < 3 ? "mm" : "deg";
    const bool at_end = bad == end[a];
    // Point at the axis word when its end point is the problem, else at the move.
    const Span at = (at_end && b_->has(l)) ? b_->span(l) : motion_word_;
    return fail(ErrorCode::GcodeBeyondTravel, at,
                "found " + quoted_block() + (at_end ? " moving " : " passing ") + std::string(1, l) + " to " +
                    num(bad) + " " + unit + (at_end ? "" : " (arc extreme)") +
                    " in machine coordinates, beyond the " + std::string(1, l) + " travel [" + num(ax.min) +
                    ", " + num(ax.max) + "] " + unit + "; expected positions within the travel");
  }
  return true;
}

bool Interpreter::move(SegmentBuffer& out) {
  const Block& b = *b_;
  if (is_cycle(block_motion_)) return canned_cycle(out);
  // G53: this block's axis words are machine coordinates (G0/G1, G90 only)
  const bool machine_coords = b.code(GGroup::NonModal) == 530;
  if (machine_coords) {
    if (block_motion_ != MotionMode::Rapid && block_motion_ != MotionMode::Linear) {
      return fail(ErrorCode::GcodeSyntax, b.code_word(GGroup::NonModal),
                  "found " + quoted_block() + ": G53 with an arc; expected G53 with G0 or G1");
    }
    if (!modal_.absolute) {
      return fail(ErrorCode::GcodeSyntax, b.code_word(GGroup::NonModal),
                  "found " + quoted_block() +
                      " in G91: G53 names machine positions; expected "
                      "G53 in G90 (absolute)");
    }
  }
  const Pose offset = machine_coords ? Pose::Zero() : offsets_;
  // Under cutter compensation (and for the move after G40) a move starts,
  // as programmed, from the programmed point, not from the tool beside it.
  Pose from = pos_;
  if ((comp_active() && !comp_first_move_) || comp_exited_) {
    from[comp_a_] = programmed_[comp_a_];
    from[comp_b_] = programmed_[comp_b_];
  }
  Pose end = from;
  for (int a = b.polar != 0 ? 2 : 0; a < kAxisCount; ++a) {
    if (((b.axis_mask >> a) & 1u) == 0) continue;
    const double v = axis_value(a);
    end[a] = modal_.absolute ? v + offset[a] : from[a] + v;
  }
  if (b.polar != 0 && !polar_target(from, end)) return false;
  if ((b.axis_mask & untraveled_axes_) != 0 && !check_magnitude(end)) return false;
  if (modal_.absolute && (b.axis_mask & wrapping_axes_) != 0) {
    // G90 on a continuous rotary axis names a position modulo 360: the axis
    // turns the shorter way to it (+180 on a tie); G91 turns by what it says.
    for (int a = 3; a < kAxisCount; ++a) {
      if (((b.axis_mask & wrapping_axes_) >> a & 1u) == 0) continue;
      double d = std::remainder(end[a] - pos_[a], 360.0);
      if (d <= -180.0) d += 360.0;
      end[a] = pos_[a] + d;
    }
    if (!check_magnitude(end)) return false;
  }
  const bool is_arc = block_motion_ == MotionMode::ArcCw || block_motion_ == MotionMode::ArcCcw;
  if (comp_exited_ && is_arc) {
    return fail(ErrorCode::GcodeCutterComp, motion_word_,
                "found " + quoted_block() +
                    " just after G40: the move that leaves the "
                    "compensated path must be straight; expected G0 or G1 first");
  }
  if (comp_active()) return is_arc ? comp_arc(end, out) : comp_straight(end, out);
  if (is_arc) return arc(end, out);
  if (block_motion_ == MotionMode::Rapid) return rapid_to(end, out);
  return check_feed() && line_to(end, out);
}

// A G0 from where the machine is to `end`: travel checked; nothing for the
// planner when it does not move.
bool Interpreter::rapid_to(const Pose& end, SegmentBuffer& out) {
  comp_exited_ = false;
  if (!check_travel(end, end, end)) return false;
  if (end == pos_) return true;
  take_synced_outputs();
  Segment& s = push_segment(out);
  fill_modal(s);
  s.kind = MotionKind::Rapid;
  s.laser = LaserMode::Off;
  s.start = pos_;
  s.end = end;
  pos_ = end;
  return true;
}

// The same for a G1 at the feed in effect, its time bounded too.
bool Interpreter::line_to(const Pose& end, SegmentBuffer& out) {
  comp_exited_ = false;
  if (!check_travel(end, end, end)) return false;
  if (end == pos_) return true;
  const double linear_mm = (end.head<3>() - pos_.head<3>()).norm();
  const double rotary_deg = (end.tail<3>() - pos_.tail<3>()).norm();
  if (!check_duration(linear_mm, rotary_deg)) return false;
  take_synced_outputs();
  Segment& s = push_segment(out);
  fill_modal(s);
  s.kind = MotionKind::Linear;
  s.start = pos_;
  s.end = end;
  set_segment_feed(s, linear_mm, rotary_deg);
  pos_ = end;
  return true;
}

// G2/G3 in the current plane. Centre from I J K (incremental from the start in
// G91.1, program coordinates in G90.1) or from R (LinuxCNC arc_data_r: the
// centre lies off the chord's midpoint by sqrt(R² − (chord/2)²), to the right
// of the chord for G2 R>0 and G3 R<0, to the left otherwise; R<0 > 180°).
bool Interpreter::arc(const Pose& end_in, SegmentBuffer& out) {
  Pose end = end_in;
  Vec3 c;
  std::uint32_t extra_turns = 0;
  return arc_centre(pos_, end, c, extra_turns) &&
         arc_to(end, c, block_motion_ == MotionMode::ArcCw, extra_turns, out);
}

bool Interpreter::arc_centre(const Pose& from, Pose& end, Vec3& c, std::uint32_t& extra_turns) {
  const Block& b = *b_;
  const bool cw = block_motion_ == MotionMode::ArcCw;
  const auto [ia, ib, in] = arc_plane_axes(modal_.plane);
  const char la = kCentreLetter[ia];
  const char lb = kCentreLetter[ib];
  const char ln = kCentreLetter[in];
  if (b.has(ln)) {
    return fail(ErrorCode::GcodeSyntax, b.span(ln),
                "found " + quoted(b.span(ln)) + " on an arc in the " + plane_name(modal_.plane) +
                    "; expected " + std::string(1, la) + " and " + std::string(1, lb) + " for the centre");
  }
  const bool has_r = b.has('R');
  const bool has_ijk = b.has(la) || b.has(lb);
  if (has_r && has_ijk) {
    return fail(ErrorCode::GcodeSyntax, b.span('R'),
                "found " + quoted(b.span('R')) + " together with " + std::string(1, la) + "/" +
                    std::string(1, lb) + " words; expected either R or " + std::string(1, la) + " " +
                    std::string(1, lb) + " for the arc, not both");
  }
  if (!has_r && !has_ijk) {
    return fail(ErrorCode::GcodeArcMissingCenter, motion_word_,
                "found " + quoted_block() + " with no centre or radius; expected " + std::string(1, la) +
                    " " + std::string(1, lb) + " (centre, " + plane_name(modal_.plane) + ") or R (radius)");
  }
  if (!check_feed()) return false;

  extra_turns = 0;
  if (b.has('P')) {
    const double p = b['P'];
    const double turns = std::round(p);
    // (bounded before the conversion: a P of 1e18 is no number of turns)
    if (std::fabs(p - turns) > kIntegerTol || turns < 1.0 || turns > kMaxArcTurns) {
      return fail(ErrorCode::GcodeBadValue, b.span('P'),
                  "found " + quoted(b.span('P')) +
                      " on an arc; expected P as a whole number of turns from 1 to " +
                      std::to_string(static_cast<int>(kMaxArcTurns)));
    }
    extra_turns = static_cast<std::uint32_t>(turns) - 1;
  }

  const double sa = from[ia];
  const double sb = from[ib];
  const double chord = std::hypot(end[ia] - sa, end[ib] - sb);
  const bool same_point = chord <= kSamePointMm;
  c = linear_part(from);  // the normal component stays the start's
  if (has_r) {
    const Span rw = b.span('R');
    if (same_point) {
      return fail(ErrorCode::GcodeArcRadius, rw,
                  "found " + quoted_block() +
                      " ending where it starts: an R-form arc cannot be a full circle (its "
                      "centre is undefined); expected I J K centre words for a full circle");
    }
    const double r = b['R'] * length_scale();
    const double abs_r = std::fabs(r);
    if (chord / 2.0 - abs_r > kArcReachMm) {
      return fail(ErrorCode::GcodeArcRadius, rw,
                  "found " + quoted(rw) + " but the end point is " + num(chord) +
                      " mm from the start: radius " + num(abs_r) + " mm reaches at most " + num(2.0 * abs_r) +
                      " mm; expected |R| >= " + num(chord / 2.0) + " mm, half the chord (less " +
                      gnum(kArcReachMm) + " mm: then a half circle through both ends)");
    }
    const double half = chord / 2.0;
    // within 1e-12 of a half circle it is one (LinuxCNC's TINY): R² − half²
    // of two roundings apart would put the centre 1e-8 R off the chord
    const double h = half / abs_r < 1.0 - 1e-12 ? std::sqrt(abs_r * abs_r - half * half) : 0.0;
    const double theta = std::atan2(end[ib] - sb, end[ia] - sa);
    const double turn = ((cw && r > 0.0) || (!cw && r < 0.0)) ? theta - std::numbers::pi / 2.0
                                                              : theta + std::numbers::pi / 2.0;
    c[ia] = (sa + end[ia]) / 2.0 + h * std::cos(turn);
    c[ib] = (sb + end[ib]) / 2.0 + h * std::sin(turn);
  } else {
    const Pose& offset = offsets_;
    const double ci = b.has(la) ? b[la] * length_scale() : 0.0;
    const double cj = b.has(lb) ? b[lb] * length_scale() : 0.0;
    c[ia] = modal_.arc_absolute ? ci + offset[ia] : sa + ci;
    c[ib] = modal_.arc_absolute ? cj + offset[ib] : sb + cj;
    if (same_point) {  // a full circle: make end == start exact for the planner
      end[ia] = sa;
      end[ib] = sb;
    }
    const Span at = b.has(la) ? b.span(la) : b.span(lb);
    const double r_start = std::hypot(sa - c[ia], sb - c[ib]);
    const double r_end = std::hypot(end[ia] - c[ia], end[ib] - c[ib]);
    if (r_start < kArcMinRadiusMm || r_end < kArcMinRadiusMm) {
      return fail(ErrorCode::GcodeArcRadius, at,
                  "found " + quoted_block() + " whose centre is at its " +
                      (r_start < kArcMinRadiusMm ? "start" : "end") + " point (radius 0); expected " +
                      std::string(1, la) + " " + std::string(1, lb) + " placing the centre away from both");
    }
    const double diff = std::fabs(r_end - r_start);
    const double rel = diff / std::max(r_start, r_end);
    const bool inch = length_scale() != 1.0;
    const double tol = inch ? kArcRadiusAbsIn * kMmPerInch : kArcRadiusAbsMm;
    if (diff > kArcRadiusHardFactor * tol || (diff > tol && rel > kArcRadiusRel)) {
      const double unit = length_scale();
      const char* name = inch ? " in" : " mm";
      return fail(ErrorCode::GcodeArcRadius, at,
                  "found " + quoted_block() + " with radius " + num(r_start / unit) + name +
                      " to the start and " + num(r_end / unit) + name + " to the end (they differ by " +
                      num(diff / unit) + name + "); expected equal radii, within " + gnum(tol / unit) + name +
                      " or " + num(kArcRadiusRel * 100.0) + " % (up to " +
                      gnum(kArcRadiusHardFactor * tol / unit) + name + ")");
    }
  }

  return true;
}

bool Interpreter::arc_to(const Pose& end, const Vec3& c, bool cw, std::uint32_t extra_turns,
                         SegmentBuffer& out) {
  const Block& b = *b_;
  const auto axes = arc_plane_axes(modal_.plane);
  comp_exited_ = false;
  take_synced_outputs();
  Segment& s = push_segment(out);
  fill_modal(s);
  s.kind = MotionKind::Arc;
  s.start = pos_;
  s.end = end;
  s.center = c;
  s.clockwise = cw;
  s.extra_turns = extra_turns;

  Vec3 lo3, hi3;
  arc_bounds(s, lo3, hi3);
  Pose lo = end.cwiseMin(pos_);
  Pose hi = end.cwiseMax(pos_);
  lo.head<3>() = lo3;
  hi.head<3>() = hi3;
  for (int a = 3; a < kAxisCount; ++a) lo[a] = hi[a] = end[a];  // rotary: end points only
  if (!check_travel(lo, hi, end)) return false;

  const double length_mm = arc_length_mm(s);
  if (length_mm > kMaxArcLengthMm) {
    return fail(ErrorCode::GcodeBadValue, b.has('P') ? b.span('P') : motion_word_,
                "found " + quoted_block() + ": an arc of " + gnum(length_mm) + " mm (radius " +
                    gnum(std::hypot(pos_[axes[0]] - c[axes[0]], pos_[axes[1]] - c[axes[1]])) + " mm" +
                    (extra_turns > 0 ? ", " + std::to_string(extra_turns + 1) + " turns" : "") +
                    "); expected an arc of at most " + gnum(kMaxArcLengthMm) +
                    " mm (1 km): fewer turns or a smaller radius");
  }
  const double rotary_deg = (end.tail<3>() - pos_.tail<3>()).norm();
  if (!check_duration(length_mm, rotary_deg)) return false;
  set_segment_feed(s, length_mm, rotary_deg);
  pos_ = end;
  return true;
}

// --- override switches (M48 … M53) ------------------------------------------

// M48 / M49: the feed (and power) overrides on / off; M50 P1 / P0: the feed
// override on / off; M51 P1 / P0: the speed override (LaserCNC has no laser
// power override: kept for #<_speed_override> and M70); M52 P1 / P0:
// adaptive feed, the machine's adaptive-feed input (0 … 1) scales the feed;
// M53 P1 / P0: the machine's feed-hold input stops the motion or not. A
// missing P is P1, as LinuxCNC. They act on the moves after them, and the
// RT applies them per period (rt/feed_override.h). Refused under cutter
// compensation, as in LinuxCNC.
bool Interpreter::set_override_switches() {
  const Block& b = *b_;
  const int code = b.m_override;
  if (comp_side_ != 0) {
    return fail(ErrorCode::GcodeModalConflict, b.m_override_word,
                "found " + quoted(b.m_override_word) +
                    " with cutter compensation on; expected G40 first (LinuxCNC neither "
                    "switches overrides under compensation)");
  }
  bool on = true;
  if (code >= 50 && b.has('P')) {
    const double p = b['P'];
    if (p != std::floor(p) || p < 0.0) {
      return fail(ErrorCode::GcodeBadValue, b.span('P'),
                  "found " + quoted(b.span('P')) + "; expected P0 (off) or P1 (on)");
    }
    on = p != 0.0;
  }
  auto set = [&](std::uint8_t bit, bool value) {
    modal_.feed_control =
        static_cast<std::uint8_t>(value ? modal_.feed_control | bit : modal_.feed_control & ~bit);
  };
  switch (code) {
    case 48:
    case 49:
      set(kFeedOverrideOff, code == 49);
      modal_.speed_override = code == 48;
      break;
    case 50: set(kFeedOverrideOff, !on); break;
    case 51: modal_.speed_override = on; break;
    case 52: set(kAdaptiveFeed, on); break;
    case 53: set(kFeedHoldInputOff, !on); break;
    default: break;
  }
  return true;
}

// --- outputs (M62 … M68) ---------------------------------------------------

// M62 P n / M63 P n: digital output n on / off with the next move (its
// first period); M64 / M65: from here on (the next segment of any kind,
// a dwell too). M67 E n Q v: analog output n to v with the next move; M68:
// from here on. (LinuxCNC's M64/M68 act when its read-ahead reaches them;
// here they act where they stand in the program, after the motion before.)
bool Interpreter::set_outputs() {
  const Block& b = *b_;
  const int code = b.m_io;
  const bool analog = code >= 67;
  const char letter = analog ? 'E' : 'P';
  const int count = analog ? kAnalogOutputs : kDigitalOutputs;
  if (!b.has(letter)) {
    return fail(ErrorCode::GcodeMissingWord, b.m_io_word,
                "found " + quoted(b.m_io_word) + " with no " + std::string(1, letter) + " word; expected " +
                    quoted(b.m_io_word) + " " + std::string(1, letter) + "<output 0 … " +
                    std::to_string(count - 1) + ">" + (analog ? " Q<value>" : ""));
  }
  const double v = b[letter];
  if (v != std::floor(v) || v < 0.0 || v >= count) {
    return fail(ErrorCode::GcodeBadValue, b.span(letter),
                "found " + quoted(b.span(letter)) + "; expected an output from 0 to " +
                    std::to_string(count - 1) + " (the machine's " + std::to_string(count) + " " +
                    (analog ? "analog" : "digital") + " outputs)");
  }
  const int n = static_cast<int>(v);
  if (analog) {
    if (!b.has('Q')) {
      return fail(ErrorCode::GcodeMissingWord, b.m_io_word,
                  "found " + quoted(b.m_io_word) + " with no Q word; expected " + quoted(b.m_io_word) +
                      " E<output> Q<value>");
    }
    const float q = static_cast<float>(b['Q']);
    if (!std::isfinite(q)) {
      return fail(ErrorCode::GcodeBadValue, b.span('Q'),
                  "found " + quoted(b.span('Q')) + "; expected an analog value a float holds");
    }
    if (code == 68) {
      analog_out_[static_cast<std::size_t>(n)] = q;
      synced_analog_ = static_cast<std::uint8_t>(synced_analog_ & ~(1u << n));
    } else {
      synced_analog_ = static_cast<std::uint8_t>(synced_analog_ | (1u << n));
      synced_analog_value_[static_cast<std::size_t>(n)] = q;
    }
    return true;
  }
  const auto bit = static_cast<std::uint8_t>(1u << n);
  switch (code) {
    case 62:
      synced_on_ |= bit;
      synced_off_ = static_cast<std::uint8_t>(synced_off_ & ~bit);
      break;
    case 63:
      synced_off_ |= bit;
      synced_on_ = static_cast<std::uint8_t>(synced_on_ & ~bit);
      break;
    case 64: digital_out_ |= bit; break;
    default: digital_out_ = static_cast<std::uint8_t>(digital_out_ & ~bit); break;
  }
  if (code >= 64) {  // now: a synchronized change of the same output waiting is superseded
    synced_on_ = static_cast<std::uint8_t>(synced_on_ & ~bit);
    synced_off_ = static_cast<std::uint8_t>(synced_off_ & ~bit);
  }
  return true;
}

// M66 P<input> L<mode> Q<timeout s>: the job waits, at rest with the beam
// off, for digital input P to rise (L1), fall (L2), be high (L3) or low
// (L4), at most Q seconds; then it stops with a fault (E420). The program is
// read ahead of the motion, so it cannot read the input's value: #5399
// reads what it will be if the job goes on (1 for L1/L3, 0 for L2/L4), and
// L0 (read at once, no wait) and analog inputs (E) are refused.
bool Interpreter::wait_input(SegmentBuffer& out) {
  const Block& b = *b_;
  const Span at = b.m_io_word;
  if (b.has('E')) {
    return fail(ErrorCode::GcodeUnsupported, b.span('E'),
                "found " + quoted(b.span('E')) +
                    " on M66: waiting on an analog input is not "
                    "supported; expected M66 P<digital input> L1…L4 Q<seconds>");
  }
  if (!b.has('P')) {
    return fail(ErrorCode::GcodeMissingWord, at,
                "found " + quoted(at) + " with no P word; expected M66 P<input 0 … " +
                    std::to_string(kDigitalInputs - 1) + "> L1…L4 Q<seconds>");
  }
  const double p = b['P'];
  if (p != std::floor(p) || p < 0.0 || p >= kDigitalInputs) {
    return fail(ErrorCode::GcodeBadValue, b.span('P'),
                "found " + quoted(b.span('P')) + " on M66; expected an input from 0 to " +
                    std::to_string(kDigitalInputs - 1));
  }
  const double l = b.has('L') ? b['L'] : 0.0;
  if (l != std::floor(l) || l < 1.0 || l > 4.0) {
    return fail(l == 0.0 ? ErrorCode::GcodeUnsupported : ErrorCode::GcodeBadValue,
                b.has('L') ? b.span('L') : at,
                "found " + quoted_block() + ": M66 " +
                    (l == 0.0 ? std::string("L0 (or no L) reads the input at once, for #5399; "
                                            "the program is read ahead of the motion, so the "
                                            "value cannot be known then")
                              : "with L" + gnum(l)) +
                    "; expected L1 (rise), L2 (fall), L3 (high) or L4 (low) with Q<seconds>");
  }
  if (!b.has('Q') || !(b['Q'] > 0.0) || b['Q'] > kMaxBlockSeconds) {
    return fail(ErrorCode::GcodeBadValue, b.has('Q') ? b.span('Q') : at,
                "found " + quoted_block() +
                    ": M66 needs a timeout; expected Q<seconds> from "
                    "more than 0 to " +
                    gnum(kMaxBlockSeconds) + " (after it the job stops)");
  }
  Segment& s = hold_segment(out);
  s.wait_input = static_cast<std::int8_t>(p);
  s.wait_mode = static_cast<std::uint8_t>(l);
  s.wait_timeout_s = static_cast<float>(b['Q']);
  numbered_[kParamInputResult] = (l == 1.0 || l == 3.0) ? 1.0 : 0.0;
  return true;
}

void Interpreter::take_synced_outputs() {
  if ((synced_on_ | synced_off_ | synced_analog_) == 0) return;
  digital_out_ = static_cast<std::uint8_t>((digital_out_ | synced_on_) & ~synced_off_);
  for (int n = 0; n < kAnalogOutputs; ++n) {
    if ((synced_analog_ >> n) & 1u)
      analog_out_[static_cast<std::size_t>(n)] = synced_analog_value_[static_cast<std::size_t>(n)];
  }
  synced_on_ = synced_off_ = synced_analog_ = 0;
}

// --- modal state contexts (M70 … M73) -------------------------------------

// What M70 saves and M72 restores (LinuxCNC's save_settings: the G modes,
// F, S, the laser and gas M codes; not the motion mode, nor cutter
// compensation here).
void Interpreter::restore_modal(const ModalState& m) {
  const int now = modal_.coord_system;
  modal_ = m;
  modal_.coord_system = now;
  // the system as it is now (its offsets may have been set since)
  if (m.coord_system != now) select_coord_system(m.coord_system);
  apply_tool_offset();
}

bool Interpreter::run_context() {
  const Block& b = *b_;
  Context& c = contexts_.back();
  switch (b.m_context) {
    case 70:
    case 73:
      c.valid = true;
      c.state = modal_;
      // M73 at the top level: nothing to return to; kept as M70's (LinuxCNC)
      c.restore_on_return = b.m_context == 73 && contexts_.size() > 1;
      return true;
    case 71: c.valid = false; return true;
    default:
      if (!c.valid) {
        return fail(ErrorCode::GcodeFlow, b.m_context_word,
                    "found " + quoted(b.m_context_word) +
                        " with no modal state saved at this call level; expected M70 (or M73) "
                        "before it, in the same subroutine or program level, and no M71 since");
      }
      if (comp_side_ != 0) {
        return fail(ErrorCode::GcodeModalConflict, b.m_context_word,
                    "found " + quoted(b.m_context_word) +
                        " with cutter compensation on (G41/G42): the plane and offsets it "
                        "restores would move the path under it; expected G40 before it");
      }
      restore_modal(c.state);
      return true;
  }
}

std::string Interpreter::modes_block() const {
  const ModalState& m = modal_;
  const double scale = length_scale();
  char buf[64];
  const auto number = [&buf](double v) {
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return std::string(buf);
  };
  std::string out;
  out += m.plane == Plane::ZX ? "G18" : m.plane == Plane::YZ ? "G19" : "G17";
  out += m.inch ? " G20" : " G21";
  out += m.absolute ? " G90" : " G91";
  out += m.arc_absolute ? " G90.1" : " G91.1";
  out += m.inverse_time ? " G93" : " G94";
  out += ' ';
  out += kWorkOffsetNames[static_cast<std::size_t>(std::clamp(m.coord_system, 0, kWorkOffsetCount - 1))];
  switch (m.path_mode) {
    case PathMode::ExactPath: out += " G61"; break;
    case PathMode::ExactStop: out += " G61.1"; break;
    case PathMode::Blend:
      out += " G64 P" + number(m.blend_tolerance_mm / scale);
      if (m.naive_cam_tolerance_mm > 0.0) out += " Q" + number(m.naive_cam_tolerance_mm / scale);
      break;
  }
  // F in the units it is read in (an inverse-time F is per block, not kept)
  if (m.feed_set && !m.inverse_time) out += " F" + number(m.feed_mm_min / scale);
  if (m.power_pct > 0.0) out += " S" + number(m.power_pct * machine_.laser.s_max / 100.0);
  if (motion_ == MotionMode::Rapid) out += " G0";
  if (motion_ == MotionMode::Linear) out += " G1";
  return out;
}

void Interpreter::enter_call() { contexts_.emplace_back(); }

void Interpreter::leave_call() {
  if (contexts_.size() < 2) return;
  const Context c = contexts_.back();
  contexts_.pop_back();
  if (c.valid && c.restore_on_return) restore_modal(c.state);
}

// LinuxCNC's predefined named parameters that mean something here (its
// "Predefined Named Parameters"): read-only views of the modal state.
bool Interpreter::predefined(std::string_view name, double& out) const {
  static constexpr std::string_view kAxes[] = {"_x", "_y", "_z", "_a", "_b", "_c"};
  static constexpr std::string_view kAbsAxes[] = {"_abs_x", "_abs_y", "_abs_z", "_abs_a", "_abs_b", "_abs_c"};
  for (int a = 0; a < kAxisCount; ++a) {
    if (name == kAxes[a]) {
      out = position_param(a);
      return true;
    }
    if (name == kAbsAxes[a]) {
      out = a < 3 ? pos_[a] / length_scale() : pos_[a];
      return true;
    }
  }
  const auto flag = [&out](bool b) {
    out = b ? 1.0 : 0.0;
    return true;
  };
  if (name == "_u" || name == "_v" || name == "_w") return flag(false);
  if (name == "_current_tool") return out = current_tool_, true;
  if (name == "_selected_tool") return out = selected_tool_, true;
  if (name == "_coord_system")
    return out = modal_.coord_system < 6 ? 540 + 10 * modal_.coord_system : 591 + (modal_.coord_system - 6),
           true;
  if (name == "_metric") return flag(!modal_.inch);
  if (name == "_imperial") return flag(modal_.inch);
  if (name == "_absolute") return flag(modal_.absolute);
  if (name == "_incremental") return flag(!modal_.absolute);
  if (name == "_inverse_time") return flag(modal_.inverse_time);
  if (name == "_units_per_minute") return flag(!modal_.inverse_time);
  if (name == "_units_per_rev") return flag(false);
  if (name == "_ijk_absolute_mode") return flag(modal_.arc_absolute);
  if (name == "_tool_offset") return flag(modal_.tool_length_on);
  if (name == "_ccomp") return out = 400, true;
  if (name == "_plane")
    return out = modal_.plane == Plane::ZX ? 180 : modal_.plane == Plane::YZ ? 190 : 170, true;
  if (name == "_motion_mode") return out = kMotionCode[static_cast<std::size_t>(motion_)], true;
  if (name == "_feed") return out = modal_.inverse_time ? 0.0 : modal_.feed_mm_min / length_scale(), true;
  if (name == "_rpm") return out = modal_.power_pct * machine_.laser.s_max / 100.0, true;
  if (name == "_spindle_on") return flag(modal_.laser != LaserMode::Off);
  if (name == "_mist") return flag(modal_.mist);
  if (name == "_flood") return flag(modal_.flood);
  if (name == "_feed_override") return flag((modal_.feed_control & kFeedOverrideOff) == 0);
  if (name == "_speed_override") return flag(modal_.speed_override);
  if (name == "_adaptive_feed") return flag((modal_.feed_control & kAdaptiveFeed) != 0);
  if (name == "_feed_hold") return flag((modal_.feed_control & kFeedHoldInputOff) == 0);
  return false;
}

}  // namespace lcnc::gcode
