// Reads a program line by line from a file or from memory, without holding
// the whole file: a file is read in chunks into one growing buffer that is
// reused, so steady-state reading allocates nothing. A line is handed out as a
// view valid until the next call; its '\n' and a trailing '\r' are removed,
// and a UTF-8 byte-order mark at the very start is skipped.
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

namespace lcnc::gcode {

class LineSource {
 public:
  // Reads lines out of `text` (kept by the source).
  explicit LineSource(std::string text);
  // Opens a file; on failure returns nullptr and sets `error` to the reason.
  [[nodiscard]] static std::unique_ptr<LineSource> open_file(const std::string& path,
                                                             std::string& error);

  // The next line; false at the end of the input or on a read error.
  [[nodiscard]] bool next(std::string_view& line);
  // Why reading stopped early (empty when the input simply ended): a
  // program must never be cut short silently.
  [[nodiscard]] const std::string& read_error() const noexcept { return read_error_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
  };
  LineSource() = default;
  // Moves the unread tail to the front and reads more; false when nothing new came.
  bool refill();

  static constexpr std::size_t kChunkBytes = 1u << 20;

  std::unique_ptr<std::FILE, FileCloser> file_;
  std::string buf_;          // file mode: chunk buffer; memory mode: the text
  std::size_t begin_ = 0;    // first unread byte
  std::size_t end_ = 0;      // one past the last valid byte
  bool eof_ = false;         // no more bytes beyond end_
  bool first_line_ = true;   // BOM check pending
  std::string read_error_;
};

}  // namespace lcnc::gcode
