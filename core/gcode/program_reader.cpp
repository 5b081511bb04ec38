// ProgramReader: line source -> block parser -> interpreter, one line at a
// time, so memory stays bounded whatever the program's length. check_program
// runs the same reader to the end and sums up what it produced.
#include "gcode/program_reader.h"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <utility>

#include "gcode/arc_geometry.h"
#include "gcode/block_parser.h"
#include "gcode/expression.h"
#include "gcode/gcode_tolerances.h"
#include "gcode/interpreter.h"
#include "gcode/line_source.h"

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
// ones, global when the name starts with '_', else local (to the program
// here; to a subroutine's call once O-word calls come).
class Parameters final : public gcode::ParameterReader {
 public:
  Parameters() : numbered_(gcode::kMaxParameterIndex + 1, 0.0) {}
  [[nodiscard]] double numbered(int index) const override { return numbered_[index]; }
  [[nodiscard]] bool named(std::string_view name, double& out) const override {
    const auto& map = name.front() == '_' ? globals_ : locals_;
    auto it = map.find(std::string(name));
    if (it == map.end()) return false;
    out = it->second;
    return true;
  }
  // A line's settings, after all of its values have been read.
  void apply(const std::vector<gcode::ParamSet>& sets) {
    for (const gcode::ParamSet& s : sets) {
      if (s.index > 0) {
        numbered_[s.index] = s.value;
      } else {
        (s.name.front() == '_' ? globals_ : locals_)[s.name] = s.value;
      }
    }
  }

 private:
  std::vector<double> numbered_;
  std::unordered_map<std::string, double> globals_;
  std::unordered_map<std::string, double> locals_;
};

}  // namespace

struct ProgramReader::Impl {
  Impl(std::unique_ptr<gcode::LineSource> src, std::string name, const MachineConfig& m,
       const ReaderOptions& opts)
      : file(std::move(name)),
        machine(m),
        options(opts),
        source(std::move(src)),
        parser(present_axes(machine)),
        interp(machine, options.start) {
    parser.set_parameters(&params);
    run_startup();
  }

  enum class State : std::uint8_t { Running, Ended, Failed };

  Next read(Segment& out);
  bool run_line(std::string_view line);
  void run_startup();
  void warn_lines_after_end();
  Next fail(ErrorCode code, std::string_view line, std::uint32_t byte_pos, std::string message);

  std::string file;
  MachineConfig machine;  // before interp, which keeps a reference to it
  ReaderOptions options;
  std::unique_ptr<gcode::LineSource> source;
  Parameters params;  // before parser, which reads them
  gcode::BlockParser parser;
  gcode::Block block;
  gcode::Interpreter interp;
  gcode::SegmentBuffer pending;

  State state = State::Running;
  Diagnostic error;
  std::vector<Diagnostic> warnings;
  std::uint32_t line = 0;

  bool seen_block = false;    // a line with words has been read
  bool seen_percent = false;  // the opening '%' has been read
  bool ended = false;         // M2, M30 or the closing '%'
  std::uint32_t end_line = 0;
  std::string end_what;
};

ProgramReader::Next ProgramReader::Impl::fail(ErrorCode code, std::string_view text,
                                              std::uint32_t byte_pos, std::string message) {
  error = make_error(code, std::move(message), file, line, column_of(text, byte_pos));
  pending.clear();
  state = State::Failed;
  return Next::Error;
}

ProgramReader::Next ProgramReader::Impl::read(Segment& out) {
  for (;;) {
    switch (state) {
      case State::Ended: return Next::End;
      case State::Failed: return Next::Error;
      case State::Running: break;
    }
    if (!pending.empty()) {
      out = pending.pop();
      return Next::Segment;
    }
    if (ended) {
      warn_lines_after_end();
      state = State::Ended;
      continue;
    }
    std::string_view text;
    if (!source->next(text)) {
      if (source->too_long()) {
        error = make_error(ErrorCode::GcodeSyntax,
                           "found a line longer than " + std::to_string(gcode::kMaxLineBytes) +
                               " bytes (no line end within it); expected program lines of at "
                               "most " + std::to_string(gcode::kMaxLineBytes) +
                               " bytes ending in a line feed: is this a G-code text file?",
                           file, line + 1, 0);
        state = State::Failed;
        return Next::Error;
      }
      if (!source->read_error().empty()) {
        error = make_error(ErrorCode::FileNotFound,
                           "reading stopped after line " + std::to_string(line) + ": " +
                               source->read_error() + "; expected to read the whole program",
                           file, line + 1, 0);
        state = State::Failed;
        return Next::Error;
      }
      state = State::Ended;
      continue;
    }
    ++line;
    pending.clear();
    if (!parser.parse(text, block)) {
      const gcode::Fault& f = parser.fault();
      return fail(f.code, text, f.byte_pos, f.message);
    }
    if (block.percent) {
      // The first '%' opens the program, the next one ends it (LinuxCNC).
      if (seen_block || seen_percent) {
        ended = true;
        end_line = line;
        end_what = "the closing '%'";
      }
      seen_percent = true;
      continue;
    }
    if (block.empty && block.sets.empty()) continue;
    seen_block = true;
    if (block.block_delete && options.block_delete.value_or(machine.block_delete)) continue;  // '/' line skipped
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

// The machine's startup modes (MachineConfig::startup_code, admitted by the
// config's validation), run as if the program's line 0. Anything it would
// move, or an error, fails the reader at once: a config that bypassed the
// validation must not move the machine.
void ProgramReader::Impl::run_startup() {
  if (machine.startup_code.empty()) return;
  const std::string& code = machine.startup_code;
  const char* why = nullptr;
  if (!parser.parse(code, block)) {
    why = parser.fault().message.c_str();
  } else if (!block.empty && !interp.execute(block, parser.text(), 0, pending)) {
    why = interp.fault().message.c_str();
  } else if (!pending.empty() || interp.ended()) {
    why = "it moves or ends";
  }
  if (why == nullptr) return;
  error = make_error(ErrorCode::ConfigBadValue,
                     std::string("machine.startup_code \"") + code + "\": " + why +
                         "; expected modal codes only",
                     file, 0, 0);
  pending.clear();
  state = State::Failed;
}

// Lines after the end are not run (RS274NGC); say so once if any would have.
void ProgramReader::Impl::warn_lines_after_end() {
  std::uint32_t count = 0;
  std::uint32_t first_line = 0;
  std::uint32_t first_col = 0;
  std::string first_text;
  std::string_view text;
  while (source->next(text)) {
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
      first_text = gcode::quote(excerpt);
    }
  }
  if (count == 0 && !source->too_long()) return;
  if (source->too_long()) {
    // Not run either; but a file that goes on without line ends is worth a word.
    ++line;
    if (count++ == 0) {
      first_line = line;
      first_col = 1;
      first_text = "longer than " + std::to_string(gcode::kMaxLineBytes) + " bytes";
    }
  }
  warnings.push_back(make_error(
      ErrorCode::GcodeLinesAfterEnd,
      "found " + std::to_string(count) + " line" + (count == 1 ? "" : "s") +
          " after the program end (" + end_what + "), the first " + first_text +
          "; they are not run: expected only blank lines, comments or '%' after the end",
      file, first_line, first_col));
}

ProgramReader::ProgramReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ProgramReader::~ProgramReader() = default;

Result<std::unique_ptr<ProgramReader>> ProgramReader::open(const std::string& path,
                                                           const MachineConfig& machine,
                                                           ReaderOptions options) {
  std::string why;
  auto src = gcode::LineSource::open_file(path, why);
  if (!src) {
    return make_error(ErrorCode::FileNotFound,
                      "cannot open G-code program '" + path + "': " + why +
                          "; expected a readable file",
                      path);
  }
  return std::unique_ptr<ProgramReader>(
      new ProgramReader(std::make_unique<Impl>(std::move(src), path, machine, options)));
}

std::unique_ptr<ProgramReader> ProgramReader::from_string(std::string text, std::string name,
                                                          const MachineConfig& machine,
                                                          ReaderOptions options) {
  auto src = std::make_unique<gcode::LineSource>(std::move(text));
  return std::unique_ptr<ProgramReader>(
      new ProgramReader(std::make_unique<Impl>(std::move(src), std::move(name), machine, options)));
}

ProgramReader::Next ProgramReader::next(Segment& out) { return impl_->read(out); }
const Diagnostic& ProgramReader::error() const { return impl_->error; }
const std::vector<Diagnostic>& ProgramReader::warnings() const { return impl_->warnings; }
std::uint32_t ProgramReader::lines_read() const { return impl_->line; }

Result<ProgramSummary> check_program(const std::string& path, const MachineConfig& machine,
                                     ReaderOptions options) {
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
    switch (s.kind) {
      case MotionKind::Dwell:
        continue;
      case MotionKind::Rapid:
      case MotionKind::Linear:
        length = (s.end.head<3>() - s.start.head<3>()).norm();
        break;
      case MotionKind::Arc: {
        length = gcode::arc_length_mm(s);
        Vec3 lo, hi;
        gcode::arc_bounds(s, lo, hi);
        sum.min.head<3>() = sum.min.head<3>().cwiseMin(lo);
        sum.max.head<3>() = sum.max.head<3>().cwiseMax(hi);
        break;
      }
    }
    sum.path_length_mm += length;
    if (s.kind != MotionKind::Rapid) sum.feed_length_mm += length;
  }
  sum.lines = reader.lines_read();
  sum.warnings = reader.warnings();
  return sum;
}

}  // namespace lcnc
