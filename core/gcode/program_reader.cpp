// ProgramReader: line source -> block parser -> interpreter, one line at a
// time, so memory stays bounded whatever the program's length. check_program
// runs the same reader to the end and sums up what it produced.
#include "gcode/program_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <utility>

#include "gcode/arc_geometry.h"
#include "gcode/block_parser.h"
#include "gcode/expression.h"
#include "gcode/gcode_tolerances.h"
#include "gcode/interpreter.h"
#include "gcode/line_source.h"
#include "gcode/parameter_file.h"

namespace lcnc {

namespace {

std::uint8_t present_axes(const MachineConfig& machine) {
  std::uint8_t mask = 0;
  for (int a = 0; a < kAxisCount; ++a) {
    if (machine.axes[a].present) mask = static_cast<std::uint8_t>(mask | (1u << a));
  }
  return mask;
}

// 1-based column of a byte offset, counting UTF-8 characters.
std::uint32_t column_of(std::string_view line, std::uint32_t byte_pos) {
  std::uint32_t col = 1;
  for (std::uint32_t i = 0; i < byte_pos && i < line.size(); ++i) {
    if ((static_cast<unsigned char>(line[i]) & 0xC0) != 0x80) ++col;
  }
  return col;
}

// Byte offset of the first thing that would run in a line, or npos when it
// holds only blanks, comments or a '%' delimiter. Lenient on purpose: it only
// decides whether lines after the end deserve a warning.
std::size_t first_content(std::string_view line) {
  bool in_comment = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_comment) {
      if (c == ')') in_comment = false;
      continue;
    }
    if (c == '(') {
      in_comment = true;
    } else if (c == ';' || c == '%') {
      return std::string_view::npos;
    } else if (c != ' ' && c != '\t' && c != '\r') {
      return i;
    }
  }
  return std::string_view::npos;
}

// The program's parameters: #1 … #5602 (unset ones read 0) and the named
// ones, global when the name starts with '_', else local to the subroutine
// call (or the program) that set them. #1 … #30 are a call's arguments: saved
// at the call, restored at its return.
class Parameters final : public gcode::ParameterReader {
 public:
  static constexpr int kArgs = static_cast<int>(gcode::kMaxCallArgs);
  using Saved = std::array<double, kArgs>;

  Parameters() : numbered_(gcode::kMaxParameterIndex + 1, 0.0), locals_(1) {
    globals_["_value"] = 0.0;           // what the last call returned
    globals_["_value_returned"] = 0.0;  // 1 when it returned a value
  }
  [[nodiscard]] double numbered(int index) const override {
    if (index >= gcode::kParamPosition && index < gcode::kParamPosition + gcode::kParamAxes &&
        interp_ != nullptr)
      return interp_->position_param(index - gcode::kParamPosition);
    return numbered_[index];
  }
  [[nodiscard]] bool named(std::string_view name, double& out) const override {
    const auto& map = name.front() == '_' ? globals_ : locals_.back();
    auto it = map.find(std::string(name));
    if (it == map.end()) return name.front() == '_' && interp_ != nullptr && interp_->predefined(name, out);
    out = it->second;
    return true;
  }
  // LinuxCNC's read-only parameters: the predefined names (views of the
  // machine's state: set, the next move would go elsewhere than the machine
  // is) and the numbered views of the tool and the position.
  [[nodiscard]] std::string read_only(int index, std::string_view name) const override {
    double v = 0.0;
    if (index == 0)
      return name.front() == '_' && interp_ != nullptr && interp_->predefined(name, v)
                 ? "a predefined parameter, the interpreter's own state"
                 : std::string();
    if (index >= gcode::kParamPosition && index < gcode::kParamPosition + gcode::kParamAxes)
      return "the current position";
    if (index >= gcode::kParamInputResult && index <= gcode::kParamToolLast)
      return index == gcode::kParamInputResult ? "M66's input value"
                                               : "the tool's data, set by M6, M61 and G43";
    return {};
  }
  // Where the interpreter keeps its offsets (and reads them back).
  std::vector<double>& store() { return numbered_; }
  [[nodiscard]] const std::vector<double>& store() const { return numbered_; }
  // The predefined names (#<_x> …) are the interpreter's state.
  void set_interpreter(const gcode::Interpreter* interp) { interp_ = interp; }
  // A line's settings, after all of its values have been read.
  void apply(const std::vector<gcode::ParamSet>& sets) {
    for (const gcode::ParamSet& s : sets) {
      if (s.index > 0) {
        numbered_[s.index] = s.value;
      } else {
        (s.name.front() == '_' ? globals_ : locals_.back())[s.name] = s.value;
      }
    }
  }
  void set_global(const std::string& name, double v) { globals_[name] = v; }
  // A call: #1 … #30 become `args` (the rest 0), named locals start empty.
  Saved enter(const std::vector<double>& args) {
    Saved saved{};
    for (int i = 0; i < kArgs; ++i) {
      saved[i] = numbered_[i + 1];
      numbered_[i + 1] = i < static_cast<int>(args.size()) ? args[i] : 0.0;
    }
    locals_.emplace_back();
    return saved;
  }
  void leave(const Saved& saved) {
    for (int i = 0; i < kArgs; ++i) numbered_[i + 1] = saved[i];
    locals_.pop_back();
  }

 private:
  std::vector<double> numbered_;
  const gcode::Interpreter* interp_ = nullptr;
  std::unordered_map<std::string, double> globals_;
  std::vector<std::unordered_map<std::string, double>> locals_;  // one map per call level
};

// Where a line starts in one of the reader's files: `line` lines come before it.
struct Location {
  std::size_t file = 0;
  std::uint64_t offset = 0;
  std::uint32_t line = 0;
};

// An open control structure of the running call (LinuxCNC keeps them by
// label; here a stack, so a mismatched end is named at once).
struct Control {
  gcode::OKind kind = gcode::OKind::If;  // If, While, Do or Repeat
  std::string label;
  Location start;          // While: its own line (re-tested); Do, Repeat: the line after
  std::uint32_t line = 0;  // where it opened, for messages
  std::int64_t left = 0;   // Repeat: passes still to run after this one
  std::uint32_t col = 1;   // of its O-word
};

// A subroutine call in progress (the program itself is frame 0).
struct Frame {
  std::string sub;     // the label called ("" for the program)
  Location return_to;  // the line after the call
  Parameters::Saved saved{};
  std::vector<Control> controls;
};

// Lines passed over unread except for O-words with `label`.
enum class Skip : std::uint8_t {
  None,
  ToSub,     // to "O<label> sub", then into it (a call of a sub defined later, or in its file)
  SubBody,   // a definition, to its endsub
  IfBranch,  // a false branch: to the elseif, else or endif
  ToEndIf,   // after the branch that ran: to the endif
  LoopEnd,   // a loop not (or no longer) run: to its end (`end`)
  ToDoTest,  // continue in a do loop: to its closing while
};

// A program file and the subroutine files it calls.
struct OpenFile {
  std::string path;
  std::unique_ptr<gcode::LineSource> src;  // null while closed (reopened on a jump back)
};

// Jumps back (loops, calls) with no motion in between (nothing that takes
// machine time: G4 P0 and M0 do not) before the reader calls it an endless
// loop: a program may compute, but never hang the reader.
constexpr std::uint32_t kMaxJumpsWithoutMotion = 1'000'000;
// Nested calls (LinuxCNC's limit).
constexpr std::size_t kMaxCallDepth = 10;

std::string o_name(const std::string& label) { return "O" + label; }

}  // namespace

struct ProgramReader::Impl {
  Impl(std::unique_ptr<gcode::LineSource> src, std::string name, const MachineConfig& m,
       const ReaderOptions& opts)
      : file(name),
        machine(m),
        options(opts),
        parser(present_axes(machine)),
        interp(machine, options.start, params.store()) {
    files.push_back(OpenFile{std::move(name), std::move(src)});
    in = files[0].src.get();
    for (int a = 0; a < 3; ++a)
      if (machine.axes[a].present) fastest_axis = std::max(fastest_axis, machine.axes[a].max_velocity);
    frames.emplace_back();
    parser.set_parameters(&params);
    params.set_interpreter(&interp);
    if (load_offsets()) run_startup();
  }

  // The segments of read_program() as the options ask: from the start line
  // on (after the approach), a pause after each block, the beam off.
  Next read(Segment& out);
  Next read_program(Segment& out);
  bool approach_to(const Segment& first);
  [[nodiscard]] Segment pause_at(const Segment& after) const;
  std::vector<Segment> queued;  // what read() returns before reading on
  std::size_t queued_next = 0;
  bool reached_start = false;  // the first move of the start line has been read
  bool emitted_any = false;
  std::uint32_t last_line = 0;  // of the last segment returned
  Segment last_segment;

  enum class State : std::uint8_t { Running, Ended, Failed };

  bool load_offsets();
  bool save_offsets();
  std::string kept_state() const;
  std::string kept_at_start;  // kept_state() after load_offsets()
  void run_startup();
  // A line of modes run before the program (line 0): nothing may move.
  void run_line0(const std::string& code, const char* what, ErrorCode code_if_bad);
  void warn_lines_after_end();
  bool grbl_system_line(std::string_view text);
  Next fail(ErrorCode code, std::string_view line, std::uint32_t byte_pos, std::string message);
  Next fail_o(std::string_view line, std::string message);
  Next at_file_end();
  // The moves cutter compensation still holds, at the program's end.
  bool release_held();

  // O-words: the line just parsed into `block`, which starts at `here`.
  bool run_o(std::string_view text, const Location& here);
  bool skip_line(std::string_view text);
  bool values(std::string_view text);
  bool call(std::string_view text, const Location& after);
  bool jump(const Location& to);
  void start_skip(Skip what, const std::string& label, gcode::OKind end = gcode::OKind::None);
  Control* find_loop(const std::string& label);
  gcode::LineSource& src() { return *in; }

  std::string file;       // the file being read (for diagnostics)
  MachineConfig machine;  // before interp, which keeps a reference to it
  ReaderOptions options;
  std::vector<OpenFile> files;      // [0] the program
  bool from_memory = false;         // [0] is a name for text held in memory (MDI), no file
  std::size_t cur = 0;              // files[cur] is being read
  gcode::LineSource* in = nullptr;  // files[cur].src
  Parameters params;                // before parser, which reads them
  gcode::BlockParser parser;
  gcode::Block block;
  gcode::Interpreter interp;
  gcode::SegmentBuffer pending;

  std::vector<Frame> frames;                                 // [0] the program
  std::unordered_map<std::string, Location> subs;            // label -> the line after its "sub"
  std::unordered_map<std::string, std::uint32_t> sub_lines;  // label -> its "sub" line
  Skip skip = Skip::None;
  std::string skip_label;
  gcode::OKind skip_end = gcode::OKind::None;  // LoopEnd: the keyword that ends the loop
  Location skip_from;                          // where the skip began (the call, the if …)
  std::uint32_t skip_col = 1;                  // and the column of its O-word
  std::vector<double> args;
  std::uint32_t jumps_without_motion = 0;
  // The work budget spent (MachineConfig::program_segment_limit,
  // program_time_limit_s): segments made, machine time at their feeds.
  double budget_segments = 0.0;
  double budget_time_s = 0.0;
  double fastest_axis = 1.0;  // mm/s: a rapid's time is counted at it (the least it takes)
  bool within_budget(const Segment& s);

  State state = State::Running;
  Diagnostic error;
  std::vector<Diagnostic> warnings;
  std::uint32_t line = 0;        // of files[cur]
  std::uint32_t main_lines = 0;  // lines of the program file read before its last jump

  bool saved = false;         // the parameter file written at the end
  bool seen_block = false;    // a line with words has been read
  bool seen_percent = false;  // the opening '%' has been read
  bool ended = false;         // M2, M30 or the closing '%'
  std::uint32_t end_line = 0;
  std::string end_what;
};

ProgramReader::Next ProgramReader::Impl::fail(ErrorCode code, std::string_view text, std::uint32_t byte_pos,
                                              std::string message) {
  error = make_error(code, std::move(message), file, line, column_of(text, byte_pos));
  pending.clear();
  state = State::Failed;
  return Next::Error;
}

// Counts `s` against the work budget; past it, the reading fails at the
// segment's line: a loop that moves (or dwells, or pauses) without end is
// stopped there, as one without motion is by jump().
bool ProgramReader::Impl::within_budget(const Segment& s) {
  budget_segments += 1.0;
  double dt = 0.0;
  switch (s.kind) {
    case MotionKind::Dwell: dt = s.dwell_s; break;
    case MotionKind::Rapid: dt = (s.end.head<3>() - s.start.head<3>()).norm() / fastest_axis; break;
    case MotionKind::Linear:
      if (s.feed_mm_s > 0.0) dt = (s.end.head<3>() - s.start.head<3>()).norm() / s.feed_mm_s;
      break;
    case MotionKind::Arc:
      if (s.feed_mm_s > 0.0) dt = gcode::arc_length_mm(s) / s.feed_mm_s;
      break;
  }
  budget_time_s += dt;
  // only what takes machine time of its own is progress: a loop of G4 P0,
  // M0 or M66 (held for the operator or an input, not by the program) is
  // stopped by jump() as one without motion
  if (dt > 0.0 && !s.pause && s.wait_input < 0) jumps_without_motion = 0;
  std::string what;
  if (budget_segments > machine.program_segment_limit) {
    char n[32];
    std::snprintf(n, sizeof n, "%.0f", machine.program_segment_limit);
    what = std::string("more than ") + n + " moves, dwells and pauses (machine.program_segment_limit)";
  } else if (budget_time_s > machine.program_time_limit_s) {
    char h[32];
    std::snprintf(h, sizeof h, "%g", machine.program_time_limit_s / 3600.0);
    what = std::string("more than ") + h + " h of machine time (machine.program_time_limit_h)";
  } else {
    return true;
  }
  error = make_error(ErrorCode::GcodeWorkBudget,
                     "the program makes " + what +
                         " by this line: an endless loop? expected a "
                         "program that ends within its work budget (raise the limit for a longer one)",
                     file, s.line, 1);
  state = State::Failed;
  return false;
}

ProgramReader::Next ProgramReader::Impl::fail_o(std::string_view text, std::string message) {
  return fail(ErrorCode::GcodeFlow, text, parser.text().byte_pos(block.o.word), std::move(message));
}

ProgramReader::Next ProgramReader::Impl::read_program(Segment& out) {
  for (;;) {
    switch (state) {
      case State::Ended:
        if (!saved && !save_offsets()) return Next::Error;
        return Next::End;
      case State::Failed: return Next::Error;
      case State::Running: break;
    }
    if (!pending.empty()) {
      out = pending.pop();
      if (!within_budget(out)) return Next::Error;
      return Next::Segment;
    }
    if (ended) {
      if (!release_held()) return Next::Error;
      if (!pending.empty()) continue;
      warn_lines_after_end();
      state = State::Ended;
      continue;
    }
    if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) {
      error =
          make_error(ErrorCode::GcodeCancelled, "the reading was cancelled before its end", file, line, 0);
      state = State::Failed;
      return Next::Error;
    }
    std::string_view text;
    const std::uint64_t line_start = in->tell();
    if (!in->next(text)) {
      if (src().too_long()) {
        error = make_error(ErrorCode::GcodeSyntax,
                           "found a line longer than " + std::to_string(gcode::kMaxLineBytes) +
                               " bytes (no line end within it); expected program lines of at "
                               "most " +
                               std::to_string(gcode::kMaxLineBytes) +
                               " bytes ending in a line feed: is this a G-code text file?",
                           file, line + 1, 0);
        state = State::Failed;
        return Next::Error;
      }
      if (!src().read_error().empty()) {
        error = make_error(ErrorCode::FileNotFound,
                           "reading stopped after line " + std::to_string(line) + ": " + src().read_error() +
                               "; expected to read the whole program",
                           file, line + 1, 0);
        state = State::Failed;
        return Next::Error;
      }
      if (at_file_end() == Next::Error) return Next::Error;
      continue;
    }
    ++line;
    pending.clear();
    if (skip != Skip::None) {
      if (!skip_line(text)) return Next::Error;
      continue;
    }
    if (machine.dialect == MachineConfig::Dialect::Grbl && grbl_system_line(text)) continue;
    if (!parser.parse(text, block)) {
      const gcode::Fault& f = parser.fault();
      return fail(f.code, text, f.byte_pos, f.message);
    }
    if (block.percent) {
      // The first '%' opens the program, the next one ends it (LinuxCNC);
      // a subroutine file's are passed over.
      if (cur != 0) continue;
      if (seen_block || seen_percent) {
        ended = true;
        end_line = line;
        end_what = "the closing '%'";
      }
      seen_percent = true;
      continue;
    }
    const bool deleted = block.block_delete && options.block_delete.value_or(machine.block_delete);
    if (block.o.kind != gcode::OKind::None) {
      seen_block = true;
      if (deleted) continue;
      if (!run_o(text, Location{cur, line_start, line - 1})) return Next::Error;
      continue;
    }
    if (block.empty && block.sets.empty()) continue;
    seen_block = true;
    if (deleted) continue;  // '/' line skipped
    params.apply(block.sets);
    if (block.empty) continue;  // settings only
    if (!interp.execute(block, parser.text(), line, pending)) {
      const gcode::Fault& f = interp.fault();
      return fail(f.code, text, f.byte_pos, f.message);
    }
    if (interp.ended()) {
      ended = true;
      end_line = line;
      end_what = block.m_stop == 30 ? "M30" : "M2";
      end_what += " on line " + std::to_string(line);
    }
  }
}

ProgramReader::Next ProgramReader::Impl::read(Segment& out) {
  // a plain reading (a program run from its start) takes the segments as
  // they come, without a copy through the queue
  if (options.start_line == 0 && !options.single_block && !options.laser_off) return read_program(out);
  for (;;) {
    if (queued_next < queued.size()) {
      out = queued[queued_next++];
      if (queued_next == queued.size()) {
        queued.clear();
        queued_next = 0;
      }
      emitted_any = true;
      last_line = out.line;
      last_segment = out;
      return Next::Segment;
    }
    Segment s;
    const Next n = read_program(s);
    if (n == Next::Error) return n;
    if (n == Next::End) {
      if (options.start_line > 0 && !reached_start) {
        error = make_error(ErrorCode::GcodeBadValue,
                           "run from line " + std::to_string(options.start_line) +
                               ": the program makes no move on or after that line (it ends on line " +
                               std::to_string(line) + "); expected the line of a move",
                           file, options.start_line, 0);
        state = State::Failed;
        return Next::Error;
      }
      return n;
    }
    if (options.laser_off) {
      s.laser = LaserMode::Off;
      s.power_pct = 0.0;
    }
    if (options.start_line > 0 && !reached_start) {
      if (s.line < options.start_line) continue;  // read, not moved
      reached_start = true;
      if (!approach_to(s)) return Next::Error;
    } else if (options.single_block && emitted_any && s.line != last_line && !last_segment.pause) {
      queued.push_back(pause_at(last_segment));
    }
    queued.push_back(s);
  }
}

// Run from line: from where the machine stands (options.start) to where
// `first` begins, at rapid with the beam off, never lower than the higher
// of the two Z's on the way across.
bool ProgramReader::Impl::approach_to(const Segment& first) {
  Segment r = first;
  r.kind = MotionKind::Rapid;
  r.laser = LaserMode::Off;
  r.power_pct = 0.0;
  r.feed_mm_s = 0.0;
  r.duration_s = 0.0;
  r.dwell_s = 0.0;
  r.pause = false;
  r.wait_input = -1;
  r.extra_turns = 0;
  const Pose& target = first.start;
  const double safe_z = std::max(options.start[2], target[2]);
  Pose at = options.start;
  const auto go = [&](const Pose& to) {
    if (to == at) return;
    r.start = at;
    r.end = to;
    queued.push_back(r);
    at = to;
  };
  Pose up = at;
  up[2] = safe_z;
  go(up);
  Pose across = target;
  across[2] = safe_z;
  go(across);
  go(target);
  return true;
}

// Single block: a stop after `after`, as M0's.
Segment ProgramReader::Impl::pause_at(const Segment& after) const {
  Segment p = after;
  p.kind = MotionKind::Dwell;
  p.start = after.end;
  p.dwell_s = 2.0 * machine.period_s();
  p.laser = LaserMode::Off;
  p.power_pct = 0.0;
  p.feed_mm_s = 0.0;
  p.duration_s = 0.0;
  p.wait_input = -1;
  p.pause = true;
  return p;
}

bool ProgramReader::Impl::release_held() {
  if (interp.finish(pending)) return true;
  const gcode::Fault& f = interp.fault();
  error = make_error(f.code, f.message, file, line, 0);
  pending.clear();
  state = State::Failed;
  return false;
}

// The end of the file being read: the program's end, or an error when a
// subroutine, a skip or a control structure is still open.
ProgramReader::Next ProgramReader::Impl::at_file_end() {
  auto fail_here = [&](const Location& at, std::string message, std::uint32_t col = 1) {
    error = make_error(ErrorCode::GcodeFlow, std::move(message), files[at.file].path, at.line + 1, col);
    pending.clear();
    state = State::Failed;
    return Next::Error;
  };
  const std::string where = "found the end of " + file;
  switch (skip) {
    case Skip::None: break;
    case Skip::ToSub: {
      std::string looked = "not defined before the call, not later in " + file;
      if (skip_label.front() == '<') {
        looked += ", and no file " + skip_label.substr(1, skip_label.size() - 2) +
                  ".ngc in the program's folder or machine.subroutine_path";
      }
      return fail_here(skip_from,
                       "subroutine " + o_name(skip_label) + " not found: " + looked + "; expected " +
                           o_name(skip_label) + " sub … " + o_name(skip_label) + " endsub",
                       skip_col);
    }
    case Skip::SubBody:
      return fail_here(skip_from,
                       where + " inside the definition of " + o_name(skip_label) + "; expected " +
                           o_name(skip_label) + " endsub",
                       skip_col);
    case Skip::IfBranch:
    case Skip::ToEndIf:
      return fail_here(skip_from,
                       where + " before " + o_name(skip_label) + " endif; expected one for this " +
                           o_name(skip_label) + " if",
                       skip_col);
    case Skip::LoopEnd:
    case Skip::ToDoTest:
      return fail_here(skip_from,
                       where + " before " + o_name(skip_label) + " " +
                           o_keyword(skip_end == gcode::OKind::None ? gcode::OKind::While : skip_end) +
                           "; expected the end of this loop",
                       skip_col);
  }
  Frame& f = frames.back();
  if (frames.size() > 1) {
    return fail_here(Location{cur, 0, line}, where + " inside subroutine " + o_name(f.sub) +
                                                 " (called from " + files[f.return_to.file].path + ":" +
                                                 std::to_string(f.return_to.line) + "); expected " +
                                                 o_name(f.sub) + " endsub");
  }
  if (!f.controls.empty()) {
    const Control& c = f.controls.back();
    const char* end = c.kind == gcode::OKind::If      ? "endif"
                      : c.kind == gcode::OKind::While ? "endwhile"
                      : c.kind == gcode::OKind::Do    ? "while"
                                                      : "endrepeat";
    return fail_here(Location{0, 0, c.line - 1},
                     where + " with " + o_name(c.label) + " " + o_keyword(c.kind) + " still open; expected " +
                         o_name(c.label) + " " + end + " before it",
                     c.col);
  }
  if (!release_held()) return Next::Error;
  if (!pending.empty()) return Next::Segment;
  state = State::Ended;
  return Next::End;
}

void ProgramReader::Impl::start_skip(Skip what, const std::string& label, gcode::OKind end) {
  skip = what;
  skip_label = label;
  skip_end = end;
  skip_from = Location{cur, 0, line - 1};
  skip_col = column_of(parser.text().original, parser.text().byte_pos(block.o.word));
}

bool ProgramReader::Impl::values(std::string_view text) {
  if (parser.o_values(block, args)) return true;
  const gcode::Fault& f = parser.fault();
  fail(f.code, text, f.byte_pos, f.message);
  return false;
}

// To a line read before (a loop's start, a call's return) or a subroutine.
bool ProgramReader::Impl::jump(const Location& to) {
  if (++jumps_without_motion > kMaxJumpsWithoutMotion) {
    error = make_error(ErrorCode::GcodeFlow,
                       "found " + std::to_string(kMaxJumpsWithoutMotion) +
                           " loop passes or calls in a row without a move or dwell that takes "
                           "time: an endless loop; "
                           "expected each loop to end (check its condition)",
                       file, line, 1);
    state = State::Failed;
    return false;
  }
  OpenFile& f = files[to.file];
  if (!f.src) {
    std::string why;
    f.src = gcode::LineSource::open_file(f.path, why);
    if (!f.src) {
      error = make_error(ErrorCode::FileNotFound, "cannot reopen subroutine file '" + f.path + "': " + why,
                         file, line, 1);
      state = State::Failed;
      return false;
    }
  }
  if (!f.src->seek(to.offset)) {
    error = make_error(ErrorCode::FileNotFound, "cannot go back in '" + f.path + "': " + f.src->read_error(),
                       file, line, 1);
    state = State::Failed;
    return false;
  }
  if (cur == 0) main_lines = std::max(main_lines, line);  // leaving, or going back in, the program
  cur = to.file;
  in = f.src.get();
  file = f.path;
  line = to.line;
  // Subroutine files no call in progress reads are closed (their buffer freed).
  for (std::size_t i = 1; i < files.size(); ++i) {
    if (i == cur || !files[i].src) continue;
    const bool in_use =
        std::any_of(frames.begin(), frames.end(), [&](const Frame& fr) { return fr.return_to.file == i; });
    if (!in_use) files[i].src.reset();
  }
  return true;
}

Control* ProgramReader::Impl::find_loop(const std::string& label) {
  auto& cs = frames.back().controls;
  for (auto it = cs.rbegin(); it != cs.rend(); ++it) {
    if (it->label == label && it->kind != gcode::OKind::If) return &*it;
  }
  return nullptr;
}

// "o<name> call [args]": a new frame, then to the subroutine: defined
// already, else its file <name>.ngc, else later in this file (LinuxCNC's order).
bool ProgramReader::Impl::call(std::string_view text, const Location& after) {
  const std::string& label = block.o.label;
  if (frames.size() > kMaxCallDepth) {
    fail_o(text, "found " + o_name(label) + " call nested " + std::to_string(kMaxCallDepth + 1) +
                     " deep; expected at most " + std::to_string(kMaxCallDepth) +
                     " calls in progress (a subroutine calling itself without end?)");
    return false;
  }
  if (!values(text)) return false;
  Frame f;
  f.sub = label;
  f.return_to = after;
  f.saved = params.enter(args);
  frames.push_back(std::move(f));
  interp.enter_call();
  params.set_global("_value", 0.0);
  params.set_global("_value_returned", 0.0);
  if (auto it = subs.find(label); it != subs.end()) return jump(it->second);
  if (label.front() == '<') {
    const std::string stem = label.substr(1, label.size() - 2);
    // a name, never a path: o</etc/x> or o<../x> would read files outside
    // the folders a program's subroutines come from
    if (stem.find_first_of("/\\") != std::string::npos || stem == "." || stem == "..") {
      fail_o(text, "found " + o_name(label) +
                       " call: a subroutine's name is a path; expected a plain "
                       "name, whose file <name>.ngc is looked for in the program's folder and "
                       "machine.subroutine_path");
      return false;
    }
    const std::string name = stem + ".ngc";
    std::vector<std::filesystem::path> dirs;
    if (options.program_dir) {
      if (!options.program_dir->empty()) dirs.emplace_back(*options.program_dir);
    } else if (!from_memory) {
      dirs.push_back(std::filesystem::path(files[0].path).parent_path());
    }
    for (const std::string& d : machine.subroutine_path) dirs.emplace_back(d);
    for (const auto& dir : dirs) {
      std::error_code ec;
      const std::filesystem::path candidate = dir / name;  // a bare program name: the working folder
      if (!std::filesystem::is_regular_file(candidate, ec)) continue;
      const std::string path = candidate.string();
      if (options.file_policy) {
        if (const Status may = options.file_policy(path); !may) {
          fail_o(text, "subroutine " + o_name(label) + ": its file " + path +
                           " is refused: " + may.error().message);
          return false;
        }
      }
      std::size_t index = 0;
      while (index < files.size() && files[index].path != path) ++index;
      if (index == files.size()) files.push_back(OpenFile{path, nullptr});
      if (!jump(Location{index, 0, 0})) return false;
      start_skip(Skip::ToSub, label);
      skip_from = Location{after.file, 0, after.line - 1};
      return true;
    }
  }
  if (cur != 0) {
    fail_o(text, "subroutine " + o_name(label) +
                     " not found: not defined before the call and no "
                     "file for it; expected it defined in the program or in its own file " +
                     (label.front() == '<' ? label.substr(1, label.size() - 2) + ".ngc" : "") +
                     " in the program's folder or machine.subroutine_path");
    return false;
  }
  start_skip(Skip::ToSub, label);  // later in the program (LinuxCNC's forward search)
  return true;
}

bool ProgramReader::Impl::run_o(std::string_view text, const Location& here) {
  using gcode::OKind;
  const gcode::OWord& o = block.o;
  const std::string& label = o.label;
  const std::string name = o_name(label);
  const Location after{cur, src().tell(), line};
  const std::uint32_t col = column_of(text, parser.text().byte_pos(o.word));
  Frame& f = frames.back();
  auto& cs = f.controls;
  auto expect_top = [&](OKind opened, const char* what) -> Control* {
    if (!cs.empty() && cs.back().label == label && cs.back().kind == opened) return &cs.back();
    std::string open_now = cs.empty() ? std::string("none is open")
                                      : o_name(cs.back().label) + " " + o_keyword(cs.back().kind) +
                                            " (line " + std::to_string(cs.back().line) + ") is the one open";
    fail_o(text, "found " + name + " " + what + " with no " + name + " " + o_keyword(opened) +
                     " open here (" + open_now + "); expected each " + what +
                     " to close the structure opened last, with the same label");
    return nullptr;
  };
  switch (o.kind) {
    case OKind::None: return true;
    case OKind::Sub: {
      if (frames.size() > 1) {
        fail_o(text, "found " + name + " sub inside subroutine " + o_name(f.sub) +
                         "; expected subroutine definitions outside any other");
        return false;
      }
      if (auto it = sub_lines.find(label); it != sub_lines.end() && it->second != line) {
        fail_o(text, "found a second definition of " + name + " (the first is on line " +
                         std::to_string(it->second) + "); expected each subroutine defined once");
        return false;
      }
      subs[label] = after;
      sub_lines[label] = line;
      start_skip(Skip::SubBody, label);
      return true;
    }
    case OKind::EndSub:
    case OKind::Return: {
      if (frames.size() == 1) {
        fail_o(text, "found " + name + " " + o_keyword(o.kind) +
                         " outside a subroutine; expected it only inside " + name + " sub");
        return false;
      }
      // a return may carry any label (LinuxCNC: it leaves the running call);
      // an endsub closes its own sub
      if (o.kind == gcode::OKind::EndSub && label != f.sub) {
        fail_o(text, "found " + name + " endsub inside subroutine " + o_name(f.sub) + "; expected " +
                         o_name(f.sub) + " endsub");
        return false;
      }
      if (!values(text)) return false;
      params.leave(f.saved);
      params.set_global("_value", args.empty() ? 0.0 : args.front());
      params.set_global("_value_returned", args.empty() ? 0.0 : 1.0);
      const Location back = f.return_to;
      frames.pop_back();
      interp.leave_call();  // an M73's modal state comes back
      return jump(back);
    }
    case OKind::Call: return call(text, after);
    case OKind::If: {
      if (!values(text)) return false;
      cs.push_back(Control{OKind::If, label, here, line, 0, col});
      if (args[0] == 0.0) start_skip(Skip::IfBranch, label);
      return true;
    }
    case OKind::ElseIf:
    case OKind::Else:
      // reached by running: the branch before it ran, so the rest is skipped
      if (expect_top(OKind::If, o_keyword(o.kind)) == nullptr) return false;
      start_skip(Skip::ToEndIf, label);
      return true;
    case OKind::EndIf:
      if (expect_top(OKind::If, "endif") == nullptr) return false;
      cs.pop_back();
      return true;
    case OKind::While: {
      if (!values(text)) return false;
      if (!cs.empty() && cs.back().label == label && cs.back().kind == OKind::Do) {
        // the end of a do loop: back to its first line while true
        if (args[0] != 0.0) return jump(cs.back().start);
        cs.pop_back();
        return true;
      }
      if (args[0] == 0.0) {
        start_skip(Skip::LoopEnd, label, OKind::EndWhile);
        return true;
      }
      cs.push_back(Control{OKind::While, label, here, line, 0, col});
      return true;
    }
    case OKind::EndWhile: {
      Control* c = expect_top(OKind::While, "endwhile");
      if (c == nullptr) return false;
      const Location back = c->start;  // the while line, tested again
      cs.pop_back();
      return jump(back);
    }
    case OKind::Do: cs.push_back(Control{OKind::Do, label, after, line, 0, col}); return true;
    case OKind::Repeat: {
      if (!values(text)) return false;
      const double n = std::round(args[0]);
      if (!(n >= 1.0)) {
        start_skip(Skip::LoopEnd, label, OKind::EndRepeat);
        return true;
      }
      cs.push_back(
          Control{OKind::Repeat, label, after, line, static_cast<std::int64_t>(std::min(n, 1e15)) - 1, col});
      return true;
    }
    case OKind::EndRepeat: {
      Control* c = expect_top(OKind::Repeat, "endrepeat");
      if (c == nullptr) return false;
      if (c->left > 0) {
        --c->left;
        return jump(c->start);
      }
      cs.pop_back();
      return true;
    }
    case OKind::Break:
    case OKind::Continue: {
      Control* loop = find_loop(label);
      if (loop == nullptr) {
        fail_o(text, "found " + name + " " + o_keyword(o.kind) + " outside any loop " + name +
                         "; expected it inside " + name + " while, do or repeat");
        return false;
      }
      while (&cs.back() != loop) cs.pop_back();  // the ifs inside the loop end here
      const OKind kind = loop->kind;
      const OKind end = kind == OKind::While ? OKind::EndWhile
                        : kind == OKind::Do  ? OKind::While
                                             : OKind::EndRepeat;
      if (o.kind == OKind::Break) {
        cs.pop_back();
        start_skip(Skip::LoopEnd, label, end);
        return true;
      }
      if (kind == OKind::While) {  // continue: the while line tests again
        const Location back = loop->start;
        cs.pop_back();
        return jump(back);
      }
      if (kind == OKind::Do) {  // continue: to the closing while's test
        start_skip(Skip::ToDoTest, label, OKind::While);
        return true;
      }
      if (loop->left > 0) {
        --loop->left;
        return jump(loop->start);
      }
      cs.pop_back();
      start_skip(Skip::LoopEnd, label, end);
      return true;
    }
  }
  return true;
}

// A line while skipping: only an O-word with the label sought counts.
bool ProgramReader::Impl::skip_line(std::string_view text) {
  using gcode::OKind;
  if (!parser.parse_o_only(text, block)) {
    const gcode::Fault& f = parser.fault();
    fail(f.code, text, f.byte_pos, f.message);
    return false;
  }
  const gcode::OWord& o = block.o;
  if (o.kind == OKind::None || o.label != skip_label) return true;
  auto& cs = frames.back().controls;
  switch (skip) {
    case Skip::None: return true;
    case Skip::ToSub:
      if (o.kind != OKind::Sub) return true;
      subs[o.label] = Location{cur, src().tell(), line};
      sub_lines[o.label] = line;
      skip = Skip::None;  // and into the subroutine
      return true;
    case Skip::SubBody:
      if (o.kind == OKind::EndSub) skip = Skip::None;
      return true;
    case Skip::IfBranch:
      if (o.kind == OKind::ElseIf) {
        if (!values(text)) return false;
        if (args[0] != 0.0) skip = Skip::None;
      } else if (o.kind == OKind::Else) {
        skip = Skip::None;
      } else if (o.kind == OKind::EndIf) {
        skip = Skip::None;
        cs.pop_back();
      }
      return true;
    case Skip::ToEndIf:
      if (o.kind == OKind::EndIf) {
        skip = Skip::None;
        cs.pop_back();
      }
      return true;
    case Skip::LoopEnd:
      if (o.kind == skip_end) skip = Skip::None;
      return true;
    case Skip::ToDoTest:
      if (o.kind != OKind::While) return true;
      skip = Skip::None;
      if (!values(text)) return false;
      if (args[0] != 0.0) return jump(cs.back().start);
      cs.pop_back();
      return true;
  }
  return true;
}

// The machine's startup modes (MachineConfig::startup_code, admitted by the
// config's validation), run as if the program's line 0. Anything it would
// move, or an error, fails the reader at once: a config that bypassed the
// validation must not move the machine.
// The offsets a job starts from: the machine config's work offsets and tool
// table, then what the parameter file kept of earlier jobs.
bool ProgramReader::Impl::load_offsets() {
  std::vector<double>& p = params.store();
  for (int i = 0; i < kWorkOffsetCount; ++i) {
    for (int a = 0; a < kAxisCount; ++a)
      p[static_cast<std::size_t>(gcode::coord_param(i) + a)] = machine.work_offsets[i][a];
  }
  p[gcode::kParamCoordSystem] = 1.0;
  std::vector<ToolConfig> tools = machine.tools;
  std::vector<int> changed;
  if (!machine.parameter_file.empty()) {
    Result<gcode::ParameterFileData> kept = gcode::read_parameter_file(machine.parameter_file);
    if (!kept) {
      error = kept.error();
      state = State::Failed;
      return false;
    }
    for (const auto& [index, value] : kept->params) p[static_cast<std::size_t>(index)] = value;
    for (const ToolConfig& t : kept->tools) {
      auto it = std::find_if(tools.begin(), tools.end(),
                             [&t](const ToolConfig& x) { return x.number == t.number; });
      if (it == tools.end()) continue;  // no longer in the machine's table
      *it = t;
      changed.push_back(t.number);
    }
  }
  interp.load_offsets(std::move(tools), std::move(changed));
  kept_at_start = kept_state();
  return true;
}

// What a job keeps in the parameter file: the persistent parameters and the
// changed tools, as one comparable text.
std::string ProgramReader::Impl::kept_state() const {
  std::string s;
  const std::vector<double>& p = params.store();
  for (int k = gcode::kParamPersistentFirst; k <= gcode::kParamPersistentLast; ++k) {
    const double v = p[static_cast<std::size_t>(k)];
    s.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  for (const ToolConfig& t : interp.changed_tools()) {
    s += std::to_string(t.number) + ' ';
    for (int a = 0; a < 3; ++a) s.append(reinterpret_cast<const char*>(&t.offset[a]), sizeof(double));
    s.append(reinterpret_cast<const char*>(&t.diameter_mm), sizeof(double));
    s += t.description + '\n';
  }
  return s;
}

// The job's reader keeps what the program set for the next job. A failure
// is the reading's error at its end: offsets and tools that are not stored
// are never reported as kept (the job fails, an MDI G10 is refused).
bool ProgramReader::Impl::save_offsets() {
  saved = true;
  if (!options.keep_parameters || machine.parameter_file.empty()) return true;
  if (kept_state() == kept_at_start) return true;  // nothing to keep: the file stays as it is
  if (Status st = gcode::write_parameter_file(machine.parameter_file, params.store(), interp.changed_tools());
      !st) {
    error = st.error();
    error.message = "the offsets and tools this program set are not kept: " + error.message;
    state = State::Failed;
    return false;
  }
  return true;
}

void ProgramReader::Impl::run_startup() {
  run_line0(machine.startup_code, "machine.startup_code", ErrorCode::ConfigBadValue);
  if (state == State::Running)
    run_line0(options.modes, "the modes carried in from before", ErrorCode::GcodeBadValue);
}

void ProgramReader::Impl::run_line0(const std::string& code, const char* what, ErrorCode code_if_bad) {
  if (code.empty()) return;
  const char* why = nullptr;
  if (!parser.parse(code, block)) {
    why = parser.fault().message.c_str();
  } else if (!block.empty && !interp.execute(block, parser.text(), 0, pending)) {
    why = interp.fault().message.c_str();
  } else if (!pending.empty() || interp.ended()) {
    why = "it moves or ends";
  }
  if (why == nullptr) return;
  error =
      make_error(code_if_bad, std::string(what) + " \"" + code + "\": " + why + "; expected modal codes only",
                 file, 0, 0);
  pending.clear();
  state = State::Failed;
}

// A grbl system command ("$H", "$X", "$32=1"): it sets up a grbl board, not
// the job; passed over with a warning (grbl dialect only).
bool ProgramReader::Impl::grbl_system_line(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  if (i >= text.size() || text[i] != '$') return false;
  std::string_view cmd = text.substr(i);
  while (!cmd.empty() && (cmd.back() == '\r' || cmd.back() == ' ')) cmd.remove_suffix(1);
  warnings.push_back(make_error(ErrorCode::GcodeLinePassedOver,
                                "found " + quote(cmd.substr(0, 40)) +
                                    ": a grbl system command, passed over (it configures a grbl "
                                    "board; this machine's setup is its config)",
                                file, line, static_cast<std::uint32_t>(i + 1)));
  return true;
}

// Lines after the end are not run (RS274NGC); say so once if any would have.
void ProgramReader::Impl::warn_lines_after_end() {
  std::uint32_t count = 0;
  std::uint32_t first_line = 0;
  std::uint32_t first_col = 0;
  std::string first_text;
  std::string_view text;
  while (src().next(text)) {
    ++line;
    const std::size_t at = first_content(text);
    if (at == std::string_view::npos) continue;
    if (count++ == 0) {
      first_line = line;
      first_col = column_of(text, static_cast<std::uint32_t>(at));
      std::string_view excerpt = text.substr(at, 60);
      while (!excerpt.empty() && (excerpt.back() == ' ' || excerpt.back() == '\t')) {
        excerpt.remove_suffix(1);
      }
      first_text = quote(excerpt);
    }
  }
  if (count == 0 && !src().too_long()) return;
  if (src().too_long()) {
    // Not run either; but a file that goes on without line ends is worth a word.
    ++line;
    if (count++ == 0) {
      first_line = line;
      first_col = 1;
      first_text = "longer than " + std::to_string(gcode::kMaxLineBytes) + " bytes";
    }
  }
  warnings.push_back(
      make_error(ErrorCode::GcodeLinesAfterEnd,
                 "found " + std::to_string(count) + " line" + (count == 1 ? "" : "s") +
                     " after the program end (" + end_what + "), the first " + first_text +
                     "; they are not run: expected only blank lines, comments or '%' after the end",
                 file, first_line, first_col));
}

ProgramReader::ProgramReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ProgramReader::~ProgramReader() = default;

Result<std::unique_ptr<ProgramReader>> ProgramReader::open(const std::string& path,
                                                           const MachineConfig& machine,
                                                           const ReaderOptions& options) {
  std::string why;
  auto src = gcode::LineSource::open_file(path, why);
  if (!src) {
    return make_error(ErrorCode::FileNotFound,
                      "cannot open G-code program '" + path + "': " + why + "; expected a readable file",
                      path);
  }
  return std::unique_ptr<ProgramReader>(
      new ProgramReader(std::make_unique<Impl>(std::move(src), path, machine, options)));
}

std::unique_ptr<ProgramReader> ProgramReader::from_string(std::string text, std::string name,
                                                          const MachineConfig& machine,
                                                          const ReaderOptions& options) {
  auto src = std::make_unique<gcode::LineSource>(std::move(text));
  auto impl = std::make_unique<Impl>(std::move(src), std::move(name), machine, options);
  impl->from_memory = true;
  return std::unique_ptr<ProgramReader>(new ProgramReader(std::move(impl)));
}

ProgramReader::Next ProgramReader::next(Segment& out) { return impl_->read(out); }
const Diagnostic& ProgramReader::error() const { return impl_->error; }
const std::vector<Diagnostic>& ProgramReader::warnings() const { return impl_->warnings; }
std::uint32_t ProgramReader::lines_read() const {
  return impl_->cur == 0 ? std::max(impl_->main_lines, impl_->line) : impl_->main_lines;
}

std::vector<std::string> ProgramReader::files_read() const {
  std::vector<std::string> out;
  for (std::size_t i = impl_->from_memory ? 1 : 0; i < impl_->files.size(); ++i)
    out.push_back(impl_->files[i].path);
  if (!impl_->machine.parameter_file.empty()) out.push_back(impl_->machine.parameter_file);
  return out;
}

ReaderModes ProgramReader::modes() const {
  const gcode::Interpreter& in = impl_->interp;
  return ReaderModes{in.modes_block(), in.offsets(), in.coord_system(), in.inch()};
}

Result<ProgramSummary> check_program(const std::string& path, const MachineConfig& machine,
                                     const ReaderOptions& options) {
  auto opened = ProgramReader::open(path, machine, options);
  if (!opened) return opened.error();
  ProgramReader& reader = **opened;

  ProgramSummary sum;
  sum.min = options.start;
  sum.max = options.start;
  Segment s;
  for (;;) {
    const ProgramReader::Next n = reader.next(s);
    if (n == ProgramReader::Next::Error) return reader.error();
    if (n == ProgramReader::Next::End) break;
    ++sum.segments;
    sum.min = sum.min.cwiseMin(s.end);
    sum.max = sum.max.cwiseMax(s.end);
    double length = 0.0;
    Pose lo = s.start.cwiseMin(s.end);
    Pose hi = s.start.cwiseMax(s.end);
    switch (s.kind) {
      case MotionKind::Dwell: continue;
      case MotionKind::Rapid:
      case MotionKind::Linear: length = (s.end.head<3>() - s.start.head<3>()).norm(); break;
      case MotionKind::Arc: {
        length = gcode::arc_length_mm(s);
        Vec3 arc_lo, arc_hi;
        gcode::arc_bounds(s, arc_lo, arc_hi);
        lo.head<3>() = lo.head<3>().cwiseMin(arc_lo);
        hi.head<3>() = hi.head<3>().cwiseMax(arc_hi);
        sum.min.head<3>() = sum.min.head<3>().cwiseMin(arc_lo);
        sum.max.head<3>() = sum.max.head<3>().cwiseMax(arc_hi);
        break;
      }
    }
    if (s.kind != MotionKind::Rapid) {
      sum.feed_min = sum.feed_min.cwiseMin(lo);
      sum.feed_max = sum.feed_max.cwiseMax(hi);
    }
    sum.path_length_mm += length;
    if (s.kind != MotionKind::Rapid) sum.feed_length_mm += length;
  }
  sum.lines = reader.lines_read();
  sum.warnings = reader.warnings();
  sum.end = reader.modes();
  sum.files = reader.files_read();
  return sum;
}

}  // namespace lcnc
