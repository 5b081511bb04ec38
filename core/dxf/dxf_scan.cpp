#include "dxf/dxf_scan.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>

#include "common/error.h"
#include "common/quote.h"
#include "dxf/dxf_tolerances.h"

namespace lcnc::dxf {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

enum class ValueType : std::uint8_t { Text, Real, Integer };

// Value types of the group code ranges (DXF reference, "Group code value types").
ValueType value_type(int code) {
  if ((code >= 10 && code <= 59) || (code >= 110 && code <= 149) || (code >= 210 && code <= 239) ||
      (code >= 460 && code <= 469) || (code >= 1010 && code <= 1059)) {
    return ValueType::Real;
  }
  if ((code >= 60 && code <= 99) || (code >= 160 && code <= 179) || (code >= 270 && code <= 299) ||
      (code >= 370 && code <= 389) || (code >= 400 && code <= 409) || (code >= 420 && code <= 429) ||
      (code >= 440 && code <= 459) || (code >= 1060 && code <= 1071)) {
    return ValueType::Integer;
  }
  return ValueType::Text;
}

bool parse_int(std::string_view s, long long& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size() && !s.empty();
}

bool parse_real(std::string_view s, double& out) {
  const std::string str(trim(s));
  if (str.empty()) return false;
  char* end = nullptr;
  out = std::strtod(str.c_str(), &end);
  return end == str.c_str() + str.size() && std::isfinite(out);
}

struct Pair {
  int code;
  std::string_view value;  // trimmed of the line end
  std::uint32_t line;      // of the code
};

// One entity as read: its pairs until the next group 0.
struct PendingEntity {
  std::string type;
  std::uint32_t line = 0;
  std::vector<Pair> pairs;
};

enum class Use : std::uint8_t { Keep, Ignore, Reject };

Use use_of(const std::string& type) {
  static const char* const kKeep[] = {"LINE",   "ARC",    "CIRCLE", "LWPOLYLINE", "POLYLINE", "VERTEX",
                                      "SEQEND", "SPLINE", "INSERT", "BLOCK",      "ENDBLK"};
  for (const char* k : kKeep) {
    if (type == k) return Use::Keep;
  }
  // Drawn geometry that would be cut but is not read: an error rather than a
  // part with a contour silently missing.
  if (type == "ELLIPSE" || type == "HELIX" || type == "REGION" || type == "MLINE") {
    return Use::Reject;
  }
  return Use::Ignore;
}

class Scanner {
 public:
  Scanner(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  Result<ScanResult> run();

 private:
  Diagnostic error(ErrorCode code, std::uint32_t line, std::string msg) const {
    return make_error(code, std::move(msg), file_, line);
  }
  Status finish_entity();
  Status check_counts(const PendingEntity& e) const;
  void emit(int code, std::string_view value) {
    out_.filtered += std::to_string(code);
    out_.filtered += '\n';
    out_.filtered += value;
    out_.filtered += '\n';
  }

  std::string_view text_;
  const std::string& file_;
  ScanResult out_;
  std::string section_;
  PendingEntity entity_;
  bool in_entity_ = false;
  std::map<std::string, int> ignored_;
};

Status Scanner::check_counts(const PendingEntity& e) const {
  // Declared count (group `declared`) against the groups that follow.
  auto check = [&](int declared, int item, const char* what) -> Status {
    long long want = -1;
    std::uint32_t at = e.line;
    std::size_t have = 0;
    for (const Pair& p : e.pairs) {
      if (p.code == declared) {
        (void)parse_int(p.value, want);
        at = p.line;
      }
      if (p.code == item) ++have;
    }
    if (want < 0) return {};  // not declared: dxflib counts itself
    if (static_cast<unsigned long long>(want) > kMaxDeclaredCount) {
      return error(ErrorCode::DxfSyntax, at,
                   e.type + " declares " + std::to_string(want) + " " + what + " (group " +
                       std::to_string(declared) + "); expected at most " + std::to_string(kMaxDeclaredCount));
    }
    if (static_cast<std::size_t>(want) != have) {
      return error(ErrorCode::DxfSyntax, at,
                   e.type + " at line " + std::to_string(e.line) + " declares " + std::to_string(want) + " " +
                       what + " (group " + std::to_string(declared) + ") but has " + std::to_string(have) +
                       " (group " + std::to_string(item) + "); expected the two to agree");
    }
    return {};
  };
  if (e.type == "LWPOLYLINE") return check(90, 10, "vertices");
  if (e.type == "SPLINE") {
    if (Status s = check(72, 40, "knots"); !s) return s;
    if (Status s = check(73, 10, "control points"); !s) return s;
    return check(74, 11, "fit points");
  }
  return {};
}

Status Scanner::finish_entity() {
  if (!in_entity_) return {};
  in_entity_ = false;
  const PendingEntity& e = entity_;
  const Use use = use_of(e.type);
  if (use == Use::Ignore) {
    ++ignored_[e.type];
    return {};
  }
  // Paper space (group 67 = 1): layouts and title blocks, never cut.
  for (const Pair& p : e.pairs) {
    long long v = 0;
    if (p.code == 67 && parse_int(p.value, v) && v == 1) {
      ++ignored_[e.type + " in paper space"];
      return {};
    }
  }
  if (use == Use::Reject) {
    return error(ErrorCode::DxfUnsupported, e.line,
                 e.type +
                     " is not supported; expected LINE, ARC, CIRCLE, LWPOLYLINE, "
                     "POLYLINE, SPLINE or INSERT (convert it to a polyline or spline)");
  }
  // dxflib reads these values; they must be numbers here.
  for (const Pair& p : e.pairs) {
    const ValueType t = value_type(p.code);
    if (t == ValueType::Real) {
      double v = 0;
      if (!parse_real(p.value, v)) {
        return error(ErrorCode::DxfSyntax, p.line + 1,
                     "found " + quote(trim(p.value)) + " for group " + std::to_string(p.code) + " of " +
                         e.type + " at line " + std::to_string(e.line) + "; expected a finite real number");
      }
    } else if (t == ValueType::Integer) {
      long long v = 0;
      if (!parse_int(p.value, v)) {
        return error(ErrorCode::DxfSyntax, p.line + 1,
                     "found " + quote(trim(p.value)) + " for group " + std::to_string(p.code) + " of " +
                         e.type + " at line " + std::to_string(e.line) + "; expected an integer");
      }
    }
  }
  if (Status s = check_counts(e); !s) return s;

  if (e.type == "LINE") out_.line_lines.push_back(e.line);
  if (e.type == "ARC") out_.arc_lines.push_back(e.line);
  if (e.type == "CIRCLE") out_.circle_lines.push_back(e.line);
  if (e.type == "SPLINE") out_.spline_lines.push_back(e.line);
  if (e.type == "INSERT") out_.insert_lines.push_back(e.line);
  if (e.type == "LWPOLYLINE" || e.type == "POLYLINE") {
    out_.poly_lines.push_back(e.line);
    out_.poly_is_lw.push_back(e.type == "LWPOLYLINE");
  }
  emit(0, e.type);
  for (const Pair& p : e.pairs) emit(p.code, p.value);
  return {};
}

Result<ScanResult> Scanner::run() {
  if (text_.substr(0, 18) == "AutoCAD Binary DXF") {
    return error(ErrorCode::DxfUnsupported, 1, "binary DXF is not supported; expected an ASCII DXF");
  }
  // Split into lines once (views into text_).
  std::vector<std::string_view> lines;
  for (std::size_t pos = 0; pos < text_.size();) {
    const std::size_t nl = text_.find('\n', pos);
    const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
    std::string_view l = text_.substr(pos, end - pos);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (l.size() > kMaxDxfLine) {
      return error(ErrorCode::DxfSyntax, static_cast<std::uint32_t>(lines.size() + 1),
                   "a line of " + std::to_string(l.size()) + " characters; expected at most " +
                       std::to_string(kMaxDxfLine) + " (a group code or value)");
    }
    lines.push_back(l);
    pos = end + 1;
  }
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();
  if (lines.empty()) return error(ErrorCode::DxfSyntax, 0, "empty file; expected a DXF drawing");

  std::string header_var;
  std::string acadver;
  bool expect_section_name = false;
  bool seen_eof = false;
  std::uint32_t section_line = 0;
  for (std::size_t i = 0; i < lines.size(); i += 2) {
    const auto line = static_cast<std::uint32_t>(i + 1);
    long long code_ll = 0;
    if (!parse_int(lines[i], code_ll) || code_ll < -5 || code_ll > 1071) {
      return error(ErrorCode::DxfSyntax, line,
                   "found " + quote(trim(lines[i])) +
                       " where a group code was expected (an integer 0–1071 on the first "
                       "line of each code/value pair)");
    }
    if (i + 1 >= lines.size()) {
      return error(ErrorCode::DxfSyntax, line,
                   "group code " + std::to_string(code_ll) +
                       " has no value: the file ends; expected a value line (truncated file?)");
    }
    const int code = static_cast<int>(code_ll);
    const std::string_view value = trim(lines[i + 1]);
    if (seen_eof) break;  // anything after EOF is not read (as AutoCAD)

    if (code == 0) {
      if (Status s = finish_entity(); !s) return s.error();
      if (expect_section_name) {
        return error(ErrorCode::DxfSyntax, line, "SECTION without a name; expected group 2");
      }
      if (value == "EOF") {
        if (!section_.empty()) {
          return error(ErrorCode::DxfSyntax, line,
                       "EOF inside section " + section_ + " (opened at line " + std::to_string(section_line) +
                           "); expected 0/ENDSEC first");
        }
        seen_eof = true;
        continue;
      }
      if (value == "SECTION") {
        if (!section_.empty()) {
          return error(ErrorCode::DxfSyntax, line,
                       "SECTION inside section " + section_ + " (opened at line " +
                           std::to_string(section_line) + "); expected 0/ENDSEC first");
        }
        expect_section_name = true;
        section_line = line;
        continue;
      }
      if (value == "ENDSEC") {
        if (section_.empty()) {
          return error(ErrorCode::DxfSyntax, line, "ENDSEC without a SECTION");
        }
        if (section_ == "BLOCKS" || section_ == "ENTITIES") emit(0, "ENDSEC");
        section_.clear();
        continue;
      }
      if (section_.empty()) {
        return error(ErrorCode::DxfSyntax, line,
                     "found " + quote(value) + " outside any section; expected 0/SECTION or 0/EOF");
      }
      if (section_ == "BLOCKS" || section_ == "ENTITIES") {
        in_entity_ = true;
        entity_.type = std::string(value);
        entity_.line = line;
        entity_.pairs.clear();
      }
      continue;
    }
    if (expect_section_name) {
      if (code != 2) {
        return error(
            ErrorCode::DxfSyntax, line,
            "found group " + std::to_string(code) + " after SECTION; expected 2 and the section name");
      }
      section_ = std::string(value);
      expect_section_name = false;
      if (section_ == "BLOCKS" || section_ == "ENTITIES") {
        emit(0, "SECTION");
        emit(2, section_);
      }
      continue;
    }
    if (section_ == "HEADER") {
      if (code == 9) {
        header_var = std::string(value);
      } else if (header_var == "$INSUNITS" && code == 70) {
        long long u = 0;
        if (!parse_int(value, u)) {
          return error(ErrorCode::DxfSyntax, line + 1,
                       "found " + quote(value) + " for $INSUNITS; expected an integer");
        }
        out_.insunits = static_cast<int>(u);
      } else if (header_var == "$ACADVER" && code == 1) {
        acadver = std::string(value);
      }
      continue;
    }
    if (in_entity_) entity_.pairs.push_back(Pair{code, value, line});
  }
  if (!seen_eof) {
    if (Status s = finish_entity(); !s) return s.error();
    return error(ErrorCode::DxfSyntax, static_cast<std::uint32_t>(lines.size()),
                 section_.empty() ? std::string("the file ends without 0/EOF (truncated?)")
                                  : "the file ends inside section " + section_ + " (opened at line " +
                                        std::to_string(section_line) +
                                        ") without 0/ENDSEC and 0/EOF "
                                        "(truncated?)");
  }
  if (!acadver.empty()) {
    out_.filtered = "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\n" + acadver + "\n0\nENDSEC\n" + out_.filtered;
  }
  out_.filtered += "0\nEOF\n";
  for (const auto& [type, n] : ignored_) out_.ignored.push_back(std::to_string(n) + " " + type);
  return std::move(out_);
}

}  // namespace

Result<ScanResult> scan_dxf(std::string_view text, const std::string& file) {
  return Scanner(text, file).run();
}

}  // namespace lcnc::dxf
