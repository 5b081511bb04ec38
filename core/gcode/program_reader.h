// The G-code front end: RS274NGC as LinuxCNC reads it, for a subset:
//   motion   G0 G1 G2 G3 (helices, P turns) G4, canned cycles G73 G81 G82
//            G83 G85 G86 G89 with G98 G99 and G80, polar @ ^
//   modes    G17-19, G20/21, G90/91, G90.1/91.1, G93/94, G61 G61.1 G64 P Q,
//            G54-59.3, G10 L1 L2 L10 L11 L20, G28 G30 G52 G53 G92, tools T M6
//            M61 G43 G49, cutter compensation G40 G41 G42 G41.1 G42.1
//   machine  M3 M4 M5 (the laser; S its power), M7 M8 M9 (assist gas), M0
//            M1 M60 (a pause until resumed), M48-M53 (override, adaptive
//            feed and feed-hold switches), M62-M65 and M67 M68 (digital and
//            analog outputs with the next move or at once), M66 (wait on an
//            input), M70-M73 (modal state save and restore), M2 M30
//   words    X Y Z A B C, F S, N numbers, comments, '/' block delete,
//            parameters and expressions, O-word subroutines and control flow
// Streams: one Segment at a time, so a program of millions of lines runs in
// bounded memory. check_program() reads a whole program once before motion
// starts, so an error on line 10,000 never stops a part half-cut. An
// unsupported word is an error at its file:line:col, never skipped.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <istream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/result.h"
#include "geom/pose.h"
#include "machine/machine_config.h"
#include "path/motion_summary.h"
#include "path/segment.h"

namespace lcnc {

struct ReaderOptions {
  Pose start = Pose::Zero();  // machine position when the program starts
  // '/' lines skipped (true) or run (false); unset: the machine's
  // block_delete (skipped by default, as LinuxCNC does)
  std::optional<bool> block_delete;
  // The folder searched first for a subroutine's file <name>.ngc: unset, the
  // program file's own (a program read from memory has none); set it when
  // the program is read from a copy; empty: none, machine.subroutine_path
  // alone (an MDI command's).
  std::optional<std::string> program_dir;
  // Every subroutine file the reading would open is asked here first (the
  // daemon's: inside the program folders, readable by the sender); a refusal
  // is the reading's error at the call, and the file is not read. Unset:
  // any file the process may read.
  std::function<Status(const std::string& path)> file_policy;
  // Set by another thread, the reading ends at its next line with
  // GcodeCancelled (the daemon's load check, cancelled by stop, reset or
  // shutdown). Null: never.
  const std::atomic<bool>* cancel = nullptr;
  // The job's own reading (not a check): at the program's end the offsets
  // and tools it set are written to the machine's parameter_file.
  bool keep_parameters = false;
  // Modes carried in from an earlier reading (an MDI command goes on in the
  // modes the one before it left: ProgramSummary::end.modes), run after the
  // machine's startup code as if line 0. Modal codes, F and S only.
  std::string modes;
  // Run from line N (0: from the start). Every block before the first move
  // of a line >= N is read — modes, offsets, tool, laser power and feed are
  // as they would be there — but its moves are not made; then a safe
  // approach, at rapid with the beam off, goes from `start` to where that
  // move begins: up to the higher of the two Z's, across, then down.
  std::uint32_t start_line = 0;
  // Single block: the machine stops (a pause, as M0) after the moves of
  // each block, until the operator resumes.
  bool single_block = false;
  // Dry run: every move as programmed with the beam off (power 0).
  bool laser_off = false;
};

// Where a reading left its modes and offsets.
struct ReaderModes {
  std::string block;            // the modes as one block (ReaderOptions::modes of the next)
  Pose offsets = Pose::Zero();  // machine = program + offsets (mm, deg)
  int coord_system = 0;         // 0 = G54 … 8 = G59.3
  bool inch = false;            // G20
};

class ProgramReader {
 public:
  enum class Next : std::uint8_t { Segment, End, Error };

  // Opens a program file. FileNotFound when it cannot be read.
  [[nodiscard]] static Result<std::unique_ptr<ProgramReader>> open(const std::string& path,
                                                                   const MachineConfig& machine,
                                                                   const ReaderOptions& options = {});
  // Reads a program held in memory; `name` stands for the file in diagnostics.
  [[nodiscard]] static std::unique_ptr<ProgramReader> from_string(std::string text, std::string name,
                                                                  const MachineConfig& machine,
                                                                  const ReaderOptions& options = {});

  ~ProgramReader();
  ProgramReader(const ProgramReader&) = delete;
  ProgramReader& operator=(const ProgramReader&) = delete;

  // The next motion segment (Rapid, Linear, Arc or Dwell). Blocks without
  // motion (S, M3, F, modal codes, comments) only change state carried by the
  // following segments: they never produce a segment. After End or Error,
  // every further call returns the same.
  [[nodiscard]] Next next(Segment& out);

  [[nodiscard]] const Diagnostic& error() const;                  // valid after Next::Error
  [[nodiscard]] const std::vector<Diagnostic>& warnings() const;  // e.g. lines after M2
  [[nodiscard]] std::uint32_t lines_read() const;
  // The modes and offsets as the blocks read so far left them.
  [[nodiscard]] ReaderModes modes() const;
  // The files this reading has read so far: the program (unless read from
  // memory), each subroutine file a call opened, the machine's parameter
  // file. What a run reads, none of its outputs may be.
  [[nodiscard]] std::vector<std::string> files_read() const;

  struct Impl;

 private:
  explicit ProgramReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// A program's motion summed (path/motion_summary.h), and the modes and
// offsets at its end.
struct ProgramSummary : MotionSummary {
  ProgramSummary() = default;
  explicit ProgramSummary(MotionSummary motion) : MotionSummary(std::move(motion)) {}
  ReaderModes end;
  std::vector<std::string> files;  // ProgramReader::files_read() at the end
};

// Reads the whole program, checking syntax, modal conflicts, arcs, feeds and
// travel. The first error is returned; nothing is run.
[[nodiscard]] Result<ProgramSummary> check_program(const std::string& path, const MachineConfig& machine,
                                                   const ReaderOptions& options = {});

}  // namespace lcnc
