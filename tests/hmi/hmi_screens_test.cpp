// The HMI's screens offscreen, found by object name: the hole table model
// (QAbstractItemModelTester), edits validated in the table, the process
// database screen's import, every screen rendered to PNG, and the machine
// screen against a real lasercncd over shared memory.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <QAbstractItemModelTester>
#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QTabWidget>
#include <QTableView>
#include <QTableWidget>
#include <QTest>
#include <QTime>

#include <filesystem>
#include <fstream>
#include <string>

#include "hmi/hole_table_model.h"
#include "hmi/machine_link.h"
#include "hmi/machine_page.h"
#include "hmi/main_window.h"
#include "hmi/process_db_page.h"
#include "holes/hole_table.h"
#include "tests/e2e/e2e_support.h"
#include "tests/hmi/hmi_test_support.h"

extern char** environ;

namespace lcnc::hmi {
namespace {

namespace fs = std::filesystem;

using e2e::temp_dir;
using test::wait_until;

std::unique_ptr<ProcessDatabase> db_with_holes(const fs::path& dir, int n) {
  auto db = ProcessDatabase::open((dir / "p.db").string());
  EXPECT_TRUE(static_cast<bool>(db));
  for (int i = 1; i <= n; ++i) {
    HoleRecord r;
    r.params.hole_number = static_cast<std::uint32_t>(i);
    r.params.position << 100.0 + i, 50.0, 20.0, 0.0, 0.0, 0.0;
    EXPECT_TRUE((*db)->put(r).ok());
  }
  return std::move(db).value();
}

TEST(HoleTableModel, PassesTheModelTesterAndRefusesOutOfRangeEdits) {
  const fs::path dir = temp_dir();
  auto db = db_with_holes(dir, 3);
  HoleTableModel model(*db);
  QAbstractItemModelTester tester(&model, QAbstractItemModelTester::FailureReportingMode::Fatal);
  EXPECT_EQ(model.rowCount(), 3);
  EXPECT_EQ(model.columnCount(), HoleTableModel::kColumnCount);
  EXPECT_EQ(model.headerData(HoleTableModel::kA, Qt::Horizontal).toString(), "A (deg)");
  QSignalSpy refused(&model, &HoleTableModel::refused);
  const QModelIndex a = model.index(1, HoleTableModel::kA);
  EXPECT_FALSE(model.setData(a, 120.0));
  ASSERT_EQ(refused.count(), 1);
  EXPECT_TRUE(refused.at(0).at(0).toString().contains("hole 2: field 5 A = 120"))
      << refused.at(0).at(0).toString().toStdString();
  EXPECT_EQ((*db->hole(2))->params.position[3], 0.0);  // nothing stored
  EXPECT_EQ(model.data(a).toDouble(), 0.0);
  EXPECT_TRUE(model.setData(a, -30.0));
  EXPECT_EQ((*db->hole(2))->params.position[3], -30.0);  // stored at once
  EXPECT_FALSE(model.setData(model.index(0, HoleTableModel::kLayers), "many"));
  EXPECT_FALSE(model.flags(model.index(0, HoleTableModel::kHole)) & Qt::ItemIsEditable);
}

TEST(ProcessDbScreen, ImportShowsWhereTheFileIsWrongAndAddsHoles) {
  const fs::path dir = temp_dir();
  auto db = db_with_holes(dir, 2);
  ProcessDbPage page(*db);
  auto* table = page.findChild<QTableView*>("holeTable");
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->model()->rowCount(), 2);
  std::ofstream(dir / "bad.csv") << "hole,x_mm\n";
  EXPECT_FALSE(page.import_file(QString::fromStdString((dir / "bad.csv").string()),
                                ProcessDatabase::ImportMode::Merge));
  auto* message = page.findChild<QLabel*>("messageLabel");
  ASSERT_NE(message, nullptr);
  EXPECT_TRUE(message->text().contains("bad.csv:1:1")) << message->text().toStdString();
  EXPECT_EQ(table->model()->rowCount(), 2);
  auto* add = page.findChild<QPushButton*>("addButton");
  ASSERT_NE(add, nullptr);
  add->click();
  EXPECT_EQ(table->model()->rowCount(), 3);
  EXPECT_EQ(page.model().record(2).params.hole_number, 3u);
  EXPECT_TRUE(page.export_file(QString::fromStdString((dir / "out.csv").string())));
  EXPECT_TRUE(page.import_file(QString::fromStdString((dir / "out.csv").string()),
                               ProcessDatabase::ImportMode::Replace));
  EXPECT_EQ(table->model()->rowCount(), 3);
}

// The holes plotted where they are, the selected one marked, a click on a
// hole selecting its row; the columns shown by group.
TEST(ProcessDbScreen, PlotsTheHolesAndShowsTheColumnsByGroup) {
  const fs::path dir = temp_dir();
  auto db = db_with_holes(dir, 4);  // X 101 … 104, Y 50
  ProcessDbPage page(*db);
  page.resize(1000, 700);
  page.show();
  auto* table = page.findChild<QTableView*>("holeTable");
  QWidget* plot = page.plot();
  ASSERT_TRUE(table && plot);
  // left to right in hole order, on one row
  for (int r = 1; r < 4; ++r) {
    EXPECT_GT(page.plotted_at(r).x(), page.plotted_at(r - 1).x() + 5);
    EXPECT_NEAR(page.plotted_at(r).y(), page.plotted_at(0).y(), 1e-9);
  }
  // the pixels in the selection colour, and those right of the middle of holes 2 and 3
  const auto marked = [&](double from_x, double to_x) {
    const QImage img = plot->grab().toImage();
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = static_cast<int>(from_x); x < static_cast<int>(to_x); ++x) {
        const QColor px = img.pixelColor(x, y);
        n += px.red() > 150 && px.green() < 80 && px.blue() < 80 ? 1 : 0;
      }
    return n;
  };
  const double mid12 = 0.5 * (page.plotted_at(1).x() + page.plotted_at(2).x());
  const double mid23 = 0.5 * (page.plotted_at(2).x() + page.plotted_at(3).x());
  EXPECT_EQ(marked(0, plot->width()), 0);
  // a click on hole 3 selects its row, and it is drawn marked
  QTest::mouseClick(plot, Qt::LeftButton, {}, page.plotted_at(2).toPoint());
  ASSERT_EQ(table->selectionModel()->selectedRows().size(), 1);
  EXPECT_EQ(table->selectionModel()->selectedRows().front().row(), 2);
  EXPECT_GT(marked(mid12, mid23), 10);
  EXPECT_EQ(marked(0, mid12 - 0.5 * (mid23 - mid12)), 0);  // holes 1 and 2 not
  // the position's columns, then the process's; the hole number always
  auto* columns = page.findChild<QComboBox*>("columnsCombo");
  ASSERT_NE(columns, nullptr);
  const int n = table->model()->columnCount();
  columns->setCurrentIndex(1);
  EXPECT_FALSE(table->isColumnHidden(0));
  EXPECT_FALSE(table->isColumnHidden(1));      // X
  EXPECT_TRUE(table->isColumnHidden(6));       // feed
  EXPECT_FALSE(table->isColumnHidden(n - 1));  // the focus offset
  columns->setCurrentIndex(2);
  EXPECT_TRUE(table->isColumnHidden(1));
  EXPECT_FALSE(table->isColumnHidden(6));
  columns->setCurrentIndex(0);
  for (int c = 0; c < n; ++c) EXPECT_FALSE(table->isColumnHidden(c)) << c;
}

TEST(MainWindow, EveryScreenRendersToPng) {
  const fs::path dir = temp_dir();
  auto db = db_with_holes(dir, 5);
  MainWindow w(*db, "/lcnc_hmi_no_daemon_" + std::to_string(getpid()));
  const QStringList files = w.screenshot_all(QString::fromStdString((dir / "shots").string()));
  ASSERT_EQ(files.size(), w.screens()->count());
  for (const QString& f : files) {
    const QImage img(f);
    EXPECT_FALSE(img.isNull()) << f.toStdString();
    EXPECT_GE(img.width(), 800) << f.toStdString();
  }
  EXPECT_TRUE(fs::exists(dir / "shots" / "machinePage.png"));
  EXPECT_TRUE(fs::exists(dir / "shots" / "processDbPage.png"));
  EXPECT_TRUE(fs::exists(dir / "shots" / "decompositionPage.png"));
}

TEST(MainWindow, ScreenshotCommandWritesEachScreen) {
  const fs::path dir = temp_dir();
  // (detect_leaks=0: under ASan, Qt's offscreen platform leaks its screen
  // objects at exit; the suite's own main suppresses exactly those)
  const std::string cmd = std::string("QT_QPA_PLATFORM=offscreen ASAN_OPTIONS=detect_leaks=0 ") +
                          LASERCNC_HMI_EXE + " --db " + (dir / "p.db").string() +
                          " --shm /lcnc_hmi_none --screenshot " + (dir / "shots").string() + " > " +
                          (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_GT(fs::file_size(dir / "shots" / "machinePage.png"), 1000u);
  EXPECT_GT(fs::file_size(dir / "shots" / "processDbPage.png"), 1000u);
}

// The machine screen and a real lasercncd on its own segment.
TEST(MachineScreen, ShowsTheDaemonSendsEStopAndSeesTheLinkLost) {
  const std::string shm = "/lcnc_hmi_e2e_" + std::to_string(getpid());
  MachinePage page(shm);
  auto* link = page.findChild<QLabel*>("linkLabel");
  auto* state = page.findChild<QLabel*>("stateLabel");
  auto* dro_x = page.findChild<QLabel*>("droX");
  auto* estop = page.findChild<QPushButton*>("estopButton");
  ASSERT_TRUE(link && state && dro_x && estop);
  page.refresh();
  EXPECT_TRUE(link->text().contains("link lost")) << link->text().toStdString();

  e2e::Daemon daemon(shm);

  EXPECT_TRUE(wait_until([&] { return link->text().contains("connected"); })) << link->text().toStdString();
  EXPECT_TRUE(wait_until([&] { return state->text().contains("idle"); })) << state->text().toStdString();
  EXPECT_EQ(dro_x->text(), "0.000");
  estop->click();
  EXPECT_TRUE(wait_until([&] { return state->text().contains("e-stop"); })) << state->text().toStdString();
  // the daemon killed outright: the screen says so within a second
  EXPECT_EQ(daemon.stop(SIGKILL), -1);
  QElapsedTimer t;
  t.start();
  EXPECT_TRUE(wait_until([&] { return link->text().contains("link lost"); }, 3000));
  EXPECT_LT(t.elapsed(), 1000);
  EXPECT_EQ(dro_x->text(), "—");
}

// The process database's holes sent to a real lasercncd as a drilling job,
// each Z raised by its measured focus offset.
TEST(ProcessDbScreen, SendsTheHolesWithTheirFocusOffsetsToTheController) {
  const std::string shm = "/lcnc_hmi_send_" + std::to_string(getpid());
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  const fs::path dir = temp_dir();
  auto db = db_with_holes(dir, 2);  // Z 20
  ASSERT_TRUE(db->set_focus_offset(1, 0.4).ok());
  ProcessDbPage page(*db, shm);
  std::string sent;
  EXPECT_TRUE(wait_until([&] { return !(sent = page.send_to_controller()).empty(); }))
      << page.message().toStdString();
  // sent again at once (a double click): the table is replaced whole, so
  // the daemon, reading the first, never sees it half-written
  EXPECT_EQ(page.send_to_controller(), sent);
  EXPECT_TRUE(page.message().contains("2 holes (1 with a measured focus offset)"))
      << page.message().toStdString();
  Result<std::vector<HoleProcessParams>> rows = read_hole_table(sent);
  ASSERT_TRUE(static_cast<bool>(rows)) << rows.error().to_string();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_NEAR((*rows)[0].position[2], 20.4, 1e-9);
  EXPECT_NEAR((*rows)[1].position[2], 20.0, 1e-9);
  MachineLink link(shm);
  std::string loaded;
  std::uint32_t lines = 0;
  EXPECT_TRUE(wait_until([&] {
    if (link.poll())
      if (auto j = link.job()) {
        loaded = j->program;
        lines = j->lines;
      }
    return loaded == sent;
  })) << loaded;
  EXPECT_EQ(lines, 2u);  // the daemon built and checked the drilling job
}

// Jog and home an axis from the screen, and the alarm list fills with the
// kernel's events — a fault in the alarm colour, newest first.
TEST(MachineScreen, JogsHomesAndListsTheAlarms) {
  const std::string shm = "/lcnc_hmi_jog_" + std::to_string(getpid());
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  MachinePage page(shm);
  auto* state = page.findChild<QLabel*>("stateLabel");
  auto* dro_x = page.findChild<QLabel*>("droX");
  auto* step = page.findChild<QDoubleSpinBox*>("jogStepSpin");
  auto* alarms = page.findChild<QTableWidget*>("alarmTable");
  ASSERT_TRUE(state && dro_x && step && alarms);
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return state->text().contains("idle");
  }));
  step->setValue(2.5);
  page.findChild<QPushButton*>("jogPlusButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return dro_x->text() == "2.500";
  })) << dro_x->text().toStdString();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return state->text().contains("idle");
  }));
  page.findChild<QPushButton*>("jogMinusButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return dro_x->text() == "0.000";
  })) << dro_x->text().toStdString();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return state->text().contains("idle");
  }));
  const auto row_with = [&](const QString& what) {
    for (int r = 0; r < alarms->rowCount(); ++r)
      if (alarms->item(r, 3)->text().contains(what, Qt::CaseInsensitive) ||
          alarms->item(r, 1)->text() == what)
        return r;
    return -1;
  };
  step->setValue(5.0);
  page.findChild<QPushButton*>("jogPlusButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return dro_x->text() == "5.000";
  })) << dro_x->text().toStdString();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return state->text().contains("idle");
  }));
  page.findChild<QPushButton*>("homeButton")->click();  // X: search, back off, latch
  EXPECT_TRUE(wait_until(
      [&] {
        page.refresh();
        return row_with("homed") >= 0;
      },
      30000))
      << page.findChild<QLabel*>("jobLabel")->text().toStdString();
  // an e-stop: a fault row, in the alarm colour
  page.findChild<QPushButton*>("estopButton")->click();
  int fault = -1;
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    for (int r = 0; r < alarms->rowCount(); ++r)
      if (alarms->item(r, 1)->text().startsWith("E")) fault = r;
    return fault >= 0;
  }));
  ASSERT_GE(fault, 0);
  EXPECT_EQ(alarms->item(fault, 1)->foreground().color(), QColor("#b00020"));
  EXPECT_GT(alarms->rowCount(), 2);  // the jogs and the homing were news too
  page.findChild<QPushButton*>("clearAlarmsButton")->click();
  EXPECT_EQ(alarms->rowCount(), 0);
}

// An operator's controls against a real lasercncd: touch-off from the
// screen sets the work DRO, MDI moves to the touched-off zero, the buttons
// follow the state, the override slider follows the controller.
TEST(MachineScreen, TouchOffMdiAndTheControlsTheStateAllows) {
  const std::string shm = "/lcnc_hmi_op_" + std::to_string(getpid());
  e2e::Daemon daemon(shm);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  MachinePage page(shm);
  auto* state = page.findChild<QLabel*>("stateLabel");
  auto* dro_x = page.findChild<QLabel*>("droX");
  auto* mach_x = page.findChild<QLabel*>("droMachX");
  const auto button = [&](const char* name) { return page.findChild<QPushButton*>(name); };
  ASSERT_TRUE(state && dro_x && mach_x && button("touchOffButton") && button("mdiSendButton"));
  const auto idle = [&] {
    page.refresh();
    return state->text().contains("idle") && button("cycleStartButton") != nullptr &&
           button("jogPlusButton")->isEnabled();
  };
  EXPECT_TRUE(wait_until(idle));
  page.findChild<QDoubleSpinBox*>("jogStepSpin")->setValue(20.0);
  button("jogPlusButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return mach_x->text() == "20.000";
  })) << mach_x->text().toStdString();
  EXPECT_TRUE(wait_until(idle));
  // touch-off: here reads X 5
  page.findChild<QComboBox*>("touchOffAxisCombo")->setCurrentIndex(0);
  page.findChild<QDoubleSpinBox*>("touchOffSpin")->setValue(5.0);
  button("touchOffButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return dro_x->text() == "5.000";
  })) << dro_x->text().toStdString();
  EXPECT_EQ(mach_x->text(), "20.000");
  // MDI to the work zero: machine X 15
  page.findChild<QLineEdit*>("mdiEdit")->setText("G0 X0");
  button("mdiSendButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return mach_x->text() == "15.000" && dro_x->text() == "0.000";
  })) << mach_x->text().toStdString()
      << " " << dro_x->text().toStdString();
  EXPECT_TRUE(wait_until(idle));
  EXPECT_FALSE(button("cycleStartButton")->isEnabled());  // nothing loaded
  EXPECT_FALSE(button("holdButton")->isEnabled());
  EXPECT_FALSE(button("resetButton")->isEnabled());
  // a long move: no start, jog, home, MDI or touch-off while it runs; hold and stop offered
  ASSERT_TRUE(page.send_mdi("M8 G1 X300 F600"));
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return state->text().contains("running");
  })) << state->text().toStdString();
  auto* to_go = page.findChild<QLabel*>("toGoX");
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    bool ok = false;
    const double left = to_go->text().toDouble(&ok);
    return ok && left > 10.0 && left < 285.0;  // X 15 → 300, under way
  })) << to_go->text().toStdString();
  auto* gas = page.findChild<QLabel*>("gasLabel");
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return gas->text().contains("high");
  })) << gas->text().toStdString();
  for (const char* off : {"cycleStartButton", "jogPlusButton", "jogMinusButton", "homeButton",
                          "mdiSendButton", "touchOffButton", "resumeButton", "resetButton", "frameButton"})
    EXPECT_FALSE(button(off)->isEnabled()) << off;
  EXPECT_TRUE(button("holdButton")->isEnabled());
  EXPECT_TRUE(button("stopButton")->isEnabled());
  EXPECT_TRUE(button("estopButton")->isEnabled());
  // the override set elsewhere (lasercnc send override 120): the slider follows
  auto* slider = page.findChild<QSlider*>("overrideSlider");
  MachineLink other(shm);
  ASSERT_TRUE(wait_until([&] { return other.poll(); }));
  ASSERT_NE(other.send(shm::CommandType::Override, 1.2), 0u);
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return slider->value() == 120;
  })) << slider->value();
  button("holdButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return button("resumeButton")->isEnabled();
  }));
  EXPECT_FALSE(button("jogPlusButton")->isEnabled());
  button("stopButton")->click();
  EXPECT_TRUE(wait_until(idle));
  // the state banner is coloured by state, and the alarm rows carry a wall-clock time
  EXPECT_TRUE(state->styleSheet().contains("#2e7d32")) << state->styleSheet().toStdString();
  auto* alarms = page.findChild<QTableWidget*>("alarmTable");
  ASSERT_GT(alarms->rowCount(), 0);
  EXPECT_TRUE(QTime::fromString(alarms->item(0, 0)->text(), "HH:mm:ss").isValid())
      << alarms->item(0, 0)->text().toStdString();
}

}  // namespace
}  // namespace lcnc::hmi
