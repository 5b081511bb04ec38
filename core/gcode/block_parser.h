// Step 1 of reading a line: the block parser. Turns one line of RS274NGC text
// into a Block (its words, its G and M codes sorted by modal group) or a Fault
// saying what was found, where, and what was expected.
//
// As LinuxCNC (rs274ngc read_text/close_and_downcase, read_items), the line is
// first compacted: comments, spaces and tabs outside comments are dropped and
// letters upper-cased, so "g 0 1 x 1 0.5" reads as "G01X10.5". Each compacted
// character remembers its byte offset in the original line, so every fault
// points at a column of what the user wrote.
//
// Syntax: ['/'] ['N' number] { letter number } ; a number is [+-] digits
// ['.' digits] or [+-] '.' digits (no exponent). Comments are "( ... )" (not
// nested, closed on the line) and everything after ';'. A '%' line is a
// program delimiter and may carry only a comment.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/error.h"
#include "common/quote.h"

namespace lcnc::gcode {

// '0' … '9' (std::isdigit depends on the locale and takes an int).
[[nodiscard]] constexpr bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }

// G modal groups of the subset (LinuxCNC numbers in kGGroupNumber). G80
// (cancel canned cycle) is in the motion group, as in LinuxCNC: after it,
// axis words need a new G0..G3.
enum class GGroup : std::uint8_t {
  NonModal,     // 0: G4 G10 G28 G28.1 G30 G30.1 G52 G53 G92 G92.1 G92.2 G92.3
  Motion,       // 1: G0 G1 G2 G3, G80, canned cycles G73 G81 G82 G83 G85 G89
  Plane,        // 2: G17 G18 G19
  Distance,     // 3: G90 G91
  ArcDistance,  // 4: G90.1 G91.1
  FeedMode,     // 5: G93 G94
  Units,        // 6: G20 G21
  CoordSystem,  // 12: G54 .. G59, G59.1 .. G59.3
  PathControl,  // 13: G61 G61.1 G64
  CutterComp,   // 7: G40 G41 G41.1 G42 G42.1 (cutter/kerf compensation)
  ToolLength,   // 8: G43 G43.1 G43.2 G49
  RetractMode,  // 10: G98 G99 (canned cycles)
};
inline constexpr int kGGroupCount = 12;
inline constexpr std::array<int, kGGroupCount> kGGroupNumber = {0, 1, 2, 3, 4, 5, 6, 12, 13, 7, 8, 10};
inline constexpr std::array<const char*, kGGroupCount> kGGroupName = {"non-modal",
                                                                      "motion",
                                                                      "plane selection",
                                                                      "distance mode",
                                                                      "arc distance mode",
                                                                      "feed rate mode",
                                                                      "units",
                                                                      "coordinate system",
                                                                      "path control mode",
                                                                      "cutter radius compensation",
                                                                      "tool length offset",
                                                                      "canned cycle return mode"};

[[nodiscard]] constexpr int group_index(GGroup g) noexcept { return static_cast<int>(g); }

// [begin, end) of a word in LineText::compact.
struct Span {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};

// The line being read: the original text and its compacted form.
struct LineText {
  std::string_view original;
  std::vector<char> compact;          // capacity reused from line to line
  std::vector<std::uint32_t> offset;  // byte offset in `original` of each compact char
  std::uint32_t size = 0;             // compact chars in use

  [[nodiscard]] std::string_view text(Span s) const { return {compact.data() + s.begin, s.end - s.begin}; }
  [[nodiscard]] std::uint32_t byte_pos(Span s) const { return offset[s.begin]; }
};

// What went wrong: code, byte offset in the original line, message.
struct Fault {
  ErrorCode code = ErrorCode::Ok;
  std::uint32_t byte_pos = 0;
  std::string message;
};

inline constexpr int kLetterCount = 26;
[[nodiscard]] constexpr int letter_index(char upper) noexcept { return upper - 'A'; }

// A parameter setting of the block (#5 = ..., #<name> = ...): it takes
// effect after every value of its line has been read (RS274NGC).
struct ParamSet {
  int index = 0;     // #index, or 0 for a named one
  std::string name;  // lower-cased, without < >
  double value = 0.0;
  Span word{};
};

class ParameterReader;

// An O-word line's keyword (LinuxCNC's O-codes): subroutines and control flow.
enum class OKind : std::uint8_t {
  None,
  Sub,
  EndSub,
  Return,
  Call,
  If,
  ElseIf,
  Else,
  EndIf,
  While,
  EndWhile,
  Do,
  Repeat,
  EndRepeat,
  Break,
  Continue
};
[[nodiscard]] const char* o_keyword(OKind k) noexcept;  // "sub", "endsub", ...

// A call passes at most #1 … #30 (LinuxCNC).
inline constexpr std::uint32_t kMaxCallArgs = 30;

// An O-word line: "O100 while [#1 LT 3]", "o<drill> call [2] [0.5]". Its
// bracketed values are read only when the line runs (o_values()), as
// LinuxCNC does: a skipped branch's expressions are never evaluated.
struct OWord {
  OKind kind = OKind::None;
  std::string label;             // "100" or "<name>" lower-cased: what matches
  Span word{};                   // the O-word and its keyword
  std::uint32_t args_begin = 0;  // compact index of the first '[' value
  std::uint32_t arg_count = 0;   // bracketed values after the keyword
};

// One parsed block. Word values are as written (program units); codes are
// stored ×10 (G61.1 -> 611), -1 when the group is not in the block.
struct Block {
  bool empty = true;           // no words: blank or comment-only line
  bool percent = false;        // a '%' program delimiter line
  bool block_delete = false;   // started with '/'
  std::uint32_t letters = 0;   // bit letter_index(L) for each word other than G, M, N
  std::uint8_t axis_mask = 0;  // bit index(Axis) for each axis word
  Span first_axis_word{};
  std::array<double, kLetterCount> value{};
  std::array<Span, kLetterCount> word{};
  std::array<std::int16_t, kGGroupCount> g{};
  std::array<Span, kGGroupCount> g_word{};
  std::int16_t m_stop = -1;     // 0 or 1 or 60 (pause), 2 or 30 (end)
  std::int16_t m_laser = -1;    // 3, 4 or 5
  std::int16_t m_tool = -1;     // 6 (tool change) or 61 (set the tool in the spindle)
  std::int16_t m_context = -1;  // 70 save, 71 forget, 72 restore, 73 save till return
  std::int16_t m_io = -1;  // 62 63 64 65 (digital out P), 66 (wait on input P L Q), 67 68 (analog out E Q)
  std::int16_t m_override =
      -1;  // 48 49 (both overrides on/off), 50 51 52 53 P (feed, speed, adaptive, feed hold)
  bool m7 = false, m8 = false, m9 = false;
  Span m_stop_word{}, m_laser_word{}, m_tool_word{}, m_context_word{}, m_io_word{}, m7_word{}, m8_word{},
      m9_word{}, m_override_word{};
  // Polar coordinates (LinuxCNC's): @ the radius and ^ the angle (degrees)
  // of X Y about the program's origin, in place of X and Y (whose bits in
  // axis_mask they set). Bit 0: @ given, bit 1: ^ given.
  std::uint8_t polar = 0;
  double polar_radius = 0.0, polar_angle_deg = 0.0;
  Span polar_word{};           // the first of them
  std::vector<ParamSet> sets;  // in the order written (capacity reused)
  OWord o;                     // kind None unless an O-word line (then nothing else is set)

  [[nodiscard]] bool has(char upper) const noexcept { return ((letters >> letter_index(upper)) & 1u) != 0; }
  [[nodiscard]] double operator[](char upper) const noexcept { return value[letter_index(upper)]; }
  [[nodiscard]] Span span(char upper) const noexcept { return word[letter_index(upper)]; }
  [[nodiscard]] std::int16_t code(GGroup grp) const noexcept { return g[group_index(grp)]; }
  [[nodiscard]] Span code_word(GGroup grp) const noexcept { return g_word[group_index(grp)]; }
};

class BlockParser {
 public:
  // present_axes: bit index(Axis) set for each axis the machine has.
  explicit BlockParser(std::uint8_t present_axes) : present_axes_(present_axes) {}

  // Where '#' and expressions read their values; without one (nullptr, the
  // default) a line with '#' or '[' is refused as outside the subset.
  void set_parameters(const ParameterReader* params) noexcept { params_ = params; }

  // Parses `line` (kept by the caller until the next parse) into `out`.
  // false on error; fault() says what and where.
  [[nodiscard]] bool parse(std::string_view line, Block& out);
  // Reads only an O-word line (out.o), leaving any other line unread: how
  // lines are passed over while skipping a branch or a definition. false on
  // an error in the line's comments or in its O-word.
  [[nodiscard]] bool parse_o_only(std::string_view line, Block& out);
  // The bracketed values of the O-word line just parsed, in order.
  [[nodiscard]] bool o_values(const Block& b, std::vector<double>& out);

  [[nodiscard]] const LineText& text() const noexcept { return text_; }
  [[nodiscard]] const Fault& fault() const noexcept { return fault_; }

 private:
  bool compact(std::string_view line);
  bool read_number(std::uint32_t& i, std::uint32_t letter_at_pos, double& value);
  bool read_word(std::uint32_t& i, Block& out);
  bool read_polar(std::uint32_t& i, Block& out);
  bool read_spindle(std::uint32_t& i);
  bool read_expression(std::uint32_t& i, double& value);
  bool read_setting(std::uint32_t& i, Block& out);
  bool read_prefix(std::string_view line, Block& out, std::uint32_t& i);
  bool read_o(std::uint32_t& i, Block& out);
  bool read_g(Span w, double value, Block& out);
  bool read_m(Span w, double value, Block& out);
  bool malformed_number(std::uint32_t i);
  [[nodiscard]] std::uint32_t word_before(std::uint32_t end) const;
  bool fail(ErrorCode code, std::uint32_t byte_pos, std::string message);
  [[nodiscard]] std::string quoted(Span s) const;
  [[nodiscard]] std::string quoted(std::uint32_t begin, std::uint32_t end) const;

  std::uint8_t present_axes_;
  const ParameterReader* params_ = nullptr;
  LineText text_;
  std::uint32_t words_begin_ = 0;  // compact index of the first word (after '/' and N)
  Fault fault_;
};

// "G38.2" from a code stored ×10.
[[nodiscard]] std::string g_code_name(int tenths);

}  // namespace lcnc::gcode
