#include "gcode/block_parser.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "gcode/expression.h"
#include "gcode/gcode_tolerances.h"

namespace lcnc::gcode {
namespace {

constexpr const char* kSupportedWords = "G M N X Y Z A B C I J K R F S P Q T H L D E";
constexpr const char* kSupportedGCodes =
    "G0 G1 G2 G3 G4 G10 G17 G18 G19 G20 G21 G28 G28.1 G30 G30.1 G40 G41 G41.1 G42 G42.1 G43 G43.1 G43.2 G49 "
    "G52 "
    "G53 G54-G59 G59.1 G59.2 G59.3 G61 G61.1 G64 G73 G80 G81 G82 G83 G85 G86 G89 G90 G91 G90.1 "
    "G91.1 G92 G92.1 G92.2 G92.3 G93 G94 G98 G99";
constexpr const char* kSupportedMCodes =
    "M0 M1 M2 M3 M4 M5 M6 M7 M8 M9 M30 M60 M61 M62 M63 M64 M65 M66 M67 M68 M70 M71 M72 M73 M48 M49 M50 M51 "
    "M52 M53";

// Exact powers of ten: a double holds 10^k exactly for k <= 22.
constexpr double kPow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                             1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
// Digits that fit a double exactly (10^15 < 2^53): then mantissa / 10^frac is
// one correctly rounded division, the same result as strtod. (The mantissa
// wraps past 19 digits; such numbers take the slow path.)
constexpr std::uint32_t kFastDigits = 15;

// What compact() does with each byte: keep it (upper-cased), drop it
// (blanks), or look closer (comments).
enum class CharClass : std::uint8_t { Keep, Blank, Special };
constexpr std::array<CharClass, 256> kCharClass = [] {
  std::array<CharClass, 256> t{};
  t[' '] = t['\t'] = t['\r'] = CharClass::Blank;
  t['('] = t[')'] = t[';'] = CharClass::Special;
  return t;
}();
// Each byte upper-cased (LinuxCNC close_and_downcase; other bytes as they are).
constexpr std::array<char, 256> kUpper = [] {
  std::array<char, 256> t{};
  for (int c = 0; c < 256; ++c) t[c] = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
  return t;
}();

// Axis index of an axis letter, -1 for other letters.
[[nodiscard]] constexpr int axis_of(char upper) noexcept {
  switch (upper) {
    case 'X': return 0;
    case 'Y': return 1;
    case 'Z': return 2;
    case 'A': return 3;
    case 'B': return 4;
    case 'C': return 5;
    default: return -1;
  }
}

// Modal group of a G code ×10; -1 when outside the subset.
[[nodiscard]] constexpr int g_group(int tenths) noexcept {
  switch (tenths) {
    case 0:
    case 10:
    case 20:
    case 30:
    case 800:
    case 730:
    case 810:
    case 820:
    case 830:
    case 850:
    case 860:
    case 890: return group_index(GGroup::Motion);
    case 980:
    case 990: return group_index(GGroup::RetractMode);
    case 400:
    case 410:
    case 411:
    case 420:
    case 421: return group_index(GGroup::CutterComp);
    case 430:
    case 431:
    case 432:
    case 490: return group_index(GGroup::ToolLength);
    case 40:
    case 100:
    case 280:
    case 281:
    case 300:
    case 301:
    case 520:
    case 530:
    case 920:
    case 921:
    case 922:
    case 923: return group_index(GGroup::NonModal);
    case 170:
    case 180:
    case 190: return group_index(GGroup::Plane);
    case 200:
    case 210: return group_index(GGroup::Units);
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 591:
    case 592:
    case 593: return group_index(GGroup::CoordSystem);
    case 610:
    case 611:
    case 640: return group_index(GGroup::PathControl);
    case 900:
    case 910: return group_index(GGroup::Distance);
    case 901:
    case 911: return group_index(GGroup::ArcDistance);
    case 930:
    case 940: return group_index(GGroup::FeedMode);
    default: return -1;
  }
}

}  // namespace

std::string g_code_name(int tenths) {
  std::string s = "G" + std::to_string(tenths / 10);
  if (tenths % 10 != 0) s += "." + std::to_string(tenths % 10);
  return s;
}

bool BlockParser::fail(ErrorCode code, std::uint32_t byte_pos, std::string message) {
  fault_.code = code;
  fault_.byte_pos = byte_pos;
  fault_.message = std::move(message);
  return false;
}

std::string BlockParser::quoted(Span s) const { return quote(text_.text(s)); }

// Compact chars [begin, end), at most 24 of them (with "..." when cut).
std::string BlockParser::quoted(std::uint32_t begin, std::uint32_t end) const {
  return quote(std::string_view(text_.compact.data() + begin, end - begin), 24);
}

// Start (compact index) of the word whose number ends just before `end`:
// back over digits, points and signs, then its letter.
std::uint32_t BlockParser::word_before(std::uint32_t end) const {
  const char* c = text_.compact.data();
  std::uint32_t at = end;
  while (at > words_begin_ &&
         (is_digit(c[at - 1]) || c[at - 1] == '.' || c[at - 1] == '+' || c[at - 1] == '-')) {
    --at;
  }
  return at > words_begin_ ? at - 1 : at;
}

// A number that runs on at compact index i (a second '.', a sign after digits).
bool BlockParser::malformed_number(std::uint32_t i) {
  const char* c = text_.compact.data();
  const std::uint32_t n = text_.size;
  const std::uint32_t word = word_before(i);
  std::uint32_t end = i;
  while (end < n && (is_digit(c[end]) || c[end] == '.' || c[end] == '+' || c[end] == '-')) ++end;
  const char letter = c[word];
  return fail(ErrorCode::GcodeBadNumber, text_.offset[word],
              "found " + quoted(word, end) + ": malformed number " + quoted(word + 1, end) +
                  (c[i] == '.' ? " (more than one decimal point)" : " (a sign inside the number)") +
                  "; expected one number: [+-] digits with at most one decimal point, such "
                  "as " +
                  std::string(1, letter) + "1.25");
}

// Drops comments and blanks, upper-cases letters (LinuxCNC close_and_downcase).
bool BlockParser::compact(std::string_view line) {
  text_.original = line;
  if (text_.compact.size() < line.size()) {
    text_.compact.resize(line.size());
    text_.offset.resize(line.size());
  }
  char* out = text_.compact.data();
  std::uint32_t* off = text_.offset.data();
  std::uint32_t n = 0;
  const auto len = static_cast<std::uint32_t>(line.size());
  for (std::uint32_t i = 0; i < len; ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    const CharClass k = kCharClass[c];
    if (k != CharClass::Special) {
      // written either way, kept only when not a blank: no branch on the
      // blanks between words
      out[n] = kUpper[c];
      off[n] = i;
      n += k == CharClass::Keep ? 1u : 0u;
      continue;
    }
    if (c == ';') break;  // the rest of the line is a comment
    if (c == ')') {
      text_.size = n;
      return fail(ErrorCode::GcodeComment, i, "found ')' with no comment open; expected '(' before it");
    }
    // '(': a comment to its ')'
    const std::uint32_t comment_pos = i;
    for (++i; i < len && line[i] != ')'; ++i) {
      if (line[i] == '(') {
        text_.size = n;
        return fail(ErrorCode::GcodeComment, i,
                    "found '(' inside the comment opened at column " + std::to_string(comment_pos + 1) +
                        "; expected ')' first: comments do not nest");
      }
    }
    if (i == len) {
      text_.size = n;
      return fail(ErrorCode::GcodeComment, comment_pos,
                  "found a comment '(' not closed on its line; expected ')' before the end "
                  "of the line");
    }
  }
  text_.size = n;
  return true;
}

// Reads [+-] digits [. digits] at compact index i; i moves past it.
bool BlockParser::read_number(std::uint32_t& i, std::uint32_t letter_at_pos, double& value) {
  const char* c = text_.compact.data();
  const std::uint32_t n = text_.size;
  const std::uint32_t start = i;
  const char letter = c[letter_at_pos];
  std::uint32_t j = i;
  bool negative = false;
  if (j < n && (c[j] == '+' || c[j] == '-')) {
    negative = c[j] == '-';
    ++j;
  }
  const std::uint32_t digits_start = j;
  // Every digit into the mantissa: with at most kFastDigits digits in all
  // (leading zeros included) it is exact; longer numbers go to from_chars.
  std::uint64_t mantissa = 0;
  while (j < n && is_digit(c[j])) mantissa = mantissa * 10 + static_cast<unsigned>(c[j++] - '0');
  const std::uint32_t int_digits = j - digits_start;
  std::uint32_t frac = 0;  // digits after the point
  if (j < n && c[j] == '.') {
    const std::uint32_t frac_start = ++j;
    while (j < n && is_digit(c[j])) mantissa = mantissa * 10 + static_cast<unsigned>(c[j++] - '0');
    frac = j - frac_start;
  }
  const bool any_digit = int_digits + frac > 0;
  const std::uint32_t digits = int_digits + frac;
  const std::uint32_t letter_pos = text_.offset[letter_at_pos];
  if (!any_digit) {
    // a function name is letters and then '[' (XSIN[30]); a lone letter is
    // the next word (X F6: X has no number)
    auto function_at = [&](std::uint32_t k) {
      while (k < n && c[k] >= 'A' && c[k] <= 'Z') ++k;
      return k > start + 1 && k < n && c[k] == '[';
    };
    if (params_ != nullptr && start < n &&
        (c[start] == '#' || c[start] == '[' || function_at(start) ||
         ((c[start] == '+' || c[start] == '-') && start + 1 < n && !is_digit(c[start + 1]) &&
          c[start + 1] != '.'))) {
      i = start;
      return read_expression(i, value);
    }
    if (start < n && c[start] == '#') {
      return fail(ErrorCode::GcodeUnsupported, text_.offset[start],
                  std::string("found '") + letter +
                      "#': parameters (#) are not supported; expected a plain number after " + letter);
    }
    if (start < n && c[start] == '[') {
      return fail(ErrorCode::GcodeUnsupported, text_.offset[start],
                  std::string("found '") + letter +
                      "[': expressions ([ ]) are not supported; expected a plain number after " + letter);
    }
    return fail(ErrorCode::GcodeBadNumber, letter_pos,
                "found " + quoted(letter_at_pos, std::min(n, start + 8)) + " with no number after " + letter +
                    "; expected a number such as " + letter + "10, " + letter + "-0.5 or " + letter + ".5");
  }
  if (digits <= kFastDigits) {
    double v = static_cast<double>(mantissa);
    if (frac > 0) v /= kPow10[frac];
    value = negative ? -v : v;
  } else {
    // Long numbers: std::from_chars rounds correctly (it takes no leading '+').
    const char* first = c + start + ((c[start] == '+') ? 1 : 0);
    const auto [end, ec] = std::from_chars(first, c + j, value);
    if (ec != std::errc() || end != c + j) {
      const std::uint32_t shown = std::min<std::uint32_t>(j - letter_at_pos, 24);
      return fail(ErrorCode::GcodeBadNumber, letter_pos,
                  "found '" + std::string(c + letter_at_pos, shown) +
                      "...': the number is out of range; expected a number a double can hold");
    }
  }
  i = j;
  return true;
}

// Why a LinuxCNC G code this machine does not run is refused, or nullptr.
[[nodiscard]] static const char* g_refusal(int tenths) noexcept {
  switch (tenths) {
    case 330:
    case 331: return "spindle-synchronized motion needs a spindle encoder; a laser has no spindle";
    case 740:
    case 840: return "tapping reverses a spindle; a laser has none";
    case 760: return "lathe threading needs a spindle; a laser has none";
    case 870: return "back boring needs an oriented spindle stop; a laser has no spindle";
    case 880: return "boring with a manual retract needs the operator's hand at a program stop";
    case 382:
    case 383:
    case 384:
    case 385: return "probing: this machine has no probe input yet";
    case 50:
    case 51:
    case 52:
    case 53: return "splines are not read yet";
    case 70:
    case 80: return "lathe diameter/radius mode; this is no lathe";
    case 950: return "feed per revolution needs a spindle; a laser has none";
    case 960:
    case 970: return "spindle speed modes; a laser's power is S (M3/M4)";
    default: return nullptr;
  }
}

bool BlockParser::read_g(Span w, double value, Block& out) {
  const std::uint32_t pos = text_.byte_pos(w);
  const double scaled = value * 10.0;
  const bool in_range = value >= 0.0 && value < 10000.0;
  // rounded half up, as lround does for these (non-negative) values, inline
  int tenths = -1;
  if (in_range) {
    tenths = static_cast<int>(scaled);
    if (scaled - tenths >= 0.5) ++tenths;
  }
  const bool whole_tenths = in_range && std::fabs(scaled - tenths) <= kCodeTenthsTol;
  const int grp = whole_tenths ? g_group(tenths) : -1;
  if (grp < 0) {
    const std::string name = whole_tenths ? g_code_name(tenths) : std::string(text_.text(w));
    const char* why = whole_tenths ? g_refusal(tenths) : nullptr;
    return fail(ErrorCode::GcodeUnknownCode, pos,
                name + " is not supported" + (why != nullptr ? std::string(" (") + why + ")" : "") +
                    "; expected one of " + kSupportedGCodes);
  }
  // G80 with another code of its group on the line is passed over, as in
  // LinuxCNC ("G80 G0 X5": the G0 runs)
  if (tenths == 800 && out.g[grp] >= 0) return true;
  if (out.g[grp] >= 0 && out.g[grp] != 800) {
    return fail(ErrorCode::GcodeModalConflict, pos,
                "found " + g_code_name(out.g[grp]) + " and " + g_code_name(tenths) +
                    " in one block, both of modal group " + std::to_string(kGGroupNumber[grp]) + " (" +
                    kGGroupName[grp] + "); expected at most one code of each group");
  }
  out.g[grp] = static_cast<std::int16_t>(tenths);
  out.g_word[grp] = w;
  return true;
}

bool BlockParser::read_m(Span w, double value, Block& out) {
  const std::uint32_t pos = text_.byte_pos(w);
  const double rounded = std::round(value);
  if (std::fabs(value - rounded) > kIntegerTol || value < 0.0 || value >= 10000.0) {
    return fail(ErrorCode::GcodeBadNumber, pos,
                "found " + quoted(w) + "; expected a whole-number M code (" + kSupportedMCodes + ")");
  }
  const int code = static_cast<int>(rounded);
  const std::string name = "M" + std::to_string(code);
  auto conflict = [&](int other, int group, const char* group_name) {
    return fail(ErrorCode::GcodeModalConflict, pos,
                "found M" + std::to_string(other) + " and " + name + " in one block, both of M modal group " +
                    std::to_string(group) + " (" + group_name + "); expected at most one code of each group");
  };
  switch (code) {
    case 0:
    case 1:
    case 2:
    case 30:
    case 60:
      if (out.m_stop >= 0) return conflict(out.m_stop, 4, "stopping");
      out.m_stop = static_cast<std::int16_t>(code);
      out.m_stop_word = w;
      return true;
    case 3:
    case 4:
    case 5:
    case 70:
    case 71:
    case 72:
    case 73: {
      // one group in LinuxCNC: the spindle (laser) and the modal state's
      // save (M70, M73), forget (M71) and restore (M72)
      const char* group_name = "laser on/off, modal state";
      if (out.m_laser >= 0) return conflict(out.m_laser, 7, group_name);
      if (out.m_context >= 0) return conflict(out.m_context, 7, group_name);
      if (code >= 70) {
        out.m_context = static_cast<std::int16_t>(code);
        out.m_context_word = w;
      } else {
        out.m_laser = static_cast<std::int16_t>(code);
        out.m_laser_word = w;
      }
      return true;
    }
    case 62:
    case 63:
    case 64:
    case 65:
    case 66:
    case 67:
    case 68:
      if (out.m_io >= 0) return conflict(out.m_io, 5, "outputs");
      out.m_io = static_cast<std::int16_t>(code);
      out.m_io_word = w;
      return true;
    case 48:
    case 49:
    case 50:
    case 51:
    case 52:
    case 53:
      if (out.m_override >= 0) return conflict(out.m_override, 9, "override switches");
      out.m_override = static_cast<std::int16_t>(code);
      out.m_override_word = w;
      return true;
    case 6:
    case 61:
      if (out.m_tool >= 0) return conflict(out.m_tool, 6, "tool change");
      out.m_tool = static_cast<std::int16_t>(code);
      out.m_tool_word = w;
      return true;
    case 7:
    case 8:
    case 9: {
      // M7 and M8 may be on together (LinuxCNC); M9 excludes both, and no
      // code may appear twice.
      const char* group_name = "assist gas: M7 mist, M8 flood, M9 off";
      if (out.m9) return conflict(9, 8, group_name);
      if (code == 9 && out.m7) return conflict(7, 8, group_name);
      if (code == 9 && out.m8) return conflict(8, 8, group_name);
      if (code == 7 && out.m7) return conflict(7, 8, group_name);
      if (code == 8 && out.m8) return conflict(8, 8, group_name);
      if (code == 7) {
        out.m7 = true;
        out.m7_word = w;
      } else if (code == 8) {
        out.m8 = true;
        out.m8_word = w;
      } else {
        out.m9 = true;
        out.m9_word = w;
      }
      return true;
    }
    default:
      return fail(ErrorCode::GcodeUnknownCode, pos,
                  name + " is not supported; expected one of " + kSupportedMCodes);
  }
}

// $: LinuxCNC's spindle selector (M3 $0 S…, as CAM posts for LinuxCNC and
// plasma write it). This machine's one laser is spindle 0; $-1 (all) is it
// too. Nothing to keep.
bool BlockParser::read_spindle(std::uint32_t& i) {
  const std::uint32_t at = i++;
  if (i < text_.size && text_.compact[i] >= 'A' && text_.compact[i] <= 'Z') {
    std::uint32_t j = i;
    while (j < text_.size && text_.compact[j] != '(') ++j;
    return fail(ErrorCode::GcodeSyntax, text_.offset[at],
                "found " + quoted(at, j) +
                    ": a grbl system command, not G-code; expected $0 "
                    "(the spindle selector), or [machine] dialect = \"grbl\" to pass such lines over");
  }
  double value = 0.0;
  if (!read_number(i, at, value)) return false;
  if (value == 0.0 || value == -1.0) return true;
  return fail(ErrorCode::GcodeBadValue, text_.offset[at],
              "found " + quoted(Span{at, i}) +
                  ": this machine has one laser, spindle $0; "
                  "expected $0 (or $-1, all of them) or no $ word");
}

// @ radius or ^ angle: X and Y in polar coordinates, never with X or Y.
bool BlockParser::read_polar(std::uint32_t& i, Block& out) {
  const char ch = text_.compact[i];
  const std::uint32_t at = i++;
  double value = 0.0;
  if (!read_number(i, at, value)) return false;
  const Span w{at, i};
  const std::uint8_t bit = ch == '@' ? 1 : 2;
  if (out.polar & bit) {
    return fail(ErrorCode::GcodeRepeatedWord, text_.offset[at],
                "found a second " + std::string(1, ch) + " word " + quoted(w) +
                    "; expected each polar word (@ radius, ^ angle) at most once per block");
  }
  if ((present_axes_ & 3u) != 3u) {
    return fail(ErrorCode::GcodeNoSuchAxis, text_.offset[at],
                "found " + quoted(w) +
                    ": polar coordinates place X and Y, and this machine "
                    "lacks one of them");
  }
  if (out.polar == 0) out.polar_word = w;
  out.polar |= bit;
  (bit == 1 ? out.polar_radius : out.polar_angle_deg) = value;
  if (out.axis_mask == 0) out.first_axis_word = w;
  out.axis_mask = static_cast<std::uint8_t>(out.axis_mask | 3u);
  return true;
}

bool BlockParser::read_word(std::uint32_t& i, Block& out) {
  const char* c = text_.compact.data();
  const std::uint32_t n = text_.size;
  const char ch = c[i];
  const std::uint32_t pos = text_.offset[i];

  if (ch == '#' && params_ != nullptr) return read_setting(i, out);
  if (ch < 'A' || ch > 'Z') {
    switch (ch) {
      case '#':
        return fail(ErrorCode::GcodeUnsupported, pos,
                    "found '#': parameters (#1 = ..., #<name>) are not supported; expected "
                    "words with plain numbers");
      case '[':
        return fail(ErrorCode::GcodeUnsupported, pos,
                    "found '[': expressions are not supported; expected words with plain "
                    "numbers");
      case '/':
        return fail(ErrorCode::GcodeSyntax, pos,
                    "found '/' inside the block; expected block delete '/' only as the first "
                    "character of a line");
      case '@':
      case '^': return read_polar(i, out);
      case '$': return read_spindle(i);
      case '.':
      case '+':
      case '-':
        // Right after a word's number ("X1.2.3", "X1-2"): that number ran on.
        // Checked here, off the path of well-formed words.
        if (i > words_begin_ && (is_digit(c[i - 1]) || c[i - 1] == '.')) {
          return malformed_number(i);
        }
        break;
      default: break;
    }
    // Quote the whole UTF-8 character when it is one.
    std::string_view orig = text_.original.substr(pos);
    std::size_t len = 1;
    while (len < orig.size() && len < 4 && (static_cast<unsigned char>(orig[len]) & 0xC0) == 0x80) {
      ++len;
    }
    return fail(ErrorCode::GcodeSyntax, pos,
                "found " + quote(orig.substr(0, len)) + "; expected a word: a letter (" + kSupportedWords +
                    ") followed by a number");
  }

  // The span of an unsupported word, for its message: the letter and what
  // looks like its number.
  auto rough_word = [&]() {
    std::uint32_t j = i + 1;
    while (j < n && (is_digit(c[j]) || c[j] == '.' || c[j] == '+' || c[j] == '-')) ++j;
    return quoted(Span{i, j});
  };
  switch (ch) {
    case 'O':
      // An O-word opens a line (parse() reads it); after another word it is
      // a stray letter, most often a zero typed as O ("X1O"). Name the word before.
      return fail(ErrorCode::GcodeSyntax, pos,
                  "found a letter 'O' after " + quoted(word_before(i), i) +
                      ": unexpected 'O' inside the block (a zero typed as the letter O?); "
                      "expected the digit 0 or a word letter (" +
                      kSupportedWords + ")");
    case 'N':
      return fail(
          ErrorCode::GcodeSyntax, pos,
          "found " + rough_word() + " after other words; expected the line number N first in the block");
    case 'U':
    case 'V':
    case 'W':
      return fail(
          ErrorCode::GcodeUnsupported, pos,
          "found " + rough_word() + ": U V W axes are not supported; expected axis words X Y Z A B C");
    default: break;
  }

  const std::uint32_t letter_at = i;
  ++i;
  double value = 0.0;
  if (!read_number(i, letter_at, value)) return false;
  const Span w{letter_at, i};
  if (ch == 'G') return read_g(w, value, out);
  if (ch == 'M') return read_m(w, value, out);

  const int li = letter_index(ch);
  if ((out.letters >> li) & 1u) {
    return fail(ErrorCode::GcodeRepeatedWord, pos,
                "found a second " + std::string(1, ch) + " word " + quoted(w) + " (the first is " +
                    quoted(out.word[li]) + "); expected each word letter at most once per block");
  }
  const int axis = axis_of(ch);
  if (axis >= 0) {
    if (((present_axes_ >> axis) & 1u) == 0) {
      std::string axes;
      for (int a = 0; a < 6; ++a) {
        if ((present_axes_ >> a) & 1u) {
          if (!axes.empty()) axes += ' ';
          axes += "XYZABC"[a];
        }
      }
      return fail(ErrorCode::GcodeNoSuchAxis, pos,
                  "found " + quoted(w) + " but this machine has no " + std::string(1, ch) +
                      " axis; expected axis words for its axes: " + axes);
    }
    if (out.axis_mask == 0) out.first_axis_word = w;
    out.axis_mask = static_cast<std::uint8_t>(out.axis_mask | (1u << axis));
  }
  out.letters |= 1u << li;
  out.value[li] = value;
  out.word[li] = w;
  return true;
}

// A value through the expression reader (a parameter, [ ], a function).
bool BlockParser::read_expression(std::uint32_t& i, double& value) {
  ExpressionReader r(text_, *params_);
  if (r.real_value(i, value)) return true;
  const Fault& f = r.fault();
  return fail(f.code, f.byte_pos, f.message);
}

// #index = value or #<name> = value (LinuxCNC read_parameter_setting).
bool BlockParser::read_setting(std::uint32_t& i, Block& out) {
  const char* c = text_.compact.data();
  const std::uint32_t n = text_.size;
  const std::uint32_t at = i;
  ExpressionReader r(text_, *params_);
  ParamSet set;
  ++i;  // '#'
  if (i < n && c[i] == '<') {
    if (!r.name(i, set.name)) return fail(r.fault().code, r.fault().byte_pos, r.fault().message);
  } else {
    const std::uint32_t index_at = i;
    double v = 0.0;
    if (!r.real_value(i, v)) return fail(r.fault().code, r.fault().byte_pos, r.fault().message);
    const double rounded = std::round(v);
    if (std::fabs(v - rounded) > kIntegerTol || rounded < 1.0 || rounded > kMaxParameterIndex) {
      return fail(ErrorCode::GcodeBadValue, text_.offset[index_at],
                  "found " + quoted(at, i) + ": parameter number " + quoted(index_at, i) +
                      "; expected a whole number from 1 to " + std::to_string(kMaxParameterIndex));
    }
    set.index = static_cast<int>(rounded);
  }
  if (const std::string why = params_->read_only(set.index, set.name); !why.empty()) {
    const std::string shown = set.index > 0 ? "#" + std::to_string(set.index) : "#<" + set.name + ">";
    return fail(ErrorCode::GcodeBadValue, text_.offset[at],
                "found " + quoted(at, i) + " set: " + shown + " is read-only (" + why +
                    "); expected a parameter a program may set, e.g. #1 … #5000 or #<_name> of "
                    "its own");
  }
  if (i >= n || c[i] != '=') {
    return fail(ErrorCode::GcodeSyntax, text_.offset[at],
                "found " + quoted(at, std::min(n, i + 1)) +
                    " with no '='; expected a parameter setting such as #1 = 2.5 or #<depth> = "
                    "-1 (a parameter's value is read only inside a word, e.g. X#1)");
  }
  ++i;
  if (!r.real_value(i, set.value)) return fail(r.fault().code, r.fault().byte_pos, r.fault().message);
  set.word = Span{at, i};
  out.sets.push_back(std::move(set));
  return true;
}

// Resets `out`, compacts the line and reads what opens it: a '%' line, '/'
// and the N number. `i` is left at the first word; false on an error.
[[gnu::always_inline]] inline bool BlockParser::read_prefix(std::string_view line, Block& out,
                                                            std::uint32_t& i) {
  out.sets.clear();
  out.empty = true;
  out.percent = false;
  out.block_delete = false;
  out.letters = 0;
  out.axis_mask = 0;
  out.g.fill(-1);
  out.m_stop = -1;
  out.m_laser = -1;
  out.m_tool = -1;
  out.m_context = -1;
  out.m_io = -1;
  out.m_override = -1;
  out.polar = 0;
  out.m7 = out.m8 = out.m9 = false;
  out.o.kind = OKind::None;

  i = 0;
  if (!compact(line)) return false;
  const char* c = text_.compact.data();
  const std::uint32_t n = text_.size;
  if (n == 0) return true;

  if (c[0] == '%') {
    out.percent = true;
    i = n;
    if (n > 1) {
      return fail(ErrorCode::GcodeSyntax, text_.offset[1],
                  "found " + quote(std::string_view(c + 1, n - 1)) +
                      " after '%'; expected nothing but a comment on a '%' program "
                      "delimiter line");
    }
    return true;
  }

  if (c[i] == '/') {
    out.block_delete = true;
    ++i;
  }
  if (i < n && c[i] == 'N') {
    const std::uint32_t letter_at = i;
    ++i;
    const std::uint32_t digits_at = i;
    while (i < n && (is_digit(c[i]) || c[i] == '.')) ++i;
    if (i == digits_at) {
      return fail(ErrorCode::GcodeBadNumber, text_.offset[letter_at],
                  "found 'N' with no line number; expected N followed by digits, e.g. N10");
    }
  }
  words_begin_ = i;
  return true;
}

bool BlockParser::parse(std::string_view line, Block& out) {
  std::uint32_t i = 0;
  if (!read_prefix(line, out, i)) return false;
  const std::uint32_t n = text_.size;
  if (i < n && text_.compact[i] == 'O') return read_o(i, out);
  while (i < n) {
    if (!read_word(i, out)) return false;
    out.empty = false;
  }
  return true;
}

bool BlockParser::parse_o_only(std::string_view line, Block& out) {
  std::uint32_t i = 0;
  if (!read_prefix(line, out, i)) return false;
  if (i < text_.size && text_.compact[i] == 'O') return read_o(i, out);
  return true;
}

const char* o_keyword(OKind k) noexcept {
  switch (k) {
    case OKind::None: return "";
    case OKind::Sub: return "sub";
    case OKind::EndSub: return "endsub";
    case OKind::Return: return "return";
    case OKind::Call: return "call";
    case OKind::If: return "if";
    case OKind::ElseIf: return "elseif";
    case OKind::Else: return "else";
    case OKind::EndIf: return "endif";
    case OKind::While: return "while";
    case OKind::EndWhile: return "endwhile";
    case OKind::Do: return "do";
    case OKind::Repeat: return "repeat";
    case OKind::EndRepeat: return "endrepeat";
    case OKind::Break: return "break";
    case OKind::Continue: return "continue";
  }
  return "";
}

// O label keyword [value]... (LinuxCNC read_o): the label is a number or a
// <name>; the values are bracketed expressions, read later by o_values().
bool BlockParser::read_o(std::uint32_t& i, Block& out) {
  const char* c = text_.compact.data();
  const std::uint32_t n = text_.size;
  const std::uint32_t at = i;
  OWord& o = out.o;
  o.label.clear();
  ++i;
  if (i < n && c[i] == '<') {
    const std::uint32_t name_at = ++i;
    while (i < n && c[i] != '>') ++i;
    if (i == n) {
      return fail(ErrorCode::GcodeSyntax, text_.offset[at],
                  "found " + quoted(at, n) +
                      " with no '>' closing the name; expected an O-word "
                      "such as o<drill_row> call");
    }
    if (i == name_at) {
      return fail(ErrorCode::GcodeSyntax, text_.offset[at],
                  "found 'O<>': an empty subroutine name; expected a name such as o<drill_row>");
    }
    o.label = "<";
    for (std::uint32_t k = name_at; k < i; ++k) {
      const char ch = c[k];
      o.label += ch >= 'A' && ch <= 'Z' ? static_cast<char>(ch - 'A' + 'a') : ch;
    }
    o.label += '>';
    ++i;
  } else {
    const std::uint32_t digits_at = i;
    while (i < n && c[i] == '0') ++i;
    const std::uint32_t significant = i;
    while (i < n && is_digit(c[i])) ++i;
    if (i == digits_at || i - significant > 9) {
      return fail(ErrorCode::GcodeSyntax, text_.offset[at],
                  "found " + quoted(at, std::min(n, i + 8)) +
                      ": an O-word needs a label; expected a number of at most 9 digits or a "
                      "<name> after O, such as O100 if or o<pierce> call");
    }
    o.label = i == significant ? "0" : std::string(c + significant, i - significant);
  }
  const std::uint32_t keyword_at = i;
  while (i < n && c[i] >= 'A' && c[i] <= 'Z') ++i;
  const std::string_view keyword(c + keyword_at, i - keyword_at);
  static constexpr std::array<std::pair<std::string_view, OKind>, 15> kKeywords = {
      {{"SUB", OKind::Sub},
       {"ENDSUB", OKind::EndSub},
       {"RETURN", OKind::Return},
       {"CALL", OKind::Call},
       {"IF", OKind::If},
       {"ELSEIF", OKind::ElseIf},
       {"ELSE", OKind::Else},
       {"ENDIF", OKind::EndIf},
       {"WHILE", OKind::While},
       {"ENDWHILE", OKind::EndWhile},
       {"DO", OKind::Do},
       {"REPEAT", OKind::Repeat},
       {"ENDREPEAT", OKind::EndRepeat},
       {"BREAK", OKind::Break},
       {"CONTINUE", OKind::Continue}}};
  o.kind = OKind::None;
  for (const auto& [word, kind] : kKeywords) {
    if (keyword == word) o.kind = kind;
  }
  if (o.kind == OKind::None) {
    return fail(ErrorCode::GcodeSyntax, text_.offset[keyword_at < n ? keyword_at : at],
                "found " + quoted(at, std::min(n, i + 4)) +
                    (keyword.empty() ? std::string(" with no keyword")
                                     : ": unknown O-word keyword " + quote(keyword)) +
                    "; expected one of sub endsub return call if elseif else endif while "
                    "endwhile do repeat endrepeat break continue");
  }
  o.word = Span{at, i};
  o.args_begin = i;
  o.arg_count = 0;
  // the values: balanced [ ] groups, one after another, nothing else
  while (i < n) {
    if (c[i] != '[') {
      return fail(ErrorCode::GcodeSyntax, text_.offset[i],
                  "found " + quoted(i, n) + " after " + quoted(o.word) +
                      "; expected only bracketed values such as [#1 + 2] (and comments) on an "
                      "O-word line");
    }
    const std::uint32_t open_at = i;
    int depth = 0;
    do {
      if (c[i] == '[') ++depth;
      if (c[i] == ']') --depth;
      ++i;
    } while (i < n && depth > 0);
    if (depth > 0) {
      return fail(ErrorCode::GcodeSyntax, text_.offset[open_at],
                  "found '[' with no matching ']' after " + quoted(o.word) +
                      "; expected each value in [ ] closed on its line");
    }
    ++o.arg_count;
  }
  std::uint32_t least = 0;
  std::uint32_t most = 0;
  switch (o.kind) {
    case OKind::If:
    case OKind::ElseIf:
    case OKind::While:
    case OKind::Repeat: least = most = 1; break;
    case OKind::Return:
    case OKind::EndSub: most = 1; break;
    case OKind::Call: most = kMaxCallArgs; break;
    default: break;
  }
  if (o.arg_count < least || o.arg_count > most) {
    const std::string kw = o_keyword(o.kind);
    std::string expected = least == 1  ? "one bracketed value, such as O100 " + kw + " [#1 LT 3]"
                           : most == 0 ? "nothing after '" + kw + "' but a comment"
                           : most == 1 ? "at most one bracketed value, the one returned"
                                       : "at most " + std::to_string(kMaxCallArgs) + " bracketed arguments";
    return fail(ErrorCode::GcodeSyntax, text_.offset[at],
                "found " + quoted(o.word) + " with " + std::to_string(o.arg_count) + " bracketed value" +
                    (o.arg_count == 1 ? "" : "s") + "; expected " + expected);
  }
  return true;
}

bool BlockParser::o_values(const Block& b, std::vector<double>& out) {
  out.clear();
  if (params_ == nullptr) {
    return fail(ErrorCode::GcodeUnsupported, text_.byte_pos(b.o.word),
                "found an O-word with values but no parameters to read them with");
  }
  ExpressionReader r(text_, *params_);
  std::uint32_t i = b.o.args_begin;
  for (std::uint32_t k = 0; k < b.o.arg_count; ++k) {
    double v = 0.0;
    if (!r.real_value(i, v)) return fail(r.fault().code, r.fault().byte_pos, r.fault().message);
    out.push_back(v);
  }
  return true;
}

}  // namespace lcnc::gcode
