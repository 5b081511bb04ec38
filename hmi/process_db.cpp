#include "hmi/process_db.h"

#include <atomic>
#include <cmath>
#include <cstdio>

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QVariant>

#include "common/output_file.h"
#include "holes/hole_fields.h"
#include "holes/hole_table.h"

namespace lcnc::hmi {
namespace {

// Schema version 1: one column per field of the hole record, named,
// typed and range-checked from its table (holes/hole_fields.h), then the
// free shape and the measured focus offset. The CHECKs hold the ranges so
// that no path, not even raw SQL, stores a value out of range; validate()
// gives the operator the message first. A database made before a range was
// added here keeps its table as it was made (CREATE … IF NOT EXISTS) and
// loads unchanged; the write paths check every row with validate() anyway.
std::string column_definition(const HoleField& f) {
  const std::string c(f.column);
  std::string range =
      f.lo_open ? c + " > " + shortest_number_text(f.lo) + " AND " + c + " <= " + shortest_number_text(f.hi)
                : c + " BETWEEN " + shortest_number_text(f.lo) + " AND " + shortest_number_text(f.hi);
  if (f.scan_radius)  // a free shape does not use the scan radii
    range = "process = " + std::to_string(static_cast<int>(HoleProcessId::FreeShape)) + " OR (" + range + ")";
  std::string def = c + (f.type == HoleFieldType::Real ? " REAL" : " INTEGER") +
                    (&f == &kHoleFields.front() ? " PRIMARY KEY" : " NOT NULL") + " CHECK (" + range + ")";
  if (f.column == "total_depth_mm")
    def += " CHECK (abs(total_depth_mm - layer_count * layer_feed_mm) <= " +
           shortest_number_text(kDepthTolerance) + ")";
  return def;
}

std::string schema() {
  std::string s = "CREATE TABLE IF NOT EXISTS holes (\n";
  for (const HoleField& f : kHoleFields) s += "  " + column_definition(f) + ",\n";
  s += "  shape TEXT NOT NULL DEFAULT '',\n";
  s += "  focus_offset_mm REAL CHECK (focus_offset_mm IS NULL OR abs(focus_offset_mm) <= " +
       shortest_number_text(kMaxFocusOffsetMm) + ")\n)";
  return s;
}
constexpr int kSchemaVersion = 1;

// The columns in the order record_of() and insert() use them.
QString columns() {
  QString c;
  for (const HoleField& f : kHoleFields)
    c += QString::fromUtf8(f.column.data(), static_cast<int>(f.column.size())) + ", ";
  return c + "shape, focus_offset_mm";
}
constexpr int kShapeColumn = static_cast<int>(kHoleFields.size());
constexpr int kFocusColumn = kShapeColumn + 1;

std::atomic<int> g_connections{0};

Diagnostic sql_error(const std::string& what, const QSqlError& e, const std::string& path) {
  return make_error(ErrorCode::ProcessDbError, what + ": " + e.text().toStdString(), path);
}

std::string shape_text(const std::vector<PolarVertex>& shape) {
  std::string s;
  char b[64];
  for (std::size_t i = 0; i < shape.size(); ++i) {
    std::snprintf(b, sizeof b, "%s%.17g@%.17g", i ? ";" : "", shape[i].radius_mm, shape[i].angle_deg);
    s += b;
  }
  return s;
}

std::vector<PolarVertex> parse_shape(const std::string& s) {
  std::vector<PolarVertex> out;
  std::size_t pos = 0;
  while (pos < s.size()) {
    const std::size_t semi = s.find(';', pos);
    const std::string v = s.substr(pos, semi == std::string::npos ? std::string::npos : semi - pos);
    PolarVertex p;
    if (std::sscanf(v.c_str(), "%lf@%lf", &p.radius_mm, &p.angle_deg) == 2) out.push_back(p);
    if (semi == std::string::npos) break;
    pos = semi + 1;
  }
  return out;
}

HoleRecord record_of(const QSqlQuery& q) {
  HoleRecord r;
  HoleProcessParams& p = r.params;
  for (std::size_t i = 0; i < kHoleFields.size(); ++i)
    kHoleFields[i].set(p, q.value(static_cast<int>(i)).toDouble());
  p.shape = parse_shape(q.value(kShapeColumn).toString().toStdString());
  if (!q.value(kFocusColumn).isNull()) r.focus_offset_mm = q.value(kFocusColumn).toDouble();
  return r;
}

// Runs `body` in one transaction: committed when it succeeds, rolled back
// (nothing changed) when it fails.
template <typename F>
Status in_transaction(QSqlDatabase& db, const std::string& path, F body) {
  if (!db.transaction()) return sql_error("begin", db.lastError(), path);
  Status s = body();
  if (!s) {
    db.rollback();
    return s;
  }
  if (!db.commit()) {
    const Diagnostic d = sql_error("commit", db.lastError(), path);
    db.rollback();
    return d;
  }
  return {};
}

Status insert(QSqlDatabase& db, const HoleRecord& r, const std::string& path) {
  const HoleProcessParams& p = r.params;
  QSqlQuery q(db);
  QString marks;
  for (int i = 0; i < kFocusColumn; ++i) marks += "?,";
  q.prepare(QString("INSERT OR REPLACE INTO holes (%1) VALUES (%2?)").arg(columns(), marks));
  for (const HoleField& f : kHoleFields) {
    const double v = f.get(p);
    q.addBindValue(f.type == HoleFieldType::Real ? QVariant(v) : QVariant(static_cast<qlonglong>(v)));
  }
  q.addBindValue(QString::fromStdString(shape_text(p.shape)));
  q.addBindValue(r.focus_offset_mm ? QVariant(*r.focus_offset_mm) : QVariant(QVariant::Double));
  if (!q.exec()) return sql_error("hole " + std::to_string(p.hole_number) + ": store", q.lastError(), path);
  return {};
}

Status check_focus(std::uint32_t hole, double mm) {
  if (std::isfinite(mm) && std::abs(mm) <= kMaxFocusOffsetMm) return {};
  char b[160];
  std::snprintf(b, sizeof b, "hole %u: focus offset = %g mm; allowed -%g … %g mm", hole, mm,
                kMaxFocusOffsetMm, kMaxFocusOffsetMm);
  return make_error(ErrorCode::HoleTableBadValue, b);
}

Status check_record(const HoleRecord& r) {
  if (Status s = validate(r.params); !s) return make_error(ErrorCode::HoleTableBadValue, s.error().message);
  if (r.focus_offset_mm) return check_focus(r.params.hole_number, *r.focus_offset_mm);
  return {};
}

}  // namespace

ProcessDatabase::ProcessDatabase(std::string path, std::string connection)
    : path_(std::move(path)), connection_(std::move(connection)) {}

ProcessDatabase::~ProcessDatabase() {
  {
    QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_), false);
    if (db.isOpen()) db.close();
  }
  QSqlDatabase::removeDatabase(QString::fromStdString(connection_));
}

Result<std::unique_ptr<ProcessDatabase>> ProcessDatabase::open(const std::string& path) {
  const std::string conn = "lcnc_process_db_" + std::to_string(++g_connections);
  std::unique_ptr<ProcessDatabase> pdb(new ProcessDatabase(path, conn));
  QSqlDatabase db = QSqlDatabase::addDatabase("QSQLITE", QString::fromStdString(conn));
  if (!db.isValid())
    return make_error(ErrorCode::ProcessDbError, "the SQLite driver of QtSql (libqt5sql5-sqlite) is missing",
                      path);
  db.setDatabaseName(QString::fromStdString(path));
  db.setConnectOptions("QSQLITE_BUSY_TIMEOUT=5000");
  if (!db.open()) return sql_error("open", db.lastError(), path);
  QSqlQuery q(db);
  for (const char* pragma : {"PRAGMA journal_mode = WAL", "PRAGMA synchronous = FULL"})
    if (!q.exec(pragma)) return sql_error(pragma, q.lastError(), path);
  if (!q.exec("PRAGMA user_version") || !q.next())
    return sql_error("read the schema version", q.lastError(), path);
  const int version = q.value(0).toInt();
  if (version > kSchemaVersion)
    return make_error(ErrorCode::ProcessDbError,
                      "schema version " + std::to_string(version) + " is newer than this program's (" +
                          std::to_string(kSchemaVersion) + ")",
                      path);
  if (Status s = in_transaction(db, path,
                                [&]() -> Status {
                                  QSqlQuery t(db);
                                  if (!t.exec(QString::fromStdString(schema())))
                                    return sql_error("create the holes table", t.lastError(), path);
                                  if (!t.exec(QString("PRAGMA user_version = %1").arg(kSchemaVersion)))
                                    return sql_error("set the schema version", t.lastError(), path);
                                  return {};
                                });
      !s)
    return s.error();
  return pdb;
}

Result<std::vector<HoleRecord>> ProcessDatabase::holes() const {
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  QSqlQuery q(db);
  if (!q.exec(QString("SELECT %1 FROM holes ORDER BY hole").arg(columns())))
    return sql_error("read the holes", q.lastError(), path_);
  std::vector<HoleRecord> out;
  while (q.next()) out.push_back(record_of(q));
  return out;
}

Result<std::optional<HoleRecord>> ProcessDatabase::hole(std::uint32_t number) const {
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  QSqlQuery q(db);
  q.prepare(QString("SELECT %1 FROM holes WHERE hole = ?").arg(columns()));
  q.addBindValue(number);
  if (!q.exec()) return sql_error("read hole " + std::to_string(number), q.lastError(), path_);
  if (!q.next()) return std::optional<HoleRecord>();
  return std::optional<HoleRecord>(record_of(q));
}

Status ProcessDatabase::put(const HoleRecord& record) {
  if (Status s = check_record(record); !s) return s;
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  return in_transaction(db, path_, [&]() -> Status {
    HoleRecord r = record;
    if (!r.focus_offset_mm) {
      Result<std::optional<HoleRecord>> old = hole(r.params.hole_number);
      if (!old) return old.error();
      if (*old) r.focus_offset_mm = (*old)->focus_offset_mm;
    }
    return insert(db, r, path_);
  });
}

Status ProcessDatabase::remove(std::uint32_t number) {
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  return in_transaction(db, path_, [&]() -> Status {
    QSqlQuery q(db);
    q.prepare("DELETE FROM holes WHERE hole = ?");
    q.addBindValue(number);
    if (!q.exec()) return sql_error("remove hole " + std::to_string(number), q.lastError(), path_);
    if (q.numRowsAffected() != 1)
      return make_error(ErrorCode::ProcessDbError, "no hole " + std::to_string(number), path_);
    return {};
  });
}

Status ProcessDatabase::set_positions(const std::vector<std::pair<std::uint32_t, Pose>>& positions) {
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  return in_transaction(db, path_, [&]() -> Status {
    for (const auto& [number, pose] : positions) {
      Result<std::optional<HoleRecord>> old = hole(number);
      if (!old) return old.error();
      if (!*old) return make_error(ErrorCode::ProcessDbError, "no hole " + std::to_string(number), path_);
      HoleRecord r = **old;
      for (int i : {0, 1, 2, 3, 5}) r.params.position[i] = pose[i];
      if (Status s = check_record(r); !s) return s;
      if (Status s = insert(db, r, path_); !s) return s;
    }
    return {};
  });
}

Status ProcessDatabase::set_focus_offset(std::uint32_t number, double offset_mm) {
  return set_focus_offsets({{number, offset_mm}});
}

Status ProcessDatabase::set_focus_offsets(const std::vector<std::pair<std::uint32_t, double>>& offsets) {
  for (const auto& [number, offset] : offsets)
    if (Status s = check_focus(number, offset); !s) return s;
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  return in_transaction(db, path_, [&]() -> Status {
    for (const auto& [number, offset] : offsets) {
      QSqlQuery q(db);
      q.prepare("UPDATE holes SET focus_offset_mm = ? WHERE hole = ?");
      q.addBindValue(offset);
      q.addBindValue(number);
      if (!q.exec())
        return sql_error("hole " + std::to_string(number) + ": focus offset", q.lastError(), path_);
      if (q.numRowsAffected() != 1)
        return make_error(ErrorCode::ProcessDbError, "no hole " + std::to_string(number), path_);
    }
    return {};
  });
}

Status ProcessDatabase::import_csv(const std::string& path, ImportMode mode) {
  Result<std::vector<HoleProcessParams>> rows = read_hole_table(path);  // every row checked, line:col
  if (!rows) return rows.error();
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  return in_transaction(db, path_, [&]() -> Status {
    if (mode == ImportMode::Replace) {
      QSqlQuery q(db);
      if (!q.exec("DELETE FROM holes")) return sql_error("empty the table", q.lastError(), path_);
    }
    for (const HoleProcessParams& p : *rows) {
      HoleRecord r{p, std::nullopt};
      if (mode == ImportMode::Merge) {
        Result<std::optional<HoleRecord>> old = hole(p.hole_number);
        if (!old) return old.error();
        if (*old) r.focus_offset_mm = (*old)->focus_offset_mm;
      }
      if (Status s = insert(db, r, path_); !s) return s;
    }
    return {};
  });
}

Status ProcessDatabase::export_csv(const std::string& path) const {
  Result<std::vector<HoleRecord>> all = holes();
  if (!all) return all.error();
  std::vector<HoleProcessParams> rows;
  for (const HoleRecord& r : *all) rows.push_back(r.params);
  // never over the database itself
  return write_output(path, {path_}, [&](std::ostream& out) { out << write_hole_table(rows); });
}

Result<std::string> ProcessDatabase::integrity_check() const {
  QSqlDatabase db = QSqlDatabase::database(QString::fromStdString(connection_));
  QSqlQuery q(db);
  if (!q.exec("PRAGMA integrity_check")) return sql_error("integrity check", q.lastError(), path_);
  std::string out;
  while (q.next()) out += (out.empty() ? "" : "; ") + q.value(0).toString().toStdString();
  return out;
}

}  // namespace lcnc::hmi
