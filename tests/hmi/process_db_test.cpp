// The process database on a real SQLite file through QtSql: round trips,
// every write path range-checked (and the schema's CHECKs behind it), all or
// nothing per call, CSV import/export, and no committed row lost when the
// writer is killed with SIGKILL mid-transaction.
#include "hmi/process_db.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>
#include <thread>

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>

#include "holes/hole_fields.h"
#include "holes/hole_table.h"

namespace lcnc::hmi {
namespace {

namespace fs = std::filesystem;

fs::path temp_db(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("lcnc_pdb_" + std::to_string(getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::create_directories(d);
  const fs::path p = d / name;
  for (const char* ext : {"", "-wal", "-shm"}) fs::remove(p.string() + ext);
  return p;
}

HoleRecord row(std::uint32_t n, double x = 100.0) {
  HoleRecord r;
  HoleProcessParams& p = r.params;
  p.hole_number = n;
  p.position << x, 50.0, 20.0, -10.0, 0.0, 45.0;
  p.feed_mm_min = 600.0;
  p.layer_feed_mm = 0.1;
  p.layer_count = 10;
  p.total_depth_mm = 1.0;
  p.power_pct = 80.0;
  p.head.start_radius_mm = 0.5;
  p.head.end_radius_mm = 0.3;
  p.head.radius_turns = 1;
  p.head.scan_speed_mm_s = 200.0;
  p.head.wedge_speed_rpm = 3000.0;
  return r;
}

std::unique_ptr<ProcessDatabase> open_db(const fs::path& p) {
  Result<std::unique_ptr<ProcessDatabase>> db = ProcessDatabase::open(p.string());
  EXPECT_TRUE(static_cast<bool>(db)) << db.error().to_string();
  return db ? std::move(db).value() : nullptr;
}

std::size_t count(const ProcessDatabase& db) {
  Result<std::vector<HoleRecord>> all = db.holes();
  EXPECT_TRUE(static_cast<bool>(all));
  return all ? all->size() : 0;
}

// Runs `body` with a query on a second, raw connection to the file at `p`
// (what a SQL tool would do, past the ProcessDatabase).
template <typename F>
void with_raw_sql(const fs::path& p, F body) {
  {
    QSqlDatabase raw = QSqlDatabase::addDatabase("QSQLITE", "raw");
    raw.setDatabaseName(QString::fromStdString(p.string()));
    ASSERT_TRUE(raw.open());
    QSqlQuery q(raw);
    body(q);
    raw.close();
  }
  QSqlDatabase::removeDatabase("raw");
}

TEST(ProcessDatabase, StoresAndReadsBackEveryField) {
  const fs::path p = temp_db("a.db");
  {
    auto db = open_db(p);
    HoleRecord free = row(3);
    free.params.process = HoleProcessId::FreeShape;
    free.params.shape = {{0.8, 0.0}, {0.5, 120.0}, {0.8, 240.0}};
    ASSERT_TRUE(db->put(row(9, 123.456)).ok());
    ASSERT_TRUE(db->put(free).ok());
    ASSERT_TRUE(db->set_focus_offset(9, -0.125).ok());
  }
  auto db = open_db(p);  // a new connection reads what was committed
  Result<std::vector<HoleRecord>> all = db->holes();
  ASSERT_TRUE(static_cast<bool>(all));
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].params.hole_number, 3u);  // by hole number
  EXPECT_EQ((*all)[0].params.shape.size(), 3u);
  EXPECT_EQ((*all)[0].params.shape[1].angle_deg, 120.0);
  EXPECT_FALSE((*all)[0].focus_offset_mm.has_value());
  const HoleRecord& h = (*all)[1];
  EXPECT_EQ(h.params.position, row(9, 123.456).params.position);
  EXPECT_EQ(h.params.head.end_radius_mm, 0.3);
  EXPECT_EQ(h.params.total_depth_mm, 1.0);
  ASSERT_TRUE(h.focus_offset_mm.has_value());
  EXPECT_EQ(*h.focus_offset_mm, -0.125);
  // an edit keeps the measured focus offset
  HoleRecord edit = row(9, 200.0);
  ASSERT_TRUE(db->put(edit).ok());
  EXPECT_EQ(*(*db->hole(9))->focus_offset_mm, -0.125);
  EXPECT_EQ((*db->hole(9))->params.position[0], 200.0);
  EXPECT_EQ(*db->integrity_check(), "ok");
}

TEST(ProcessDatabase, EveryWritePathRefusesOutOfRangeAndStoresNothing) {
  auto db = open_db(temp_db("b.db"));
  ASSERT_TRUE(db->put(row(1)).ok());
  HoleRecord bad = row(2);
  bad.params.position[3] = 120.0;  // A
  Status s = db->put(bad);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::HoleTableBadValue);
  EXPECT_NE(s.error().message.find("hole 2: field 5 A = 120"), std::string::npos) << s.error().message;
  EXPECT_EQ(count(*db), 1u);
  // the 3D measurement: one position out of the travel → none written
  Pose in = row(1).params.position, out = in;
  out[0] = 1200.0;
  ASSERT_TRUE(db->put(row(2)).ok());
  in[0] = 300.0;
  s = db->set_positions({{1, in}, {2, out}});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("field 2 X = 1200"), std::string::npos) << s.error().message;
  EXPECT_EQ((*db->hole(1))->params.position[0], 100.0);  // the good one was not written either
  EXPECT_TRUE(db->set_positions({{1, in}}).ok());
  EXPECT_EQ((*db->hole(1))->params.position[0], 300.0);
  EXPECT_FALSE(db->set_positions({{77, in}}).ok());  // no such hole
  // focus offsets
  EXPECT_FALSE(db->set_focus_offset(1, 80.0).ok());
  EXPECT_FALSE(db->set_focus_offset(1, std::nan("")).ok());
  EXPECT_FALSE(db->set_focus_offset(55, 0.1).ok());
  EXPECT_FALSE((*db->hole(1))->focus_offset_mm.has_value());
  EXPECT_FALSE(db->remove(55).ok());
  EXPECT_TRUE(db->remove(2).ok());
  EXPECT_EQ(count(*db), 1u);
}

TEST(ProcessDatabase, TheSchemaRefusesOutOfRangeEvenFromRawSql) {
  const fs::path p = temp_db("c.db");
  auto db = open_db(p);
  with_raw_sql(p, [](QSqlQuery& q) {
    EXPECT_FALSE(
        q.exec("INSERT INTO holes (hole, x_mm, y_mm, z_mm, a_deg, c_deg, feed_mm_min, "
               "layer_feed_mm, layer_count, total_depth_mm, power_pct, start_radius_mm, "
               "end_radius_mm, radius_turns, scan_speed_mm_s, wedge_speed_rpm, beam_offset_mm, "
               "process) VALUES (5, 100, 50, 20, 0, 0, 600, 0.1, 10, 2.0, 80, 0.5, 0.5, 1, 200, "
               "3000, 0, 0)"));  // depth ≠ layers × layer feed
    EXPECT_FALSE(
        q.exec("INSERT INTO holes (hole, x_mm, y_mm, z_mm, a_deg, c_deg, feed_mm_min, "
               "layer_feed_mm, layer_count, total_depth_mm, power_pct, start_radius_mm, "
               "end_radius_mm, radius_turns, scan_speed_mm_s, wedge_speed_rpm, beam_offset_mm, "
               "process) VALUES (5, 100, 50, 20, 0, 0, 600, 0.1, 10, 1.0, 130, 0.5, 0.5, 1, 200, "
               "3000, 0, 0)"));  // power 130 %
  });
  EXPECT_EQ(count(*db), 0u);
}

// Every field just past either end of its range (holes/hole_fields.h) is
// refused by put() with a message naming the field, and the hole stored
// before — every field and its focus offset — reads back unchanged.
TEST(ProcessDatabase, RefusesEachFieldOutOfRangeNamingItAndLosesNothing) {
  const fs::path p = temp_db("f.db");
  auto db = open_db(p);
  HoleRecord stored = row(1);
  stored.params.head.beam_offset_mm = 1.5;
  ASSERT_TRUE(db->put(stored).ok());
  ASSERT_TRUE(db->set_focus_offset(1, 0.25).ok());
  for (const HoleField& f : kHoleFields) {
    for (const double v : {f.lo - 1, f.hi + 1}) {
      if (f.type != HoleFieldType::Real && v < 0) continue;  // a count cannot hold it
      HoleRecord bad = stored;
      f.set(bad.params, v);
      const Status s = db->put(bad);
      ASSERT_FALSE(s.ok()) << f.column << " = " << v << " was stored";
      EXPECT_EQ(s.error().code, ErrorCode::HoleTableBadValue);
      const std::string want = "field " + std::to_string(f.number) + " " + std::string(f.label) + " = ";
      EXPECT_NE(s.error().message.find(want), std::string::npos) << s.error().message;
    }
  }
  HoleRecord beyond_head = stored;
  beyond_head.params.head.beam_offset_mm = 10.0;  // within the old ±50 mm, beyond the head's ±2 mm
  const Status s = db->put(beyond_head);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("hole 1: field 17 beam offset = 10 mm; allowed -2 … 2 mm"),
            std::string::npos)
      << s.error().message;
  auto again = open_db(p);  // what is committed, through a new connection
  Result<std::vector<HoleRecord>> all = again->holes();
  ASSERT_TRUE(static_cast<bool>(all));
  ASSERT_EQ(all->size(), 1u);
  for (const HoleField& f : kHoleFields) EXPECT_EQ(f.get((*all)[0].params), f.get(stored.params)) << f.column;
  EXPECT_EQ((*all)[0].focus_offset_mm, std::optional<double>(0.25));
}

// The schema's CHECKs come from the same table: a beam offset beyond the
// head is refused even from raw SQL, and the ends of the range are taken.
TEST(ProcessDatabase, TheSchemaTakesItsRangesFromTheFieldTable) {
  const fs::path p = temp_db("g.db");
  auto db = open_db(p);
  with_raw_sql(p, [](QSqlQuery& q) {
    const QString insert =
        "INSERT INTO holes (hole, x_mm, y_mm, z_mm, a_deg, c_deg, feed_mm_min, layer_feed_mm, "
        "layer_count, total_depth_mm, power_pct, start_radius_mm, end_radius_mm, radius_turns, "
        "scan_speed_mm_s, wedge_speed_rpm, beam_offset_mm, process) VALUES (%1, 100, 50, 20, 0, 0, "
        "600, 0.1, 10, 1.0, 80, 0.5, 0.5, 1, 200, 3000, %2, 0)";
    EXPECT_FALSE(q.exec(insert.arg(5).arg(2.5)));
    EXPECT_FALSE(q.exec(insert.arg(5).arg(-3)));
    EXPECT_TRUE(q.exec(insert.arg(6).arg(-2))) << q.lastError().text().toStdString();
  });
  EXPECT_EQ(count(*db), 1u);
}

// A database made by the first release of schema 1 (its CHECKs written out
// by hand, no range on the beam offset) opens, reads back every field and
// takes new rows: the column names and order are unchanged.
TEST(ProcessDatabase, ADatabaseOfTheFirstSchemaStillLoads) {
  const fs::path p = temp_db("old.db");
  with_raw_sql(p, [](QSqlQuery& q) {
    ASSERT_TRUE(q.exec(R"(
CREATE TABLE holes (
  hole            INTEGER PRIMARY KEY CHECK (hole BETWEEN 1 AND 10000),
  x_mm            REAL NOT NULL CHECK (x_mm BETWEEN 0 AND 1000),
  y_mm            REAL NOT NULL CHECK (y_mm BETWEEN 0 AND 450),
  z_mm            REAL NOT NULL CHECK (z_mm BETWEEN 0 AND 500),
  a_deg           REAL NOT NULL CHECK (a_deg BETWEEN -95 AND 95),
  c_deg           REAL NOT NULL CHECK (c_deg >= 0 AND c_deg <= 359.999),
  feed_mm_min     REAL NOT NULL CHECK (feed_mm_min > 0 AND feed_mm_min <= 2000),
  layer_feed_mm   REAL NOT NULL CHECK (layer_feed_mm > 0 AND layer_feed_mm <= 1),
  layer_count     INTEGER NOT NULL CHECK (layer_count BETWEEN 1 AND 10000),
  total_depth_mm  REAL NOT NULL CHECK (abs(total_depth_mm - layer_count * layer_feed_mm) <= 0.001),
  power_pct       REAL NOT NULL CHECK (power_pct BETWEEN 0 AND 100),
  start_radius_mm REAL NOT NULL CHECK (start_radius_mm BETWEEN 0 AND 50),
  end_radius_mm   REAL NOT NULL CHECK (end_radius_mm BETWEEN 0 AND 50),
  radius_turns    INTEGER NOT NULL CHECK (radius_turns BETWEEN 1 AND 1000),
  scan_speed_mm_s REAL NOT NULL CHECK (scan_speed_mm_s >= 0),
  wedge_speed_rpm REAL NOT NULL CHECK (wedge_speed_rpm >= 0),
  beam_offset_mm  REAL NOT NULL,
  process         INTEGER NOT NULL CHECK (process IN (0, 1, 2)),
  shape           TEXT NOT NULL DEFAULT '',
  focus_offset_mm REAL CHECK (focus_offset_mm IS NULL OR abs(focus_offset_mm) <= 50)
))")) << q.lastError().text().toStdString();
    ASSERT_TRUE(q.exec("PRAGMA user_version = 1"));
    ASSERT_TRUE(
        q.exec("INSERT INTO holes VALUES (4, 123.5, 50, 20, -10, 45, 600, 0.1, 10, 1.0, 80, "
               "0.5, 0.3, 1, 200, 3000, 0.125, 0, '', -0.5)"));
    ASSERT_TRUE(
        q.exec("INSERT INTO holes VALUES (7, 100, 50, 20, 0, 0, 300, 0.1, 5, 0.5, 90, 0.5, 0.5, "
               "1, 100, 3000, 0, 2, '0.8@0;0.5@120;0.8@240', NULL)"));
  });
  auto db = open_db(p);
  ASSERT_NE(db, nullptr);
  Result<std::vector<HoleRecord>> all = db->holes();
  ASSERT_TRUE(static_cast<bool>(all)) << all.error().to_string();
  ASSERT_EQ(all->size(), 2u);
  const HoleProcessParams& h = (*all)[0].params;
  EXPECT_EQ(h.hole_number, 4u);
  EXPECT_EQ(h.position[0], 123.5);
  EXPECT_EQ(h.position[3], -10.0);
  EXPECT_EQ(h.position[5], 45.0);
  EXPECT_EQ(h.layer_count, 10u);
  EXPECT_EQ(h.head.end_radius_mm, 0.3);
  EXPECT_EQ(h.head.beam_offset_mm, 0.125);
  EXPECT_EQ((*all)[0].focus_offset_mm, std::optional<double>(-0.5));
  EXPECT_TRUE(validate(h).ok());
  EXPECT_EQ((*all)[1].params.process, HoleProcessId::FreeShape);
  EXPECT_EQ((*all)[1].params.shape.size(), 3u);
  EXPECT_TRUE(db->put(row(9)).ok());
  EXPECT_EQ(count(*db), 3u);
  EXPECT_EQ(*db->integrity_check(), "ok");
}

TEST(ProcessDatabase, CsvImportIsAllOrNothingAndExportReadsBack) {
  const fs::path p = temp_db("d.db");
  auto db = open_db(p);
  ASSERT_TRUE(db->put(row(1)).ok());
  ASSERT_TRUE(db->set_focus_offset(1, 0.2).ok());
  const fs::path dir = p.parent_path();
  // a table whose third row is bad: nothing of it is stored
  std::string good = write_hole_table({row(1, 110).params, row(2).params});
  const std::string bad_text = good + "3,100,50,20,0,0,600,0.1,10,1,80,0.5,0.5,1,200,3000,0,spiral,\n";
  std::ofstream(dir / "bad.csv") << bad_text;
  Status s = db->import_csv((dir / "bad.csv").string(), ProcessDatabase::ImportMode::Replace);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().to_string().find("bad.csv:4:"), std::string::npos) << s.error().to_string();
  EXPECT_EQ(count(*db), 1u);
  EXPECT_EQ((*db->hole(1))->params.position[0], 100.0);
  // merge keeps hole 1's focus offset, adds hole 2
  std::ofstream(dir / "good.csv") << good;
  ASSERT_TRUE(db->import_csv((dir / "good.csv").string(), ProcessDatabase::ImportMode::Merge).ok());
  EXPECT_EQ(count(*db), 2u);
  EXPECT_EQ((*db->hole(1))->params.position[0], 110.0);
  EXPECT_EQ(*(*db->hole(1))->focus_offset_mm, 0.2);
  // export, then replace from it: the same rows
  ASSERT_TRUE(db->export_csv((dir / "out.csv").string()).ok());
  for (const fs::directory_entry& e : fs::directory_iterator(dir))  // no temporary file left
    EXPECT_NE(e.path().filename().string().rfind(".out.csv.", 0), 0u) << e.path();
  // an export over the database itself (or a link to it) is refused, the
  // database unchanged
  const fs::path db_link = dir / "db_link.csv";
  fs::create_symlink(db->path(), db_link);
  for (const std::string& over : {db->path(), db_link.string()}) {
    const Status refused = db->export_csv(over);
    ASSERT_FALSE(refused.ok()) << over;
    EXPECT_EQ(refused.error().code, ErrorCode::OutputIsInput) << refused.error().to_string();
  }
  EXPECT_EQ(count(*db), 2u);
  ASSERT_TRUE(db->import_csv((dir / "out.csv").string(), ProcessDatabase::ImportMode::Replace).ok());
  Result<std::vector<HoleRecord>> all = db->holes();
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].params.position, row(1, 110).params.position);
  EXPECT_FALSE((*all)[0].focus_offset_mm.has_value());  // Replace: measured offsets start afresh
}

// A writer process commits hole after hole (and, between them, a big import
// in one transaction) and is killed with SIGKILL at a random moment: every
// hole it reported committed is there, the import is there whole or not at
// all, and SQLite finds nothing wrong. Runs kKills times.
// LCNC_SOAK_KILLS=1000 makes it the soak of RELIABILITY.md (8 by default).
TEST(ProcessDatabase, KilledWriterLosesNoCommittedRowAndCorruptsNothing) {
  const char* soak = std::getenv("LCNC_SOAK_KILLS");
  const int kKills = soak != nullptr ? std::max(1, std::atoi(soak)) : 8;
  const fs::path p = temp_db("e.db");
  const fs::path table = p.parent_path() / "big.csv";
  {
    std::vector<HoleProcessParams> big;
    for (std::uint32_t n = 5001; n <= 7000; ++n) big.push_back(row(n).params);
    std::ofstream(table) << write_hole_table(big);
  }
  std::mt19937 rng(17);
  std::size_t committed_total = 0, kills_mid_job = 0;
  for (int k = 0; k < kKills; ++k) {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(fds[0]);
      auto db = ProcessDatabase::open(p.string());
      if (!db) _exit(2);
      const auto first = static_cast<std::uint32_t>(1 + (500 * k) % 4500);  // hole numbers 1 … 5000
      for (std::uint32_t n = first; n < first + 500; ++n) {
        if ((*db)->put(row(n)).ok()) {
          const std::uint32_t done = n;
          if (write(fds[1], &done, sizeof done) != sizeof done) _exit(3);
        }
        if (n % 50 == 0) (void)(*db)->import_csv(table.string(), ProcessDatabase::ImportMode::Merge);
      }
      _exit(0);
    }
    close(fds[1]);
    std::this_thread::sleep_for(std::chrono::milliseconds(20 + rng() % 200));
    kill(child, SIGKILL);
    std::set<std::uint32_t> committed;
    std::uint32_t n = 0;
    while (read(fds[0], &n, sizeof n) == sizeof n) committed.insert(n);
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    auto db = open_db(p);
    ASSERT_TRUE(db);
    Result<std::string> ok = db->integrity_check();
    ASSERT_TRUE(static_cast<bool>(ok));
    EXPECT_EQ(*ok, "ok") << "kill " << k;
    Result<std::vector<HoleRecord>> all = db->holes();
    ASSERT_TRUE(static_cast<bool>(all));
    std::set<std::uint32_t> present;
    std::size_t imported = 0;
    for (const HoleRecord& r : *all) {
      present.insert(r.params.hole_number);
      if (r.params.hole_number > 5000) ++imported;
    }
    for (std::uint32_t c : committed) EXPECT_TRUE(present.count(c)) << "hole " << c << " lost, kill " << k;
    committed_total += committed.size();
    if (WIFSIGNALED(status)) ++kills_mid_job;  // not already done by itself
    EXPECT_TRUE(imported == 0 || imported == 2000) << imported << " of the import's rows, kill " << k;
  }
  // the kills came while the writer was writing, after it had committed some
  EXPECT_GT(committed_total, 0u);
  EXPECT_EQ(kills_mid_job, static_cast<std::size_t>(kKills));
  std::printf("killed %d writers mid-job; %zu rows they had committed, all present\n", kKills,
              committed_total);
}

}  // namespace
}  // namespace lcnc::hmi
