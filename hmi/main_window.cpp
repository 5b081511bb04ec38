#include "hmi/main_window.h"

#include <QDir>

#include <QPixmap>
#include <QTabWidget>
#include <cstdlib>
#include <string>

#include "common/share_path.h"
#include "hmi/adjust_page.h"
#include "hmi/cut_page.h"
#include "hmi/decomposition_page.h"
#include "hmi/focal_page.h"
#include "hmi/machine_page.h"
#include "hmi/measure_page.h"
#include "hmi/process_db_page.h"
#include "hmi/program_page.h"

namespace lcnc::hmi {

Result<MachineConfig> shipped_machine() { return load_machine_config(share_path("machines/default.toml")); }

MainWindow::MainWindow(ProcessDatabase& db, const std::string& shm_name,
                       const PeripheralEndpoints& peripherals, const MachineConfig* machine, QWidget* parent)
    : QMainWindow(parent), tabs_(new QTabWidget(this)) {
  setObjectName("mainWindow");
  setWindowTitle(tr("LaserCNC"));
  tabs_->setObjectName("screens");
  db_page_ = new ProcessDbPage(db, shm_name, tabs_);
  db_page_->setObjectName("processDbPage");
  machine_page_ = new MachinePage(shm_name, tabs_);
  machine_page_->setObjectName("machinePage");
  tabs_->addTab(machine_page_, tr("Machine"));
  MachineConfig m;
  if (machine != nullptr) {
    m = *machine;
  } else if (Result<MachineConfig> d = shipped_machine()) {
    m = *d;
  }
  program_page_ = new ProgramPage(m, shm_name, tabs_);
  program_page_->setObjectName("programPage");
  tabs_->addTab(program_page_, tr("Program"));
  cut_page_ = new CutPage(shm_name, tabs_);
  cut_page_->setObjectName("cutPage");
  tabs_->addTab(cut_page_, tr("Laser cutting"));
  tabs_->addTab(db_page_, tr("Process database"));
  measure_page_ = new MeasurePage(db, shm_name, peripherals.probe_serial, tabs_);
  measure_page_->setObjectName("measurePage");
  tabs_->addTab(measure_page_, tr("3D measurement"));
  focal_page_ = new FocalPage(db, shm_name, peripherals.sensor, tabs_);
  focal_page_->setObjectName("focalPage");
  tabs_->addTab(focal_page_, tr("Focal length"));
  adjust_page_ = new AdjustPage({peripherals.laser, peripherals.meter, peripherals.head}, tabs_);
  adjust_page_->setObjectName("adjustPage");
  tabs_->addTab(adjust_page_, tr("Laser and head"));
  decomposition_page_ = new DecompositionPage(tabs_);
  decomposition_page_->setObjectName("decompositionPage");
  tabs_->addTab(decomposition_page_, tr("Main + auxiliary axes"));
  setCentralWidget(tabs_);
  resize(1200, 640);
}

MainWindow::~MainWindow() = default;

QStringList MainWindow::screenshot_all(const QString& dir) {
  QDir().mkpath(dir);
  QStringList written;
  for (int i = 0; i < tabs_->count(); ++i) {
    tabs_->setCurrentIndex(i);
    QWidget* page = tabs_->widget(i);
    const QString path = QDir(dir).filePath(page->objectName() + ".png");
    if (grab().save(path, "PNG")) written << path;
  }
  tabs_->setCurrentIndex(0);
  return written;
}

}  // namespace lcnc::hmi
