// Reads a program line by line from a file or from memory, without holding
// the whole file: a file is read in chunks into one fixed buffer that is
// reused, so reading allocates nothing after open_file. A line is handed out
// as a view valid until the next call. Lines end at "\n", "\r\n" or a lone
// "\r" (old Mac files), each counted as one line end; the end is removed, and
// a UTF-8 byte-order mark at the very start is skipped. A line longer than
// kMaxLineBytes stops reading (too_long()): a file with no line ends
// (/dev/zero, a binary) must fail, not fill the memory.
#pragma once

#include <cstddef>
#include <cstdint>
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
  [[nodiscard]] static std::unique_ptr<LineSource> open_file(const std::string& path, std::string& error);

  // The next line; false at the end of the input, on a read error or at a
  // line longer than kMaxLineBytes.
  [[nodiscard]] bool next(std::string_view& line);
  // Why reading stopped early (empty when the input simply ended or a line
  // was too long): a program must never be cut short silently.
  [[nodiscard]] const std::string& read_error() const noexcept { return read_error_; }
  // Reading stopped at a line longer than kMaxLineBytes (the next line).
  [[nodiscard]] bool too_long() const noexcept { return too_long_; }
  // Bytes the source holds for reading: kChunkBytes for a file, whatever its
  // lines; the text's size in memory.
  [[nodiscard]] std::size_t buffer_bytes() const noexcept { return buf_.capacity(); }

  // Where the next line starts, as a byte offset in the input: what seek()
  // takes back to read a line again (O-word loops, subroutine returns).
  [[nodiscard]] std::uint64_t tell() const noexcept { return base_ + begin_; }
  // The next line starts at `offset` (one tell() returned). Within the chunk
  // held it moves there; else the file is re-read from there. false when the
  // file cannot seek (read_error() says why).
  [[nodiscard]] bool seek(std::uint64_t offset);

  static constexpr std::size_t kChunkBytes = 1u << 20;

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
  };
  LineSource() = default;
  // Moves the unread tail to the front and reads more; sets eof_ when nothing came.
  void refill();

  std::unique_ptr<std::FILE, FileCloser> file_;
  std::string buf_;         // file mode: chunk buffer; memory mode: the text
  std::uint64_t base_ = 0;  // input offset of buf_[0]
  std::size_t begin_ = 0;   // first unread byte
  std::size_t end_ = 0;     // one past the last valid byte
  bool eof_ = false;        // no more bytes beyond end_
  bool first_line_ = true;  // BOM check pending
  bool too_long_ = false;
  std::size_t cr_at_ = 0;  // first '\r' at or after begin_, end_ when none
  bool cr_valid_ = false;  // cr_at_ holds for the bytes in buf_
  std::string read_error_;
};

}  // namespace lcnc::gcode
