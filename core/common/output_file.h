// The one door for output files (the CLI's trace, tables, pictures and
// programs, the HMI's exports): written so that nothing already stored is
// lost or half-written, and never over a file the work read.
//
// * An output is refused when it is one of the command's inputs or another
//   output of the same command: same file = same device and inode, so a
//   symbolic or hard link to the input is caught too; a target that does not
//   exist yet is identified by its directory's device and inode plus its name.
// * A regular target (or a new one) is written to a temporary file beside it,
//   `.NAME.XXXXXX.tmp`, and renamed over the target only by commit(): an
//   atomic replace. Until then the target is untouched; a run that is refused
//   or fails leaves it byte-identical (or absent), the destructor removes the
//   temporary file. A symbolic link as target is followed: the file it names
//   is replaced, the link stays. A replaced file keeps its permission bits; a
//   new one gets 0666 less the umask, as any file the shell creates.
// * "-" or /dev/stdout is this process's standard output, written through
//   it even when the shell redirected it to a regular file (renaming over
//   that would lose the output, or replace /dev/stdout itself).
// * A target that is not a regular file (/dev/…, /proc/…, a FIFO)
//   cannot be renamed over: it is opened and written directly, so what was
//   written before a failure stays written there (a stream cannot be
//   unwritten). Errors are still caught: every write, fflush and fclose is
//   checked, and commit() fails naming the file and the errno text.
#pragma once

#include <cstdio>
#include <functional>
#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "common/result.h"

namespace lcnc {

class OutputFile {
 public:
  // Opens `path` for writing (its temporary file, for a regular target);
  // OutputIsInput when it is the same file as one of `inputs` (inputs that
  // do not exist are skipped), OutputWrite when it cannot be created.
  [[nodiscard]] static Result<OutputFile> open(const std::string& path,
                                               const std::vector<std::string>& inputs);

  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&& other) noexcept;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  // Not committed: the temporary file is removed, the target untouched.
  ~OutputFile();

  // Appends; the first failure is kept (errno) and reported by commit().
  void write(std::string_view text);
  // printf-style, for row-by-row writers (the trace).
  void printf(const char* format, ...) __attribute__((format(printf, 2, 3)));
  // True once a write failed: a caller may stop producing early.
  [[nodiscard]] bool failed() const { return errno_ != 0; }

  // Flushes, syncs and closes; for a regular target renames the temporary
  // file over it. OutputWrite naming the file and the errno text on any
  // failure (then the temporary file is removed and the target untouched).
  [[nodiscard]] Status commit();

  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  OutputFile() = default;
  void discard() noexcept;
  void note_error() noexcept;

  std::string path_;    // as the user gave it (messages)
  std::string target_;  // the file replaced (symbolic links resolved)
  std::string temp_;    // the temporary file; empty: writing the target directly
  std::FILE* file_ = nullptr;
  int errno_ = 0;  // first write error
  bool has_mode_ = false;
  unsigned mode_ = 0;  // permission bits of the replaced file
};

// An std::ostream's buffer onto an OutputFile, for writers that take a
// stream (decompose::write_csv); errors land in the OutputFile.
class OutputStreamBuf : public std::streambuf {
 public:
  explicit OutputStreamBuf(OutputFile& f) : f_(f) {}

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    f_.write(std::string_view(s, static_cast<std::size_t>(n)));
    return n;
  }
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      const char ch = traits_type::to_char_type(c);
      f_.write(std::string_view(&ch, 1));
    }
    return traits_type::not_eof(c);
  }

 private:
  OutputFile& f_;
};

// Refuses a command's outputs when one is one of `inputs` or two are the same
// file (OutputIsInput, naming both). Empty paths are skipped (no such output).
// Nothing is created: this runs before any work.
[[nodiscard]] Status check_outputs(const std::vector<std::string>& outputs,
                                   const std::vector<std::string>& inputs);

// One output whole: opened as OutputFile::open (refused over any of
// `inputs`), written by `fill` through a stream, committed. On any failure
// the target is as it was.
[[nodiscard]] Status write_output(const std::string& path, const std::vector<std::string>& inputs,
                                  const std::function<void(std::ostream&)>& fill);

}  // namespace lcnc
