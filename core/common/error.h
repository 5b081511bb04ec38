// Errors off the RT path: an ErrorCode from the one table (share/errors.def)
// plus a Diagnostic that says where (file:line:col) and what was found and
// expected. States and errors are separate: nothing here is a state.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace lcnc {

enum class ErrorCode : std::uint16_t {
  Ok = 0,
#define LCNC_ERROR(name, number, summary) name = number,  // NOLINT(bugprone-macro-parentheses): an enumerator
#include "errors.def"
#undef LCNC_ERROR
};

// Fixed summary text of an error code (from share/errors.def).
[[nodiscard]] std::string_view error_summary(ErrorCode code) noexcept;
// Symbolic name of an error code, e.g. "GcodeNoFeed".
[[nodiscard]] std::string_view error_name(ErrorCode code) noexcept;

struct Diagnostic {
  ErrorCode code = ErrorCode::Ok;
  std::string file;        // empty when not about a file
  std::uint32_t line = 0;  // 1-based; 0 = no line
  std::uint32_t col = 0;   // 1-based; 0 = no column
  std::string message;     // what was found and what was expected

  // "file:line:col: error E301 (GcodeNoFeed): message"
  [[nodiscard]] std::string to_string() const;
};

[[nodiscard]] Diagnostic make_error(ErrorCode code, std::string message, std::string file = {},
                                    std::uint32_t line = 0, std::uint32_t col = 0);

}  // namespace lcnc
