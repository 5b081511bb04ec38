// The process database (docs/design.md §6, Shao (2022) Table 1): one row per hole with
// fields 1–18 and the focus offset the focal-length workflow measures,
// SQLite through QtSql. Widget-free: the HMI's screens and the tests use the
// same object.
//
// Safety. Every write path — an edit, an import, a measurement — goes
// through validate() of the hole processes (hole_processes.h) before SQL
// sees it, and the table's columns and CHECK constraints are made from the
// hole record's field table (holes/hole_fields.h), so not even a raw SQL
// edit stores a value out of range. Each call is one
// transaction: it is applied whole or not at all. The journal is WAL with
// synchronous = FULL, so a committed row survives the process being killed
// (SIGKILL) or the machine losing power; an import that fails on any line
// leaves the table as it was. Export writes a temporary file and renames it
// over the target, so a crash never leaves half a CSV.
//
// One object per connection; not for use from two threads at once (QtSql
// connections are per thread). Errors name the hole and field (validation),
// the file:line:col (import), or what SQLite said.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/result.h"
#include "holes/hole_processes.h"

namespace lcnc::hmi {

struct HoleRecord {
  HoleProcessParams params;
  std::optional<double> focus_offset_mm;  // measured by the focal-length workflow
};

// The focus offset's range, mm (the displacement sensor's reach).
inline constexpr double kMaxFocusOffsetMm = 50.0;

class ProcessDatabase {
 public:
  // Opens (creating the file and schema if needed) the database at `path`.
  [[nodiscard]] static Result<std::unique_ptr<ProcessDatabase>> open(const std::string& path);
  ~ProcessDatabase();
  ProcessDatabase(const ProcessDatabase&) = delete;
  ProcessDatabase& operator=(const ProcessDatabase&) = delete;

  // Every hole, by hole number.
  [[nodiscard]] Result<std::vector<HoleRecord>> holes() const;
  [[nodiscard]] Result<std::optional<HoleRecord>> hole(std::uint32_t number) const;
  // Inserts or replaces the hole of params.hole_number (its focus offset is
  // kept when it had one and `record` has none).
  [[nodiscard]] Status put(const HoleRecord& record);
  [[nodiscard]] Status remove(std::uint32_t number);
  // The 3D-measurement workflow: X Y Z A C of many holes at once, all or none.
  [[nodiscard]] Status set_positions(const std::vector<std::pair<std::uint32_t, Pose>>& positions);
  // The focal-length workflow: the measured focus offset of a hole, or of
  // many at once (all or none).
  [[nodiscard]] Status set_focus_offset(std::uint32_t number, double offset_mm);
  [[nodiscard]] Status set_focus_offsets(const std::vector<std::pair<std::uint32_t, double>>& offsets);

  enum class ImportMode : std::uint8_t { Replace, Merge };
  // A hole table (holes/hole_table.h): Replace empties the table first,
  // Merge puts each row over the hole of its number. All or nothing.
  [[nodiscard]] Status import_csv(const std::string& path, ImportMode mode);
  [[nodiscard]] Status export_csv(const std::string& path) const;

  // SQLite's PRAGMA integrity_check: "ok", or what is wrong.
  [[nodiscard]] Result<std::string> integrity_check() const;
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  explicit ProcessDatabase(std::string path, std::string connection);
  struct Impl;
  std::string path_;
  std::string connection_;
};

}  // namespace lcnc::hmi
