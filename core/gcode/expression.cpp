#include "gcode/expression.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

#include "gcode/gcode_tolerances.h"

namespace lcnc::gcode {
namespace {

// Binary operators, by precedence (LinuxCNC precedence()).
enum Op : int {
  kClose,  // ']' ends the expression
  kAnd,
  kOr,
  kXor,
  kEq,
  kNe,
  kGt,
  kGe,
  kLt,
  kLe,
  kPlus,
  kMinus,
  kTimes,
  kDivide,
  kMod,
  kPower,
};

int precedence(int op) {
  switch (op) {
    case kClose: return 1;
    case kAnd:
    case kOr:
    case kXor: return 2;
    case kEq:
    case kNe:
    case kGt:
    case kGe:
    case kLt:
    case kLe: return 3;
    case kPlus:
    case kMinus: return 4;
    case kTimes:
    case kDivide:
    case kMod: return 5;
    default: return 6;  // kPower
  }
}

// LinuxCNC's TOLERANCE_EQUAL: EQ NE LE GE compare within it.
constexpr double kEqualityTolerance = 1e-6;
// Degrees and radians through long double, as LinuxCNC (M_PIl).
constexpr long double kPiL = 3.141592653589793238462643383279502884L;
double rad(double deg) { return static_cast<double>((static_cast<long double>(deg) * kPiL) / 180.0L); }
double deg(double rad) { return static_cast<double>((static_cast<long double>(rad) * 180.0L) / kPiL); }

struct Function {
  const char* name;
  int id;
};
enum Fn : int { kAbs, kAcos, kAsin, kAtan, kCos, kExp, kExists, kFix, kFup, kLn, kRound, kSin, kSqrt, kTan };
// Longest first where one name starts another (none do here).
constexpr std::array<Function, 14> kFunctions = {{{"ABS", kAbs},
                                                  {"ACOS", kAcos},
                                                  {"ASIN", kAsin},
                                                  {"ATAN", kAtan},
                                                  {"COS", kCos},
                                                  {"EXP", kExp},
                                                  {"EXISTS", kExists},
                                                  {"FIX", kFix},
                                                  {"FUP", kFup},
                                                  {"LN", kLn},
                                                  {"ROUND", kRound},
                                                  {"SIN", kSin},
                                                  {"SQRT", kSqrt},
                                                  {"TAN", kTan}}};

constexpr const char* kOperators = "+ - * / ** MOD EQ NE GT GE LT LE AND OR XOR";

}  // namespace

std::uint32_t ExpressionReader::pos(std::uint32_t i) const {
  if (i < n_) return text_.offset[i];
  return static_cast<std::uint32_t>(text_.original.size());
}

std::string ExpressionReader::excerpt(std::uint32_t begin, std::uint32_t end) const {
  constexpr std::uint32_t kShown = 24;
  if (end > n_) end = n_;
  if (begin > end) begin = end;
  const bool cut = end - begin > kShown;
  std::string q = quote(std::string_view(c_ + begin, cut ? kShown : end - begin));
  if (cut) q.insert(q.size() - 1, "...");
  return q;
}

bool ExpressionReader::fail(std::uint32_t at, std::string message) {
  fault_.code = ErrorCode::GcodeSyntax;
  fault_.byte_pos = pos(at);
  fault_.message = std::move(message);
  return false;
}

bool ExpressionReader::real_value(std::uint32_t& i, double& out) { return value(i, out, 0); }

bool ExpressionReader::integer_value(std::uint32_t& i, int& out) {
  const std::uint32_t at = i;
  double v = 0.0;
  if (!real_value(i, v)) return false;
  const double r = std::round(v);
  if (std::fabs(v - r) > kIntegerTol || std::fabs(r) > 1e9) {
    return fail(at, "found " + excerpt(at, i) + " = " + std::to_string(v) + "; expected a whole number here");
  }
  out = static_cast<int>(r);
  return true;
}

bool ExpressionReader::name(std::uint32_t& i, std::string& out) {
  const std::uint32_t open = i;
  ++i;  // '<'
  out.clear();
  while (i < n_ && c_[i] != '>') {
    const char ch = c_[i];
    if (ch == '<' || ch == '[' || ch == ']' || ch == '#' || ch == '=') {
      return fail(i, "found " + excerpt(open, i + 1) + ": " + quote(std::string_view(&c_[i], 1)) +
                         " inside a parameter name; expected the name to end with '>'");
    }
    out += (ch >= 'A' && ch <= 'Z') ? static_cast<char>(ch - 'A' + 'a') : ch;
    ++i;
  }
  if (i == n_) {
    return fail(open,
                "found " + excerpt(open, i) + ": a parameter name not closed; expected '>' after the name");
  }
  if (out.empty()) return fail(open, "found '<>': an empty parameter name; expected #<name>");
  ++i;  // '>'
  return true;
}

bool ExpressionReader::value(std::uint32_t& i, double& out, int depth) {
  if (depth > kMaxExpressionDepth) {
    return fail(i, "found expressions nested deeper than " + std::to_string(kMaxExpressionDepth) +
                       " levels; expected fewer brackets");
  }
  if (i >= n_) return fail(i, "found the end of the line; expected a value (a number, #, [ or a function)");
  const char ch = c_[i];
  const char next = i + 1 < n_ ? c_[i + 1] : '\0';
  bool ok = false;
  if (ch == '[') {
    ok = expression(i, out, depth + 1);
  } else if (ch == '#') {
    ok = parameter(i, out, depth + 1);
  } else if ((ch == '+' || ch == '-') && next != '\0' && !is_digit(next) && next != '.') {
    ++i;
    ok = value(i, out, depth + 1);
    if (ok && ch == '-') out = -out;
  } else if (ch >= 'A' && ch <= 'Z') {
    ok = function(i, out, depth + 1);
  } else {
    ok = number(i, out);
  }
  if (!ok) return false;
  if (!std::isfinite(out)) {
    return fail(i > 0 ? i - 1 : 0, "a calculation ended in " +
                                       std::string(std::isnan(out) ? "not a number" : "infinity") +
                                       "; expected a finite value");
  }
  return true;
}

bool ExpressionReader::number(std::uint32_t& i, double& out) {
  const std::uint32_t start = i;
  std::uint32_t j = i;
  if (j < n_ && (c_[j] == '+' || c_[j] == '-')) ++j;
  const std::uint32_t digits = j;
  while (j < n_ && is_digit(c_[j])) ++j;
  if (j < n_ && c_[j] == '.') {
    ++j;
    while (j < n_ && is_digit(c_[j])) ++j;
  }
  const bool any = j > digits && !(j == digits + 1 && c_[digits] == '.');
  if (!any) {
    return fail(start, "found " + excerpt(start, start + 8) +
                           "; expected a value: a number, a parameter (#), an expression ([ ]) or a "
                           "function such as SIN[30]");
  }
  const char* first = c_ + start + (c_[start] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(first, c_ + j, out);
  if (ec != std::errc() || end != c_ + j) {
    return fail(start, "found " + excerpt(start, j) + ": the number is out of range");
  }
  i = j;
  return true;
}

bool ExpressionReader::parameter(std::uint32_t& i, double& out, int depth) {
  const std::uint32_t at = i;
  ++i;  // '#'
  if (i < n_ && c_[i] == '<') {
    std::string nm;
    if (!name(i, nm)) return false;
    if (!params_.named(nm, out)) {
      return fail(at, "found #<" + nm + ">: a named parameter not defined; expected it set (#<" + nm +
                          "> = ...) before it is read");
    }
    return true;
  }
  // #n, #[expr], ##n: the index is itself a value
  const std::uint32_t index_at = i;
  double v = 0.0;
  if (!value(i, v, depth + 1)) return false;
  const double r = std::round(v);
  if (std::fabs(v - r) > kIntegerTol || r < 1.0 || r > kMaxParameterIndex) {
    return fail(index_at, "found " + excerpt(at, i) + ": parameter number " + std::to_string(v) +
                              "; expected a whole number from 1 to " + std::to_string(kMaxParameterIndex));
  }
  out = params_.numbered(static_cast<int>(r));
  return true;
}

bool ExpressionReader::function(std::uint32_t& i, double& out, int depth) {
  const std::uint32_t at = i;
  std::uint32_t j = i;
  while (j < n_ && c_[j] >= 'A' && c_[j] <= 'Z') ++j;
  const std::string_view word(c_ + i, j - i);
  int id = -1;
  for (const Function& f : kFunctions) {
    if (word == f.name) id = f.id;
  }
  if (id < 0) {
    return fail(at, "found " + excerpt(at, j + 1) +
                        ": not a function; expected a value, or one of ABS ACOS ASIN ATAN COS "
                        "EXP EXISTS FIX FUP LN ROUND SIN SQRT TAN followed by [");
  }
  i = j;
  if (i >= n_ || c_[i] != '[') {
    return fail(at, "found " + excerpt(at, i + 1) + ": " + std::string(word) + " without '['; expected " +
                        std::string(word) + "[...]");
  }
  if (id == kExists) {
    // EXISTS[#<name>]: 1 when the named parameter is defined
    ++i;
    if (i + 1 >= n_ || c_[i] != '#' || c_[i + 1] != '<') {
      return fail(i, "found " + excerpt(at, i + 2) + "; expected EXISTS[#<name>]");
    }
    ++i;
    std::string nm;
    if (!name(i, nm)) return false;
    if (i >= n_ || c_[i] != ']')
      return fail(i, "found " + excerpt(at, i + 1) + "; expected ']' after the name");
    ++i;
    double ignored = 0.0;
    out = params_.named(nm, ignored) ? 1.0 : 0.0;
    return true;
  }
  const std::uint32_t arg_at = i;
  double v = 0.0;
  if (!expression(i, v, depth + 1)) return false;
  auto domain = [&](const char* what) {
    fault_.code = ErrorCode::GcodeBadValue;
    fault_.byte_pos = pos(at);
    fault_.message = "found " + excerpt(at, i) + " of " + std::to_string(v) + "; expected " + what;
    return false;
  };
  switch (id) {
    case kAbs: out = std::fabs(v); return true;
    case kAcos:
      if (v < -1.0 || v > 1.0) return domain("ACOS of a value from -1 to 1");
      out = deg(std::acos(v));
      return true;
    case kAsin:
      if (v < -1.0 || v > 1.0) return domain("ASIN of a value from -1 to 1");
      out = deg(std::asin(v));
      return true;
    case kAtan: {
      // ATAN[y]/[x]: the angle of (x, y), degrees
      if (i >= n_ || c_[i] != '/' || i + 1 >= n_ || c_[i + 1] != '[') {
        return fail(arg_at, "found " + excerpt(at, i + 1) + "; expected ATAN[y]/[x]");
      }
      ++i;
      double x = 0.0;
      if (!expression(i, x, depth + 1)) return false;
      out = deg(std::atan2(v, x));
      return true;
    }
    case kCos: out = std::cos(rad(v)); return true;
    case kExp: out = std::exp(v); return true;
    case kFix: out = std::floor(v); return true;
    case kFup: out = std::ceil(v); return true;
    case kLn:
      if (v <= 0.0) return domain("LN of a value > 0");
      out = std::log(v);
      return true;
    case kRound: out = std::round(v); return true;  // half away from zero, as LinuxCNC
    case kSin: out = std::sin(rad(v)); return true;
    case kSqrt:
      if (v < 0.0) return domain("SQRT of a value >= 0");
      out = std::sqrt(v);
      return true;
    case kTan: out = std::tan(rad(v)); return true;
    default: return fail(at, "unknown function");
  }
}

// An operator at i: its code, i past it; false when none is there.
bool ExpressionReader::binary(int op, double& left, double right, std::uint32_t at) {
  auto bad = [&](std::string what) {
    fault_.code = ErrorCode::GcodeBadValue;
    fault_.byte_pos = pos(at);
    fault_.message = std::move(what);
    return false;
  };
  switch (op) {
    case kDivide:
      if (right == 0.0) return bad("found a division by zero; expected a divisor other than 0");
      left /= right;
      return true;
    case kMod:
      if (right == 0.0) return bad("found MOD 0; expected a divisor other than 0");
      left = std::fmod(left, right);
      if (left < 0.0) left += std::fabs(right);
      return true;
    case kPower:
      if (left < 0.0 && std::floor(right) != right) {
        return bad(
            "found a negative number to a non-integer power; expected a whole power of a "
            "negative number");
      }
      left = std::pow(left, right);
      return true;
    case kTimes: left *= right; return true;
    case kPlus: left += right; return true;
    case kMinus: left -= right; return true;
    case kAnd: left = (left != 0.0 && right != 0.0) ? 1.0 : 0.0; return true;
    case kOr: left = (left != 0.0 || right != 0.0) ? 1.0 : 0.0; return true;
    case kXor: left = ((left != 0.0) != (right != 0.0)) ? 1.0 : 0.0; return true;
    case kEq: left = std::fabs(left - right) < kEqualityTolerance ? 1.0 : 0.0; return true;
    case kNe: left = std::fabs(left - right) >= kEqualityTolerance ? 1.0 : 0.0; return true;
    case kLe: left = (std::fabs(left - right) < kEqualityTolerance || left <= right) ? 1.0 : 0.0; return true;
    case kGe: left = (std::fabs(left - right) < kEqualityTolerance || left >= right) ? 1.0 : 0.0; return true;
    case kGt: left = left > right ? 1.0 : 0.0; return true;
    case kLt: left = left < right ? 1.0 : 0.0; return true;
    default: return bad("unknown operator");
  }
}

// [ value { op value } ]: LinuxCNC read_real_expression, an operator stack
// evaluated by precedence, left to right among equals.
bool ExpressionReader::expression(std::uint32_t& i, double& out, int depth) {
  const std::uint32_t open = i;
  ++i;  // '['
  constexpr int kStack = kMaxExpressionDepth;
  std::array<double, kStack + 2> values{};
  std::array<int, kStack + 2> ops{};
  std::array<std::uint32_t, kStack + 2> op_at{};

  auto read_op = [&](int& op, std::uint32_t& at) {
    at = i;
    if (i >= n_) {
      return fail(open, "found " + excerpt(open, i) +
                            ": an expression not closed; expected ']' before the end of the line");
    }
    auto is = [&](const char* s) {
      const std::size_t len = std::strlen(s);
      if (i + len <= n_ && std::memcmp(c_ + i, s, len) == 0) {
        i += static_cast<std::uint32_t>(len);
        return true;
      }
      return false;
    };
    if (is("]"))
      op = kClose;
    else if (is("**"))
      op = kPower;
    else if (is("*"))
      op = kTimes;
    else if (is("/"))
      op = kDivide;
    else if (is("+"))
      op = kPlus;
    else if (is("-"))
      op = kMinus;
    else if (is("MOD"))
      op = kMod;
    else if (is("AND"))
      op = kAnd;
    else if (is("OR"))
      op = kOr;
    else if (is("XOR"))
      op = kXor;
    else if (is("EQ"))
      op = kEq;
    else if (is("NE"))
      op = kNe;
    else if (is("GT"))
      op = kGt;
    else if (is("GE"))
      op = kGe;
    else if (is("LT"))
      op = kLt;
    else if (is("LE"))
      op = kLe;
    else {
      return fail(i, "found " + excerpt(i, i + 6) + " in the expression opened at " +
                         excerpt(open, open + 1) + "; expected an operator (" + kOperators + ") or ']'");
    }
    return true;
  };

  if (!value(i, values[0], depth + 1)) return false;
  if (!read_op(ops[0], op_at[0])) return false;
  int top = 1;
  while (ops[0] != kClose) {
    if (top > kStack) return fail(i, "found an expression too long; expected fewer operators");
    if (!value(i, values[top], depth + 1)) return false;
    if (!read_op(ops[top], op_at[top])) return false;
    if (precedence(ops[top]) > precedence(ops[top - 1])) {
      ++top;
      continue;
    }
    while (precedence(ops[top]) <= precedence(ops[top - 1])) {
      if (!binary(ops[top - 1], values[top - 1], values[top], op_at[top - 1])) return false;
      ops[top - 1] = ops[top];
      op_at[top - 1] = op_at[top];
      if (top > 1 && precedence(ops[top - 1]) <= precedence(ops[top - 2])) {
        --top;
      } else {
        break;
      }
    }
  }
  out = values[0];
  return true;
}

}  // namespace lcnc::gcode
