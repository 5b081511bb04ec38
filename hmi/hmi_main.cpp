// lasercnc-hmi — the operator HMI (Qt5 Widgets). Talks to lasercncd through
// shared memory only; keeps the process database in SQLite.
//
//   lasercnc-hmi [--db FILE] [--shm NAME] [--import HOLES.csv] [--program FILE] [--dxf PART.dxf]
//                [--cut PART.dxf]
//                [--sensor|--laser|--meter|--head tcp:HOST:PORT|rtu:DEV[:BAUD[:PARITY]]]
//                [--probe SERIAL] [--machine FILE] [--lang en|zh_CN|ru]
//                [--screenshot DIR]
//
// Without any of --sensor, --laser, --meter, --head the peripherals are the
// simulators (hmi/sim_peripherals.h), started in-process and riding on the
// machine of --shm; --probe is the 3D probe's serial device (its RS-232 line
// protocol). --lang: the operator's language (default: the system's, English
// when there is no translation for it).
// --db: the process database (SQLite); default
// $XDG_DATA_HOME/lasercnc/process.db, i.e. ~/.local/share/lasercnc/process.db.
// --import merges a hole table (holes/hole_table.h) into the database first.
// --program opens and plans a program on the program screen; --dxf opens a
// part on the main + auxiliary axes screen and decomposes it; --cut opens a
// part on the laser cutting screen and plans its cut.
// --screenshot renders every screen to DIR/<screen>.png and exits (works
// offscreen: QT_QPA_PLATFORM=offscreen). Exit codes: 0, 1 the database
// cannot be opened, 2 bad command line.
#include <QApplication>
#include <QDir>
#include <QStandardPaths>
#include <QStringList>

#include <cstdio>
#include <memory>
#include <string>
#include <tuple>

#include "drivers/modbus/endpoint_spec.h"
#include "hmi/adjust_page.h"
#include "hmi/cut_page.h"
#include "hmi/decomposition_page.h"
#include "hmi/hmi_font.h"
#include "hmi/main_window.h"
#include "hmi/process_db.h"
#include "hmi/program_page.h"
#include "hmi/sim_peripherals.h"
#include "hmi/translations.h"
#include "rt/shm_interface.h"

namespace {

constexpr const char* kUsage =
    "usage: lasercnc-hmi [--db FILE] [--shm NAME] [--import HOLES.csv] [--program FILE] [--dxf PART.dxf]\n"
    "                    [--cut PART.dxf]\n"
    "                    [--sensor|--laser|--meter|--head ENDPOINT] [--probe SERIAL]\n"
    "                    [--machine FILE] [--lang en|zh_CN|ru] [--screenshot DIR]\n";

constexpr const char* kHelp =
    "The operator HMI of LaserCNC: machine, program, laser cutting, process database,\n"
    "3D measurement, focal length, laser and head, main + auxiliary axes. Talks to\n"
    "lasercncd through shared memory.\n"
    "  --db FILE          the process database (SQLite); default\n"
    "                     $XDG_DATA_HOME/lasercnc/process.db (~/.local/share/lasercnc/process.db)\n"
    "  --shm NAME         the daemon's shared-memory segment (default /lasercnc)\n"
    "  --import HOLES.csv merge a hole table into the database first\n"
    "  --program FILE     open and plan a program on the program screen\n"
    "  --dxf PART.dxf     open a part on the main + auxiliary axes screen and decompose it\n"
    "  --cut PART.dxf     open a part on the laser cutting screen and plan its cut\n"
    "  --sensor, --laser, --meter, --head ENDPOINT\n"
    "                     a real peripheral: tcp:HOST:PORT or rtu:DEV[:BAUD[:PARITY]];\n"
    "                     without any of them the peripherals are simulators\n"
    "  --probe SERIAL     the 3D probe's serial device\n"
    "  --machine FILE     the machine configuration (default: the shipped one)\n"
    "  --lang LANG        en, zh_CN or ru (default: the system's)\n"
    "  --screenshot DIR   render every screen to DIR/<screen>.png and exit\n"
    "                     (works without a display: QT_QPA_PLATFORM=offscreen)\n"
    "Exit codes: 0 done, 1 the database or a peripheral cannot be opened, 2 bad command line.\n";

}  // namespace

int main(int argc, char** argv) {
  // before QApplication, which needs a display
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::fputs(kHelp, stdout);
      return 0;
    }
  }
  QApplication app(argc, argv);
  lcnc::hmi::apply_hmi_font();
  if (const QStringList missing = lcnc::hmi::missing_hmi_font_families(); !missing.isEmpty())
    std::fprintf(stderr, "lasercnc-hmi: warning: font %s not installed: the screens may not fit 1280 x 800\n",
                 missing.join(", ").toStdString().c_str());
  std::string db_path;  // default: the user's data folder
  std::string shm_name = lcnc::shm::kDefaultName;
  QString screenshot_dir;
  std::string import_path;
  QString dxf_path, program_path, cut_path;
  std::string sensor_spec, probe_device, laser_spec, meter_spec, head_spec;
  QString language = "system";
  std::string machine_file;
  const QStringList args = app.arguments();
  for (int i = 1; i < args.size(); ++i) {
    const QString& a = args[i];
    if ((a == "--db" || a == "--shm" || a == "--screenshot" || a == "--import" || a == "--dxf" ||
         a == "--sensor" || a == "--probe" || a == "--laser" || a == "--meter" || a == "--head" ||
         a == "--lang" || a == "--machine" || a == "--program" || a == "--cut") &&
        i + 1 < args.size()) {
      const QString& v = args[++i];
      if (a == "--db")
        db_path = v.toStdString();
      else if (a == "--shm")
        shm_name = v.toStdString();
      else if (a == "--import")
        import_path = v.toStdString();
      else if (a == "--dxf")
        dxf_path = v;
      else if (a == "--program")
        program_path = v;
      else if (a == "--cut")
        cut_path = v;
      else if (a == "--sensor")
        sensor_spec = v.toStdString();
      else if (a == "--probe")
        probe_device = v.toStdString();
      else if (a == "--laser")
        laser_spec = v.toStdString();
      else if (a == "--meter")
        meter_spec = v.toStdString();
      else if (a == "--head")
        head_spec = v.toStdString();
      else if (a == "--lang")
        language = v;
      else if (a == "--machine")
        machine_file = v.toStdString();
      else
        screenshot_dir = v;
    } else {
      std::fputs(kUsage, stderr);
      return 2;
    }
  }
  QString why;
  if (!lcnc::hmi::install_language(language, &why)) {
    std::fprintf(stderr, "lasercnc-hmi: --lang: %s\n", why.toUtf8().constData());
    return 2;
  }
  if (db_path.empty()) {
    // $XDG_DATA_HOME/lasercnc (~/.local/share/lasercnc): the operator's,
    // whatever folder the HMI is started from
    const QString dir = QStandardPaths::writableLocation(QStandardPaths::GenericDataLocation) + "/lasercnc";
    if (!QDir().mkpath(dir)) {
      std::fprintf(stderr, "lasercnc-hmi: cannot create %s for the process database (--db FILE)\n",
                   dir.toUtf8().constData());
      return 1;
    }
    db_path = (dir + "/process.db").toStdString();
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
  lcnc::hmi::PeripheralEndpoints peripherals;
  std::unique_ptr<lcnc::hmi::SimPeripherals> sims;
  peripherals.probe_serial = probe_device;
  const bool real = !(sensor_spec.empty() && laser_spec.empty() && meter_spec.empty() && head_spec.empty());
  if (real) {
    for (auto [flag, spec, out] : {std::tuple{"--sensor", &sensor_spec, &peripherals.sensor},
                                   std::tuple{"--laser", &laser_spec, &peripherals.laser},
                                   std::tuple{"--meter", &meter_spec, &peripherals.meter},
                                   std::tuple{"--head", &head_spec, &peripherals.head}}) {
      if (spec->empty()) continue;
      auto ep = lcnc::drivers::parse_endpoint(*spec);
      if (!ep) {
        std::fprintf(stderr, "lasercnc-hmi: %s %s\n", flag, ep.error().message.c_str());
        return 2;
      }
      *out = *ep;
    }
  } else {
    auto started = lcnc::hmi::SimPeripherals::start(shm_name);
    if (!started) {
      std::fprintf(stderr, "lasercnc-hmi: the simulated peripherals: %s\n",
                   started.error().to_string().c_str());
      return 1;
    }
    sims = std::move(started).value();
    peripherals.sensor = sims->sensor_endpoint();
    if (probe_device.empty()) peripherals.probe_serial = sims->probe_serial_path();
    peripherals.laser = sims->laser_endpoint();
    peripherals.meter = sims->meter_endpoint();
    peripherals.head = sims->head_endpoint();
  }
  lcnc::Result<lcnc::MachineConfig> machine =
      machine_file.empty() ? lcnc::hmi::shipped_machine() : lcnc::load_machine_config(machine_file);
  if (!machine) {
    std::fprintf(stderr, "lasercnc-hmi: %s\n", machine.error().to_string().c_str());
    return 1;
  }
  lcnc::hmi::MainWindow window(**db, shm_name, peripherals, &*machine);
  if (!program_path.isEmpty()) {
    window.program()->open_file(program_path);
    if (!screenshot_dir.isEmpty()) window.program()->wait_done();
  }
  if (!cut_path.isEmpty()) window.cutting()->open_file(cut_path);
  if (!dxf_path.isEmpty()) {
    window.decomposition()->open_file(dxf_path);
    window.decomposition()->decompose();
    if (!screenshot_dir.isEmpty()) window.decomposition()->wait_done();
  }
  if (!screenshot_dir.isEmpty()) {
    window.adjust()->wait_polled();
    for (const QString& f : window.screenshot_all(screenshot_dir))
      std::printf("%s\n", f.toUtf8().constData());
    return 0;
  }
  window.show();
  return app.exec();
}
