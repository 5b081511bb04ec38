// The interpreter's tools, as LinuxCNC handles them. On a laser a "tool" is
// a nozzle and lens set: its Z offset is how much longer or shorter the
// head is with it, its diameter the kerf it cuts.
//
//   T n        select tool n (it must be in the tool table; T0: no tool)
//   M6         put the selected tool in the spindle (no motion: the change
//              is the operator's, between jobs or at an M0)
//   M61 Q n    say tool n is in the spindle
//   G43 [H n]  apply tool n's offsets (default: the tool in the spindle)
//   G43.1 X Y Z  offsets as written; G43.2 H n adds tool n's; G49 none
//   G10 L1 P n X Y Z R   set tool n's offsets (and radius R: diameter 2R)
//   G10 L10 P n …  set them so the position, with them applied, reads the
//   axis words; L11 the same as if G59.3 were in effect, without G92.
//
// Offsets are mm in the table whatever G20/G21; the words are read in the
// program's units. The tool in the spindle is #5400, the offsets in effect
// #5401 …, its diameter #5410 (gcode/parameter_file.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "gcode/interpreter.h"

namespace lcnc::gcode {

void Interpreter::load_offsets(std::vector<ToolConfig> tools, std::vector<int> changed) {
  tools_ = std::move(tools);
  changed_tools_ = std::move(changed);
  const double cs = numbered_[kParamCoordSystem];
  select_coord_system(cs >= 1.0 && cs <= kWorkOffsetCount ? static_cast<int>(cs) - 1 : 0);
  if (numbered_[kParamG92On] == 1.0) {
    for (int a = 0; a < kAxisCount; ++a) axis_offset_[a] = numbered_[static_cast<std::size_t>(kParamG92 + a)];
  }
  update_offsets();
}

const ToolConfig* Interpreter::find_tool(int number) const {
  for (const ToolConfig& t : tools_)
    if (t.number == number) return &t;
  return nullptr;
}

// The whole-number tool of a T, H, P or Q word, 0 … kMaxToolNumber, in
// the tool table (0: no tool).
bool Interpreter::tool_number(char letter, int& out) {
  const Block& b = *b_;
  const double v = b[letter];
  if (v != std::floor(v) || v < 0.0 || v > kMaxToolNumber) {
    return fail(ErrorCode::GcodeBadValue, b.span(letter),
                "found " + quoted(b.span(letter)) + "; expected a tool number from 0 to " +
                    std::to_string(kMaxToolNumber));
  }
  out = static_cast<int>(v);
  if (out == 0 || find_tool(out) != nullptr) return true;
  std::string table;
  for (const ToolConfig& t : tools_) {
    if (table.size() > 60) {
      table += " …";
      break;
    }
    table += (table.empty() ? "" : " ") + std::to_string(t.number);
  }
  return fail(
      ErrorCode::GcodeNoSuchTool, b.span(letter),
      "found " + quoted(b.span(letter)) + ": tool " + std::to_string(out) +
          " is not in the tool table ([tools." + std::to_string(out) + "] of the machine config); expected " +
          (table.empty() ? std::string("T0: the table is empty") : "one of " + table + ", or 0 (no tool)"));
}

bool Interpreter::change_tool() {
  const Block& b = *b_;
  if (b.has('T') && !tool_number('T', selected_tool_)) return false;
  if (b.m_tool == 6) {
    current_tool_ = selected_tool_;
    comp_exited_ = false;  // the change reads back where the tool stands (LinuxCNC)
  } else if (b.m_tool == 61) {
    if (!b.has('Q')) {
      return fail(ErrorCode::GcodeMissingWord, b.m_tool_word,
                  "found " + quoted_block() + " with no Q word; expected M61 Q<tool>");
    }
    if (!tool_number('Q', current_tool_)) return false;
  }
  if (b.m_tool >= 0) numbered_[kParamTool] = current_tool_;
  return true;
}

bool Interpreter::set_tool_length() {
  const Block& b = *b_;
  const int code = b.code(GGroup::ToolLength);
  switch (code) {
    case 490:
      modal_.tool_offset.setZero();
      modal_.tool_length_on = false;
      break;
    case 430:
    case 432: {
      int h = current_tool_;
      if (b.has('H')) {
        if (!tool_number('H', h)) return false;
      } else if (code == 432) {
        return fail(ErrorCode::GcodeMissingWord, b.code_word(GGroup::ToolLength),
                    "found " + quoted_block() + " with no H word; expected G43.2 H<tool>");
      }
      const ToolConfig* t = find_tool(h);
      const Pose add = t != nullptr ? t->offset : Pose::Zero();
      modal_.tool_offset = code == 430 ? add : Pose(modal_.tool_offset + add);
      modal_.tool_length_on = true;
      break;
    }
    case 431:
      for (int a = 0; a < kAxisCount; ++a)
        if ((b.axis_mask >> a) & 1u) modal_.tool_offset[a] = axis_value(a);
      modal_.tool_length_on = true;
      break;
    default: return true;
  }
  apply_tool_offset();
  const ToolConfig* in_spindle = find_tool(current_tool_);
  numbered_[kParamToolDiameter] = in_spindle != nullptr ? in_spindle->diameter_mm : 0.0;
  return true;
}

void Interpreter::apply_tool_offset() {
  update_offsets();
  for (int a = 0; a < kAxisCount; ++a)
    numbered_[static_cast<std::size_t>(kParamToolOffset + a)] = modal_.tool_offset[a];
}

bool Interpreter::set_tool_data() {
  const Block& b = *b_;
  const int l = static_cast<int>(b['L']);
  if (!b.has('P')) {
    return fail(
        ErrorCode::GcodeMissingWord, b.code_word(GGroup::NonModal),
        "found " + quoted_block() + " with no P word; expected G10 L" + std::to_string(l) + " P<tool>");
  }
  int n = 0;
  if (!tool_number('P', n)) return false;
  if (n == 0) {
    return fail(ErrorCode::GcodeBadValue, b.span('P'),
                "found " + quoted(b.span('P')) + " on G10 L" + std::to_string(l) +
                    "; expected a tool of the table, not P0 (no tool)");
  }
  ToolConfig& t =
      *std::find_if(tools_.begin(), tools_.end(), [n](const ToolConfig& x) { return x.number == n; });
  Pose reference = origin_ + axis_offset_;  // L10: the offsets in effect
  if (l == 11) {
    reference =
        Eigen::Map<const Pose>(&numbered_[static_cast<std::size_t>(coord_param(kWorkOffsetCount - 1))]);
  }
  for (int a = 0; a < 3; ++a) {
    if (((b.axis_mask >> a) & 1u) == 0) continue;
    const double v = axis_value(a);
    t.offset[a] = l == 1 ? v : pos_[a] - reference[a] - v;
    if (std::fabs(t.offset[a]) > kMaxToolOffsetMm) {
      return fail(ErrorCode::GcodeBadValue, b.span(kAxisLetters[a]),
                  "found " + quoted_block() + ": a tool offset of " + std::to_string(t.offset[a]) +
                      " mm; expected at most ±" + std::to_string(static_cast<int>(kMaxToolOffsetMm)) + " mm");
    }
  }
  for (int a = 3; a < kAxisCount; ++a) {
    if ((b.axis_mask >> a) & 1u) {
      return fail(ErrorCode::GcodeUnsupported, b.span(kAxisLetters[a]),
                  "found " + quoted(b.span(kAxisLetters[a])) + " on G10 L" + std::to_string(l) +
                      "; expected tool offsets on X Y Z only");
    }
  }
  if (b.has('R')) {
    const double r = b['R'] * length_scale();
    if (r < 0.0 || 2.0 * r > kMaxToolOffsetMm) {
      return fail(ErrorCode::GcodeBadValue, b.span('R'),
                  "found " + quoted(b.span('R')) + " on G10 L" + std::to_string(l) +
                      "; expected a tool radius from 0 to " +
                      std::to_string(static_cast<int>(kMaxToolOffsetMm / 2)) + " mm");
    }
    t.diameter_mm = 2.0 * r;
  }
  if (std::find(changed_tools_.begin(), changed_tools_.end(), n) == changed_tools_.end())
    changed_tools_.push_back(n);
  return true;
}

std::vector<ToolConfig> Interpreter::changed_tools() const {
  std::vector<ToolConfig> out;
  for (const ToolConfig& t : tools_)
    if (std::find(changed_tools_.begin(), changed_tools_.end(), t.number) != changed_tools_.end())
      out.push_back(t);
  return out;
}

}  // namespace lcnc::gcode
