#include "gcode/line_source.h"

#include <cerrno>
#include <cstring>

namespace lcnc::gcode {

LineSource::LineSource(std::string text)
    : buf_(std::move(text)), end_(buf_.size()), eof_(true) {}

std::unique_ptr<LineSource> LineSource::open_file(const std::string& path, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    error = std::strerror(errno);
    return nullptr;
  }
  std::unique_ptr<LineSource> src(new LineSource());
  src->file_.reset(f);
  src->buf_.resize(kChunkBytes);
  return src;
}

bool LineSource::refill() {
  if (eof_) return false;
  const std::size_t unread = end_ - begin_;
  if (begin_ > 0 && unread > 0) std::memmove(buf_.data(), buf_.data() + begin_, unread);
  begin_ = 0;
  end_ = unread;
  // A line longer than the buffer: grow it (rare; the buffer is then kept).
  if (end_ == buf_.size()) buf_.resize(buf_.size() * 2);
  const std::size_t got = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_.get());
  end_ += got;
  if (got == 0) {  // std::fread returns 0 only at end of file or on an error
    eof_ = true;
    if (std::ferror(file_.get()) != 0) read_error_ = std::strerror(errno);
  }
  return got > 0;
}

bool LineSource::next(std::string_view& line) {
  for (;;) {
    const char* base = buf_.data();
    const void* nl = std::memchr(base + begin_, '\n', end_ - begin_);
    std::size_t line_end = 0;
    std::size_t next_begin = 0;
    if (nl != nullptr) {
      line_end = static_cast<std::size_t>(static_cast<const char*>(nl) - base);
      next_begin = line_end + 1;
    } else if (refill()) {
      continue;
    } else if (begin_ < end_) {  // last line without '\n'
      line_end = end_;
      next_begin = end_;
    } else {
      return false;
    }
    std::size_t line_begin = begin_;
    begin_ = next_begin;
    if (line_end > line_begin && buf_[line_end - 1] == '\r') --line_end;
    if (first_line_) {
      first_line_ = false;
      if (line_end - line_begin >= 3 && std::memcmp(base + line_begin, "\xEF\xBB\xBF", 3) == 0) {
        line_begin += 3;
      }
    }
    line = std::string_view(base + line_begin, line_end - line_begin);
    return true;
  }
}

}  // namespace lcnc::gcode
