#include "common/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdarg>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <random>

namespace lcnc {
namespace {

// The stdio buffer of an output: rows are small, syscalls few.
constexpr std::size_t kBufferBytes = std::size_t{1} << 20;
// Names tried for the temporary file before giving up (each O_EXCL).
constexpr int kTempAttempts = 64;

// What makes two paths the same file: device and inode of the file, or for a
// file not there yet, of its directory plus its name.
struct FileId {
  dev_t dev = 0;
  ino_t ino = 0;
  std::string name;  // empty: the file exists (dev, ino are its own)
  bool operator==(const FileId&) const = default;
};

std::string dir_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string base_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::optional<FileId> file_id(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return FileId{st.st_dev, st.st_ino, {}};
  if (errno != ENOENT) return std::nullopt;
  if (::stat(dir_of(path).c_str(), &st) != 0) return std::nullopt;
  return FileId{st.st_dev, st.st_ino, base_of(path)};
}

Diagnostic same_file(const std::string& output, const std::string& other, const char* what) {
  return make_error(ErrorCode::OutputIsInput,
                    "the output '" + output + "' is the same file as " + what + " '" + other +
                        "'; expected an output that is neither an input nor another output",
                    output);
}

Diagnostic write_error(const std::string& path, int err, const char* doing) {
  return make_error(ErrorCode::OutputWrite,
                    std::string("cannot ") + doing + ": " + std::strerror(err) +
                        "; expected a writable file with room for the output",
                    path);
}

// An output not there yet is still refused where an input will be (a
// parameter file the run writes at its end): same folder, same name.
Status check_inputs(const std::string& output, const std::optional<FileId>& id,
                    const std::vector<std::string>& inputs) {
  if (!id) return {};
  for (const std::string& in : inputs) {
    if (in.empty()) continue;
    if (const std::optional<FileId> iid = file_id(in); iid && *iid == *id)
      return same_file(output, in, "the input");
  }
  return {};
}

}  // namespace

Status check_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  std::vector<std::pair<std::string, FileId>> seen;
  for (const std::string& out : outputs) {
    if (out.empty()) continue;
    const std::optional<FileId> id = file_id(out);
    if (Status s = check_inputs(out, id, inputs); !s) return s;
    if (!id) continue;  // open() reports why it cannot be written
    for (const auto& [other, oid] : seen)
      if (oid == *id) return same_file(out, other, "the output");
    seen.emplace_back(out, *id);
  }
  return {};
}

Result<OutputFile> OutputFile::open(const std::string& path, const std::vector<std::string>& inputs) {
  if (path.empty()) return make_error(ErrorCode::OutputWrite, "an output needs a file name");
  OutputFile f;
  f.path_ = path;
  f.target_ = path;
  if (path == "-" || path == "/dev/stdout") {
    // This process's standard output, whatever it is (a terminal, a pipe,
    // a file the shell opened): written through it, never renamed over —
    // when it is a regular file, the path names the shell's redirection.
    const int fd = ::dup(STDOUT_FILENO);
    f.file_ = fd >= 0 ? ::fdopen(fd, "w") : nullptr;
    if (f.file_ == nullptr) {
      const int err = errno;
      if (fd >= 0) ::close(fd);
      return write_error(path, err, "open it");
    }
    std::setvbuf(f.file_, nullptr, _IOFBF, kBufferBytes);
    return f;
  }
  if (path.starts_with("/dev/") || path.starts_with("/proc/")) {
    // a device or a process's descriptor: written in place, never renamed over
    f.file_ = std::fopen(path.c_str(), "w");
    if (f.file_ == nullptr) return write_error(path, errno, "open it");
    std::setvbuf(f.file_, nullptr, _IOFBF, kBufferBytes);
    return f;
  }
  if (Status s = check_inputs(path, file_id(path), inputs); !s) return s.error();
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return write_error(path, EISDIR, "write it");
    if (!S_ISREG(st.st_mode)) {
      // A device or FIFO: written in place (see the header).
      f.file_ = std::fopen(path.c_str(), "w");
      if (f.file_ == nullptr) return write_error(path, errno, "open it");
      std::setvbuf(f.file_, nullptr, _IOFBF, kBufferBytes);
      return f;
    }
    char* real = ::realpath(path.c_str(), nullptr);  // a symlink: replace what it names
    if (real != nullptr) {
      f.target_ = real;
      std::free(real);
    }
    f.has_mode_ = true;
    f.mode_ = st.st_mode & 07777;
  } else if (errno != ENOENT) {
    return write_error(path, errno, "open it");
  }
  const std::string dir = dir_of(f.target_), base = base_of(f.target_);
  std::random_device rd;
  int fd = -1;
  int err = 0;
  for (int attempt = 0; attempt < kTempAttempts && fd < 0; ++attempt) {
    char tag[16];
    std::snprintf(tag, sizeof tag, "%06x", static_cast<unsigned>(rd()) & 0xffffffu);
    f.temp_ = dir + "/." + base + "." + tag + ".tmp";
    // 0666 less the umask, as for any new file; a replaced file's mode below
    fd = ::open(f.temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    err = errno;
    if (fd < 0 && err != EEXIST) break;
  }
  if (fd < 0) {
    f.temp_.clear();
    return write_error(path, err, ("create a file in " + dir).c_str());
  }
  if (f.has_mode_ && ::fchmod(fd, f.mode_) != 0) {
    err = errno;
    ::close(fd);
    ::unlink(f.temp_.c_str());
    f.temp_.clear();
    return write_error(path, err, "keep its permissions");
  }
  f.file_ = ::fdopen(fd, "w");
  if (f.file_ == nullptr) {
    err = errno;
    ::close(fd);
    ::unlink(f.temp_.c_str());
    f.temp_.clear();
    return write_error(path, err, "open it");
  }
  std::setvbuf(f.file_, nullptr, _IOFBF, kBufferBytes);
  return f;
}

OutputFile::OutputFile(OutputFile&& o) noexcept
    : path_(std::move(o.path_)),
      target_(std::move(o.target_)),
      temp_(std::move(o.temp_)),
      file_(o.file_),
      errno_(o.errno_),
      has_mode_(o.has_mode_),
      mode_(o.mode_) {
  o.file_ = nullptr;
  o.temp_.clear();
}

OutputFile& OutputFile::operator=(OutputFile&& o) noexcept {
  if (this != &o) {
    discard();
    path_ = std::move(o.path_);
    target_ = std::move(o.target_);
    temp_ = std::move(o.temp_);
    file_ = o.file_;
    errno_ = o.errno_;
    has_mode_ = o.has_mode_;
    mode_ = o.mode_;
    o.file_ = nullptr;
    o.temp_.clear();
  }
  return *this;
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() noexcept {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  if (!temp_.empty()) ::unlink(temp_.c_str());
  temp_.clear();
}

void OutputFile::note_error() noexcept {
  if (errno_ == 0) errno_ = errno != 0 ? errno : EIO;
}

void OutputFile::write(std::string_view text) {
  if (file_ == nullptr || errno_ != 0 || text.empty()) return;
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) note_error();
}

void OutputFile::printf(const char* format, ...) {
  if (file_ == nullptr || errno_ != 0) return;
  std::va_list args;
  va_start(args, format);
  errno = 0;
  if (std::vfprintf(file_, format, args) < 0) note_error();
  va_end(args);
}

Status OutputFile::commit() {
  if (file_ == nullptr) return make_error(ErrorCode::Internal, "output committed twice", path_);
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_) != 0) note_error();
  if (errno_ == 0 && !temp_.empty() && ::fsync(::fileno(file_)) != 0) note_error();
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) note_error();
  if (errno_ != 0) {
    const int err = errno_;
    discard();
    return write_error(path_, err, "write it");
  }
  if (!temp_.empty()) {
    if (::rename(temp_.c_str(), target_.c_str()) != 0) {
      const int err = errno;
      discard();
      return write_error(path_, err, "replace it");
    }
    temp_.clear();
  }
  return {};
}

Status write_output(const std::string& path, const std::vector<std::string>& inputs,
                    const std::function<void(std::ostream&)>& fill) {
  Result<OutputFile> f = OutputFile::open(path, inputs);
  if (!f) return f.error();
  OutputStreamBuf buf(*f);
  std::ostream out(&buf);
  fill(out);
  out.flush();
  return f->commit();
}

}  // namespace lcnc
