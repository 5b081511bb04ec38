// RS274NGC values as LinuxCNC reads them: a number, a parameter (#5, #[expr],
// ##2, #<name>), a bracketed expression with binary operators
// ([#1 + 2 * SIN[30]]), a function (ABS ACOS ASIN ATAN[y]/[x] COS EXP FIX
// FUP LN ROUND SIN SQRT TAN, EXISTS[#<name>]) or a signed one of those.
//
// Operators and their precedence (LinuxCNC interp_internal precedence(); the
// same precedence evaluates left to right): ** ; * / MOD ; + - ;
// EQ NE GT GE LT LE ; AND OR XOR. Angles are degrees. EQ and NE compare
// within 1e-6; AND OR XOR give 1 or 0, any non-zero being true; MOD is never
// negative; a division by zero, a square root or logarithm out of domain,
// ACOS/ASIN beyond ±1, a negative number to a non-integer power and a result
// that is not finite are errors, each saying where.
//
// The text is the block parser's compacted line: upper-case, without blanks
// or comments, with the byte offset in the original line of each character,
// so an error points at the column the user wrote.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "gcode/block_parser.h"

namespace lcnc::gcode {

// Parameters #1 … #5602 (LinuxCNC's RS274NGC_MAX_PARAMETERS − 1).
inline constexpr int kMaxParameterIndex = 5602;
// Brackets nested at most this deep (a line is 64 KiB: no stack overflow).
inline constexpr int kMaxExpressionDepth = 64;

// Where expressions read parameters. Names come lower-cased, without < >.
class ParameterReader {
 public:
  virtual ~ParameterReader() = default;
  // #index, 1 <= index <= kMaxParameterIndex; unset ones read 0.
  [[nodiscard]] virtual double numbered(int index) const = 0;
  // #<name>: false when it is not defined (an error for the reader).
  [[nodiscard]] virtual bool named(std::string_view name, double& out) const = 0;
  // What an assignment may not set (#index, or #<name> when index is 0):
  // why not ("the current position, …"), empty when it may.
  [[nodiscard]] virtual std::string read_only(int index, std::string_view name) const {
    (void)index;
    (void)name;
    return {};
  }
};

class ExpressionReader {
 public:
  ExpressionReader(const LineText& text, const ParameterReader& params)
      : c_(text.compact.data()), n_(text.size), text_(text), params_(params) {}

  // A real value starting at compact index i; i moves past it. false on
  // error (fault()).
  [[nodiscard]] bool real_value(std::uint32_t& i, double& out);
  // A real value that must be a whole number (within 1e-4, as LinuxCNC's
  // read_integer_value), e.g. a parameter index.
  [[nodiscard]] bool integer_value(std::uint32_t& i, int& out);
  // A parameter name "<...>" at i (i on '<'): lower-cased, i past the '>'.
  [[nodiscard]] bool name(std::uint32_t& i, std::string& out);

  [[nodiscard]] const Fault& fault() const noexcept { return fault_; }

 private:
  bool expression(std::uint32_t& i, double& out, int depth);
  bool value(std::uint32_t& i, double& out, int depth);
  bool parameter(std::uint32_t& i, double& out, int depth);
  bool function(std::uint32_t& i, double& out, int depth);
  bool number(std::uint32_t& i, double& out);
  bool binary(int op, double& left, double right, std::uint32_t at);
  bool fail(std::uint32_t at, std::string message);
  [[nodiscard]] std::uint32_t pos(std::uint32_t i) const;
  [[nodiscard]] std::string excerpt(std::uint32_t begin, std::uint32_t end) const;

  const char* c_;
  std::uint32_t n_;
  const LineText& text_;
  const ParameterReader& params_;
  Fault fault_;
};

}  // namespace lcnc::gcode
