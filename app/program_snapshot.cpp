#include "app/program_snapshot.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace lcnc::app {
namespace {

// The copy's home: an unlinked file in the temporary folder ($TMPDIR,
// /var/tmp, /tmp: on disk, so a program of any length costs page cache that
// the kernel can drop, not memory), else an anonymous memory file.
int open_copy() {
  for (const char* dir : {static_cast<const char*>(std::getenv("TMPDIR")), "/var/tmp", "/tmp"}) {
    if (dir == nullptr || *dir == '\0') continue;
    const int fd = open(dir, O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd >= 0) return fd;
  }
  return memfd_create("lasercncd-program", MFD_CLOEXEC);
}

// Closes a descriptor on every way out.
struct Fd {
  int fd = -1;
  explicit Fd(int f) : fd(f) {}
  ~Fd() {
    if (fd >= 0) close(fd);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int release() { return std::exchange(fd, -1); }
};

Diagnostic refused(const std::string& path, const std::string& why) {
  // the diagnostic names the file: the message says only why
  return make_error(ErrorCode::FileNotFound, "cannot load it: " + why, path);
}

const char* kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a named pipe (FIFO)";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

// The sender may read the file by its mode bits: owner, group or others
// (root reads anything). Its supplementary groups are not known: a file
// readable only through one of them is refused.
bool sender_may_read(const struct stat& st, std::uint32_t uid, std::uint32_t gid) {
  if (uid == 0) return true;
  if (st.st_uid == uid) return (st.st_mode & S_IRUSR) != 0;
  if (st.st_gid == gid) return (st.st_mode & S_IRGRP) != 0;
  return (st.st_mode & S_IROTH) != 0;
}

// Where `fd` really is: its canonical path (symlinks and ".." resolved).
std::string real_path_of(int fd) {
  std::array<char, 4096> buf{};
  const std::string link = "/proc/self/fd/" + std::to_string(fd);
  const ssize_t n = readlink(link.c_str(), buf.data(), buf.size() - 1);
  return n > 0 ? std::string(buf.data(), static_cast<std::size_t>(n)) : std::string();
}

bool inside(const std::string& path, const std::vector<std::string>& dirs) {
  for (const std::string& d : dirs) {
    const std::string prefix = d.ends_with('/') ? d : d + "/";
    if (path.starts_with(prefix)) return true;
  }
  return false;
}

// The policy on a file opened already (`real`: where it is): why it may not
// be read, empty if it may.
std::string access_of(const struct stat& st, const std::string& real, const FileAccess& a) {
  if (!S_ISREG(st.st_mode)) return std::string("it is ") + kind_of(st.st_mode) + "; expected a regular file";
  if (!sender_may_read(st, a.sender_uid, a.sender_gid))
    return "the sender (uid " + std::to_string(a.sender_uid) + ") may not read it";
  if (!a.program_dirs.empty() && !inside(real, a.program_dirs)) {
    std::string dirs;
    for (const std::string& d : a.program_dirs) dirs += (dirs.empty() ? "" : ", ") + d;
    return "outside the program folders; expected a file in " + dirs;
  }
  return {};
}

bool write_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

}  // namespace

bool looks_like_program(const std::string& head, bool hole_table) {
  std::size_t i = head.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // UTF-8 BOM
  for (std::size_t k = i; k < head.size(); ++k) {
    const auto c = static_cast<unsigned char>(head[k]);
    if (c < 0x20 && c != '\t' && c != '\r' && c != '\n') return false;  // binary
  }
  // the first line that says something
  for (;;) {
    while (i < head.size() && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n')) ++i;
    if (i >= head.size()) return true;  // empty: the reader says so
    if (!hole_table || head[i] != '#') break;
    while (i < head.size() && head[i] != '\n') ++i;  // a table's comment line
  }
  const std::size_t eol = std::min(head.find('\n', i), head.size());
  if (hole_table) {
    // a header: column names, commas
    for (std::size_t k = i; k < eol; ++k) {
      const char c = head[k];
      if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) ||
            c == '_' || c == ',' || c == ' ' || c == '\t' || c == '"' || c == '\r'))
        return false;
    }
    return true;
  }
  const char c = head[i];
  if (c == '(' || c == ';' || c == '%' || c == '/' || c == '#') return true;
  if (!std::isalpha(static_cast<unsigned char>(c))) return false;
  std::size_t k = i + 1;
  while (k < eol && (head[k] == ' ' || head[k] == '\t')) ++k;
  if (k >= eol) return false;
  const char n = head[k];
  return std::isdigit(static_cast<unsigned char>(n)) || n == '+' || n == '-' || n == '.' || n == '#' ||
         n == '[' || ((c == 'o' || c == 'O') && n == '<');  // o<name> sub
}

Result<std::shared_ptr<const ProgramSnapshot>> ProgramSnapshot::take(const SnapshotRequest& r) {
  const std::string& path = r.path;
  // O_NONBLOCK: a FIFO without a writer, a device, must not block the open;
  // what it is, fstat says next, on the file opened (no race with a rename).
  Fd in(open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (in.fd < 0) return refused(path, std::strerror(errno));
  struct stat st {};
  if (fstat(in.fd, &st) != 0) return refused(path, std::strerror(errno));
  if (const std::string why = access_of(st, real_path_of(in.fd), r.access); !why.empty())
    return refused(path, why);
  if (static_cast<std::uint64_t>(st.st_size) > kMaxProgramBytes)
    return refused(path, std::to_string(st.st_size) + " bytes; a program may have at most " +
                             std::to_string(kMaxProgramBytes) + " bytes");
  // Reads block again from here: a regular file's read does not wait for a writer.
  const int flags = fcntl(in.fd, F_GETFL);
  if (flags >= 0) (void)fcntl(in.fd, F_SETFL, flags & ~O_NONBLOCK);
  Fd copy(open_copy());
  if (copy.fd < 0) return refused(path, std::string("no room for its copy: ") + std::strerror(errno));
  std::string head;
  std::uint64_t total = 0;
  std::array<char, 1 << 16> buf{};
  for (;;) {
    if (r.cancel != nullptr && r.cancel->load(std::memory_order_relaxed))
      return refused(path, "cancelled (stop, reset or shutdown) while it was copied");
    const ssize_t n = read(in.fd, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return refused(path, std::string("read failed: ") + std::strerror(errno));
    if (n == 0) break;
    const auto got = static_cast<std::size_t>(n);
    if (head.size() < kSniffBytes) head.append(buf.data(), std::min(got, kSniffBytes - head.size()));
    total += got;
    if (total > kMaxProgramBytes)  // it grew while being read
      return refused(
          path, "longer than " + std::to_string(kMaxProgramBytes) + " bytes, the most a program may have");
    if (!write_all(copy.fd, buf.data(), got))
      return refused(path, std::string("no room for its copy: ") + std::strerror(errno));
  }
  if (!looks_like_program(head, r.hole_table)) {
    // Its content is not shown: the daemon may read files its sender may not.
    return make_error(r.hole_table ? ErrorCode::HoleTableSyntax : ErrorCode::GcodeSyntax,
                      std::string("not ") + (r.hole_table ? "a hole table" : "a G-code program") +
                          " (binary, or its first line is not " +
                          (r.hole_table ? "a header of column names" : "a G-code block") +
                          "); its content is not shown",
                      path, 1, 1);
  }
  return std::shared_ptr<const ProgramSnapshot>(new ProgramSnapshot(path, copy.release(), total, r.access));
}

Status may_read(const std::string& path, const FileAccess& access) {
  // opened as take() opens, so that what is checked is the file itself
  Fd in(open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  struct stat st {};
  std::string why = in.fd < 0 || fstat(in.fd, &st) != 0 ? std::string(std::strerror(errno))
                                                        : access_of(st, real_path_of(in.fd), access);
  if (why.empty()) return {};
  return make_error(ErrorCode::FileNotFound, why, path);
}

Result<std::shared_ptr<const ProgramSnapshot>> ProgramSnapshot::from_text(std::string name,
                                                                          const std::string& text,
                                                                          FileAccess access) {
  Fd copy(open_copy());
  if (copy.fd < 0 || !write_all(copy.fd, text.data(), text.size()))
    return make_error(ErrorCode::FileNotFound, std::string("no room for its copy: ") + std::strerror(errno),
                      name);
  return std::shared_ptr<const ProgramSnapshot>(
      new ProgramSnapshot(std::move(name), copy.release(), text.size(), std::move(access)));
}

ProgramSnapshot::ProgramSnapshot(std::string name, int fd, std::uint64_t bytes, FileAccess access)
    : name_(std::move(name)),
      access_(std::move(access)),
      path_("/proc/self/fd/" + std::to_string(fd)),
      fd_(fd),
      bytes_(bytes) {}

ProgramSnapshot::~ProgramSnapshot() {
  if (fd_ >= 0) close(fd_);
}

Diagnostic ProgramSnapshot::rename(Diagnostic d) const {
  if (d.file == path_) d.file = name_;
  for (std::size_t at = d.message.find(path_); at != std::string::npos;
       at = d.message.find(path_, at + name_.size()))
    d.message.replace(at, path_.size(), name_);
  return d;
}

}  // namespace lcnc::app
