// What lasercncd runs of a `load`: a private copy of the file taken once,
// when it is loaded, so the job runs exactly the content that was checked —
// editing or replacing the file afterwards changes nothing of the job.
//
// The file is opened without blocking (O_NONBLOCK: a FIFO nobody writes
// opens at once) and refused unless it is a regular file, readable by the
// sender (its uid/gid as the command frame carries them: the group's trust,
// rt/shm_interface.h), inside the configured program folders when there are
// any, at most kMaxProgramBytes long, and text that looks like a program:
// a file that is not is refused without quoting its bytes. The copy lives in
// an unlinked temporary file on disk (an anonymous memory file where none
// can be made) that the reader and the planner open through /proc/self/fd,
// like any program file: streaming from it keeps the daemon's memory
// bounded whatever the program's length.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/result.h"

namespace lcnc::app {

// The largest program a load takes: 4 GiB, some 100 million CAM lines (its
// copy takes as much of the temporary folder's disk).
inline constexpr std::uint64_t kMaxProgramBytes = 4ull << 30;
// The bytes looked at to tell a program from another file.
inline constexpr std::size_t kSniffBytes = 4096;

// Who a file is read for, and where it may lie: the one policy of every file
// a daemon job or MDI command reads (the program a load copies, each
// subroutine file its reading opens). A regular file, readable by the
// sender by its mode bits, inside the program folders when there are any.
struct FileAccess {
  std::uint32_t sender_uid = 0;
  std::uint32_t sender_gid = 0;
  // Canonical folders a file must lie in; empty: anywhere.
  std::vector<std::string> program_dirs;
};

// Whether `path` may be read for `access`: FileNotFound saying why not
// ("outside the program folders", "the sender (uid 65534) may not read
// it"), never what the file holds.
[[nodiscard]] Status may_read(const std::string& path, const FileAccess& access);

struct SnapshotRequest {
  std::string path;  // absolute, as the sender named it
  FileAccess access;
  bool hole_table = false;  // a .csv hole table, not G-code
  // Set by another thread: the copy ends at its next chunk, refused as
  // cancelled. Null: never.
  const std::atomic<bool>* cancel = nullptr;
};

class ProgramSnapshot {
 public:
  // Copies the file; FileNotFound (or GcodeSyntax for a file that is not a
  // program) with a message naming the path and what is allowed.
  [[nodiscard]] static Result<std::shared_ptr<const ProgramSnapshot>> take(const SnapshotRequest& r);
  // A program the daemon writes itself (an MDI command, framing), read like
  // a loaded one; `name` stands for it in messages ("MDI:1:7: …").
  [[nodiscard]] static Result<std::shared_ptr<const ProgramSnapshot>> from_text(std::string name,
                                                                                const std::string& text,
                                                                                FileAccess access);
  ~ProgramSnapshot();
  ProgramSnapshot(const ProgramSnapshot&) = delete;
  ProgramSnapshot& operator=(const ProgramSnapshot&) = delete;

  // The file as the sender named it: what messages say.
  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  // Where the copy reads from (/proc/self/fd/N).
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] std::uint64_t bytes() const noexcept { return bytes_; }
  // A diagnostic of the copy, told of the file it was taken from.
  [[nodiscard]] Diagnostic rename(Diagnostic d) const;
  // Whom it was loaded (or its text sent) for: every file its readings open
  // passes may_read() for them.
  [[nodiscard]] const FileAccess& access() const noexcept { return access_; }

 private:
  ProgramSnapshot(std::string name, int fd, std::uint64_t bytes, FileAccess access);
  std::string name_;
  FileAccess access_;
  std::string path_;
  int fd_ = -1;
  std::uint64_t bytes_ = 0;
};

// True if `head` (a file's first bytes) may be a program: no control bytes
// but tab, CR, LF, and for G-code a first non-blank line that begins with a
// word (a letter and a number), a comment, '%' or '/'; for a hole table a
// first line that begins with its header's "hole".
[[nodiscard]] bool looks_like_program(const std::string& head, bool hole_table);

}  // namespace lcnc::app
