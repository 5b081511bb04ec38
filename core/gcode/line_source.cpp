#include "gcode/line_source.h"

#include <cerrno>
#include <cstring>

#include "gcode/gcode_tolerances.h"

namespace lcnc::gcode {

// The unread tail moved to the front by refill() is shorter than a line
// (else reading stopped), so a chunk always has room for more.
static_assert(kMaxLineBytes + 2 < LineSource::kChunkBytes,
              "a whole line and its end must fit one read chunk");

LineSource::LineSource(std::string text) : buf_(std::move(text)), end_(buf_.size()), eof_(true) {}

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

void LineSource::refill() {
  const std::size_t unread = end_ - begin_;
  if (begin_ > 0 && unread > 0) std::memmove(buf_.data(), buf_.data() + begin_, unread);
  base_ += begin_;
  begin_ = 0;
  end_ = unread;
  cr_valid_ = false;  // the bytes moved
  const std::size_t got = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_.get());
  end_ += got;
  if (got == 0) {  // std::fread returns 0 only at end of file or on an error
    eof_ = true;
    if (std::ferror(file_.get()) != 0) read_error_ = std::strerror(errno);
  }
}

bool LineSource::seek(std::uint64_t offset) {
  too_long_ = false;
  first_line_ = offset == 0;
  cr_valid_ = false;
  if (offset >= base_ && offset <= base_ + end_) {  // within what is held
    begin_ = static_cast<std::size_t>(offset - base_);
    return true;
  }
  if (!file_ || std::fseek(file_.get(), static_cast<long>(offset), SEEK_SET) != 0) {
    read_error_ = file_ ? std::strerror(errno) : "offset beyond the text";
    begin_ = end_;
    eof_ = true;
    return false;
  }
  base_ = offset;
  begin_ = end_ = 0;
  eof_ = false;
  return true;
}

bool LineSource::next(std::string_view& line) {
  if (too_long_) return false;
  for (;;) {
    const char* base = buf_.data();
    const char* p = base + begin_;
    // The first '\n', and the first '\r' (kept from an earlier search while
    // still ahead: a file without any costs one search per chunk, not per
    // line). "\r\n" or a lone '\r' before the '\n' ends the line there.
    const auto* nl = static_cast<const char*>(std::memchr(p, '\n', end_ - begin_));
    if (!cr_valid_ || cr_at_ < begin_) {
      const auto* r = static_cast<const char*>(std::memchr(p, '\r', end_ - begin_));
      cr_at_ = r != nullptr ? static_cast<std::size_t>(r - base) : end_;
      cr_valid_ = true;
    }
    const char* stop = nl != nullptr ? nl : base + end_;
    const char* cr = cr_at_ < static_cast<std::size_t>(stop - base) ? base + cr_at_ : nullptr;
    std::size_t line_end = 0;
    std::size_t next_begin = 0;
    if (cr != nullptr && (cr + 1 < base + end_ || eof_)) {
      // a '\r' whose next byte is known (or that ends the input)
      line_end = static_cast<std::size_t>(cr - base);
      next_begin = line_end + (cr + 1 == nl ? 2 : 1);
    } else if (nl != nullptr) {
      line_end = static_cast<std::size_t>(nl - base);
      next_begin = line_end + 1;
    } else if (static_cast<std::size_t>((cr != nullptr ? cr : stop) - p) > kMaxLineBytes) {
      too_long_ = true;  // no line end within the bound: stop before reading more
      return false;
    } else if (!eof_) {
      refill();
      continue;
    } else if (begin_ < end_) {  // last line without a line end
      line_end = end_;
      next_begin = end_;
    } else {
      return false;
    }
    if (line_end - begin_ > kMaxLineBytes) {
      too_long_ = true;
      return false;
    }
    std::size_t line_begin = begin_;
    begin_ = next_begin;
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
