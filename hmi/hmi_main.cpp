// lasercnc-hmi — the operator HMI (Qt5 Widgets). Talks to lasercncd through
// shared memory only; keeps the process database in SQLite.
//
//   lasercnc-hmi [--db FILE] [--shm NAME] [--import HOLES.csv] [--dxf PART.dxf]
//                [--screenshot DIR]
//
// --import merges a hole table (holes/hole_table.h) into the database first.
// --dxf opens a part on the main + auxiliary axes screen and decomposes it.
// --screenshot renders every screen to DIR/<screen>.png and exits (works
// offscreen: QT_QPA_PLATFORM=offscreen). Exit codes: 0, 1 the database
// cannot be opened, 2 bad command line.
#include <QApplication>
#include <QStringList>

#include <cstdio>
#include <string>

#include "hmi/decomposition_page.h"
#include "hmi/main_window.h"
#include "hmi/process_db.h"
#include "rt/shm_interface.h"

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  std::string db_path = "lasercnc_process.db";
  std::string shm_name = lcnc::shm::kDefaultName;
  QString screenshot_dir;
  std::string import_path;
  QString dxf_path;
  const QStringList args = app.arguments();
  for (int i = 1; i < args.size(); ++i) {
    const QString& a = args[i];
    if ((a == "--db" || a == "--shm" || a == "--screenshot" || a == "--import" || a == "--dxf") &&
        i + 1 < args.size()) {
      const QString v = args[++i];
      if (a == "--db") db_path = v.toStdString();
      else if (a == "--shm") shm_name = v.toStdString();
      else if (a == "--import") import_path = v.toStdString();
      else if (a == "--dxf") dxf_path = v;
      else screenshot_dir = v;
    } else {
      std::fprintf(stderr, "usage: lasercnc-hmi [--db FILE] [--shm NAME] [--import HOLES.csv] "
                           "[--dxf PART.dxf] [--screenshot DIR]\n");
      return 2;
    }
  }
  auto db = lcnc::hmi::ProcessDatabase::open(db_path);
  if (!db) {
    std::fprintf(stderr, "lasercnc-hmi: %s\n", db.error().to_string().c_str());
    return 1;
  }
  if (!import_path.empty()) {
    if (lcnc::Status s = (*db)->import_csv(import_path, lcnc::hmi::ProcessDatabase::ImportMode::Merge); !s) {
      std::fprintf(stderr, "lasercnc-hmi: %s\n", s.error().to_string().c_str());
      return 1;
    }
  }
  lcnc::hmi::MainWindow window(**db, shm_name);
  if (!dxf_path.isEmpty()) {
    window.decomposition()->open_file(dxf_path);
    window.decomposition()->decompose();
    if (!screenshot_dir.isEmpty()) window.decomposition()->wait_done();
  }
  if (!screenshot_dir.isEmpty()) {
    for (const QString& f : window.screenshot_all(screenshot_dir)) std::printf("%s\n", f.toUtf8().constData());
    return 0;
  }
  window.show();
  return app.exec();
}
