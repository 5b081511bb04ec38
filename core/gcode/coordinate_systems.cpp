// The interpreter's coordinate systems, as LinuxCNC keeps them:
//
//   machine = program + origin (G54 … G59.3) + axis offset (G92/G52) + tool offset (G43)
//
// G10 L2 P n sets system n's origin to the axis words; G10 L20 P n sets it
// so the current position reads as the axis words:
//   origin = machine − axis offset − tool offset − value.
// G92 sets the axis offset the same way (axis offset = machine − origin −
// tool offset − value); G52 sets it to the words themselves; G92.1 clears
// it and its parameters, G92.2 clears it and keeps them, G92.3 takes it back
// from them. G28 / G30 go at rapid, through the axis words' point when
// there are any (then only those axes go on), to the position G28.1 / G30.1
// stored. Every value is written to the numbered parameters
// (gcode/parameter_file.h): a program reads them there, the parameter file
// keeps them, and selecting a system reads its origin back from them.
#include <cmath>
#include <numbers>
#include <string>

#include "gcode/gcode_tolerances.h"
#include "gcode/interpreter.h"

namespace lcnc::gcode {

void Interpreter::select_coord_system(int index) {
  modal_.coord_system = index;
  const int base = coord_param(index);
  for (int a = 0; a < kAxisCount; ++a) origin_[a] = numbered_[static_cast<std::size_t>(base + a)];
  numbered_[kParamCoordSystem] = index + 1;
  update_offsets();
}

double Interpreter::position_param(int axis) const {
  if (axis >= kAxisCount) return 0.0;  // U V W
  const double p = pos_[axis] - offsets_[axis];
  return axis < 3 ? p / length_scale() : p;
}

// LinuxCNC's polar coordinates: X = r·cos θ, Y = r·sin θ about the
// program's origin; a word not given keeps the current radius or angle; in
// G91 the words are added to them (so at the origin, where the angle is
// undefined, G91 polar is an error).
bool Interpreter::polar_target(const Pose& from, Pose& to) {
  const Block& b = *b_;
  const double scale = length_scale();
  const double cx = (from[0] - offsets_[0]) / scale;
  const double cy = (from[1] - offsets_[1]) / scale;
  const bool has_r = (b.polar & 1u) != 0, has_a = (b.polar & 2u) != 0;
  const double a_rad = b.polar_angle_deg * std::numbers::pi / 180.0;
  double r = std::hypot(cx, cy);
  double theta = std::atan2(cy, cx);
  if (modal_.absolute) {
    if (has_r) r = b.polar_radius;
    if (has_a) theta = a_rad;
  } else {
    if (cx == 0.0 && cy == 0.0) {
      return fail(ErrorCode::GcodeSyntax, b.polar_word,
                  "found " + quoted(b.polar_word) +
                      " in G91 at the origin, where the angle is "
                      "undefined; expected an incremental polar move from elsewhere, or G90");
    }
    if (has_r) r += b.polar_radius;
    if (has_a) theta += a_rad;
  }
  to[0] = r * std::cos(theta) * scale + offsets_[0];
  to[1] = r * std::sin(theta) * scale + offsets_[1];
  return true;
}

bool Interpreter::run_non_modal(SegmentBuffer& out) {
  const int code = b_->code(GGroup::NonModal);
  switch (code) {
    case 100: {  // G10
      if (!b_->has('L')) {
        return fail(ErrorCode::GcodeMissingWord, b_->code_word(GGroup::NonModal),
                    "found " + quoted_block() +
                        " with no L word; expected G10 L2 or L20 "
                        "(a work offset) or L1, L10 or L11 (a tool)");
      }
      const double l = (*b_)['L'];
      if (l == 2.0 || l == 20.0) return set_coord_system_data();
      if (l == 1.0 || l == 10.0 || l == 11.0) return set_tool_data();
      return fail(ErrorCode::GcodeUnsupported, b_->span('L'),
                  "found " + quoted(b_->span('L')) +
                      " on G10; expected L1, L10, L11 (tool "
                      "table), L2 or L20 (work offsets)");
    }
    case 280:
    case 300: return go_home(code == 280 ? kParamG28 : kParamG30, out);
    case 281:
    case 301: {  // store where the machine is
      const int first = code == 281 ? kParamG28 : kParamG30;
      for (int a = 0; a < kAxisCount; ++a) numbered_[static_cast<std::size_t>(first + a)] = pos_[a];
      return true;
    }
    case 520:
    case 920:
    case 921:
    case 922:
    case 923: {
      const bool ok = set_axis_offsets();
      update_offsets();
      return ok;
    }
    default: return true;
  }
}

bool Interpreter::set_coord_system_data() {
  const Block& b = *b_;
  const bool l20 = b['L'] == 20.0;
  if (!b.has('P')) {
    return fail(ErrorCode::GcodeMissingWord, b.code_word(GGroup::NonModal),
                "found " + quoted_block() + " with no P word; expected G10 L" + (l20 ? "20" : "2") +
                    " P1 … P9 (G54 … G59.3; P0: the system in effect)");
  }
  const double p = b['P'];
  if (p != std::floor(p) || p < 0.0 || p > kWorkOffsetCount) {
    return fail(ErrorCode::GcodeBadValue, b.span('P'),
                "found " + quoted(b.span('P')) + " on G10 L" + (l20 ? "20" : "2") +
                    "; expected P0 (the system in effect) or P1 … P9 (G54 … G59.3)");
  }
  if (b.has('R') && b['R'] != 0.0) {
    return fail(ErrorCode::GcodeUnsupported, b.span('R'),
                "found " + quoted(b.span('R')) +
                    ": a rotated coordinate system is not "
                    "supported; expected no R, or R0");
  }
  const int index = p == 0.0 ? modal_.coord_system : static_cast<int>(p) - 1;
  const int base = coord_param(index);
  for (int a = 0; a < kAxisCount; ++a) {
    if (((b.axis_mask >> a) & 1u) == 0) continue;
    const double v = axis_value(a);
    numbered_[static_cast<std::size_t>(base + a)] =
        l20 ? pos_[a] - axis_offset_[a] - modal_.tool_offset[a] - v : v;
  }
  if (index == modal_.coord_system) select_coord_system(index);
  return true;
}

bool Interpreter::set_axis_offsets() {
  const Block& b = *b_;
  const int code = b.code(GGroup::NonModal);
  auto store = [&](bool on) {
    numbered_[kParamG92On] = on ? 1.0 : 0.0;
    for (int a = 0; a < kAxisCount; ++a) numbered_[static_cast<std::size_t>(kParamG92 + a)] = axis_offset_[a];
  };
  switch (code) {
    case 920:
    case 520:
      if (b.axis_mask == 0) {
        return fail(ErrorCode::GcodeMissingWord, b.code_word(GGroup::NonModal),
                    "found " + quoted_block() + " with no axis words; expected " + g_code_name(code) +
                        " with the axes to offset, e.g. " + g_code_name(code) + " X0 Y0");
      }
      for (int a = 0; a < kAxisCount; ++a) {
        if (((b.axis_mask >> a) & 1u) == 0) continue;
        const double v = axis_value(a);
        axis_offset_[a] = code == 520 ? v : pos_[a] - origin_[a] - modal_.tool_offset[a] - v;
      }
      store(true);
      return true;
    case 921:  // cleared, and its parameters
      axis_offset_.setZero();
      store(false);
      return true;
    case 922:  // cleared, its parameters kept
      axis_offset_.setZero();
      numbered_[kParamG92On] = 0.0;
      return true;
    case 923:  // back from its parameters
      for (int a = 0; a < kAxisCount; ++a)
        axis_offset_[a] = numbered_[static_cast<std::size_t>(kParamG92 + a)];
      numbered_[kParamG92On] = 1.0;
      return true;
    default: return true;
  }
}

bool Interpreter::go_home(int first_param, SegmentBuffer& out) {
  const Block& b = *b_;
  motion_word_ = b.code_word(GGroup::NonModal);
  Pose stored = pos_;
  std::uint8_t axes = b.axis_mask;
  if (axes == 0) {
    for (int a = 0; a < kAxisCount; ++a)
      if (machine_.axes[a].present) axes = static_cast<std::uint8_t>(axes | (1u << a));
  } else {
    // through the axis words' point, in the program's coordinates and mode
    Pose mid = pos_;
    const Pose& offset = offsets_;
    for (int a = 0; a < kAxisCount; ++a) {
      if (((b.axis_mask >> a) & 1u) == 0) continue;
      mid[a] = modal_.absolute ? axis_value(a) + offset[a] : pos_[a] + axis_value(a);
    }
    if (!rapid_to(mid, out)) return false;
  }
  for (int a = 0; a < kAxisCount; ++a)
    if ((axes >> a) & 1u) stored[a] = numbered_[static_cast<std::size_t>(first_param + a)];
  return rapid_to(stored, out);
}

}  // namespace lcnc::gcode
