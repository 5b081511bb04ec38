#include "common/error.h"

namespace lcnc {

std::string_view error_summary(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::Ok: return "no error";
#define LCNC_ERROR(name, number, summary) \
  case ErrorCode::name:                   \
    return summary;
#include "errors.def"
#undef LCNC_ERROR
  }
  return "unknown error";
}

std::string_view error_name(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::Ok: return "Ok";
#define LCNC_ERROR(name, number, summary) \
  case ErrorCode::name:                   \
    return #name;
#include "errors.def"
#undef LCNC_ERROR
  }
  return "Unknown";
}

namespace {

// Codes that report something the program or file is still used despite:
// they print as warnings (their summaries in share/errors.def say so).
bool is_warning(ErrorCode code) noexcept { return code == ErrorCode::GcodeLinesAfterEnd; }

}  // namespace

std::string Diagnostic::to_string() const {
  std::string out;
  if (!file.empty()) {
    out += file;
    if (line > 0) {
      out += ':' + std::to_string(line);
      if (col > 0) out += ':' + std::to_string(col);
    }
    out += ": ";
  }
  out += is_warning(code) ? "warning E" : "error E";
  out += std::to_string(static_cast<unsigned>(code)) + " (" + std::string(error_name(code)) + "): ";
  out += message.empty() ? std::string(error_summary(code)) : message;
  return out;
}

Diagnostic make_error(ErrorCode code, std::string message, std::string file, std::uint32_t line,
                      std::uint32_t col) {
  return Diagnostic{code, std::move(file), line, col, std::move(message)};
}

}  // namespace lcnc
