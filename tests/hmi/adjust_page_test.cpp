// The adjustment and monitoring screen against the simulated laser source,
// power meter and scanning head (real Modbus TCP on loopback), driven by
// object name: power set and emission gated with live read-back, the meter
// following the beam, the power plot filling, the head's parameter block
// written and refused whole while it runs, the links' counters.
#include <gtest/gtest.h>

#include <unistd.h>

#include <QApplication>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>

#include <string>

#include "hmi/adjust_page.h"
#include "hmi/sim_peripherals.h"
#include "tests/hmi/hmi_test_support.h"

namespace lcnc::hmi {
namespace {

using test::wait_until;

double label_value(QWidget& w, const char* name) {
  return w.findChild<QLabel*>(name)->text().split(' ').front().toDouble();
}

TEST(AdjustScreen, SetsPowerGatesEmissionWritesTheHeadAndShowsTheLinks) {
  auto sims = SimPeripherals::start("/lcnc_hmi_adjust_none_" + std::to_string(getpid()));
  ASSERT_TRUE(static_cast<bool>(sims)) << sims.error().to_string();
  AdjustPage page({(*sims)->laser_endpoint(), (*sims)->meter_endpoint(), (*sims)->head_endpoint()});
  QTableWidget* links = page.links();
  ASSERT_EQ(links->rowCount(), 3);
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return links->item(0, 1)->text() == "up" && links->item(1, 1)->text() == "up" &&
           links->item(2, 1)->text() == "up";
  }));
  EXPECT_EQ(page.findChild<QLabel*>("laserStateLabel")->text(), "standby");  // not enabled
  // 40 % of the rated 50 W, emission on: the source and then the meter follow
  page.findChild<QDoubleSpinBox*>("setpointSpin")->setValue(40.0);
  page.findChild<QPushButton*>("applySetpointButton")->click();
  page.findChild<QPushButton*>("enableButton")->setChecked(true);
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return page.findChild<QLabel*>("laserStateLabel")->text() == "emitting";
  })) << page.findChild<QLabel*>("laserStateLabel")->text().toStdString();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return std::abs(label_value(page, "laserPowerLabel") - 20.0) < 0.5;
  })) << page.findChild<QLabel*>("laserPowerLabel")->text().toStdString();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return label_value(page, "meterPowerLabel") > 15.0;  // the thermopile's lag
  })) << page.findChild<QLabel*>("meterPowerLabel")->text().toStdString();
  EXPECT_TRUE(wait_until([&] {  // the plot fills with the laser's polls
    page.refresh();
    return page.plot_samples() >= 8;
  }));
  page.findChild<QPushButton*>("enableButton")->setChecked(false);
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return page.findChild<QLabel*>("laserStateLabel")->text() == "standby";
  }));

  // the head: a block written whole and read back; refused whole while running
  page.findChild<QDoubleSpinBox*>("startRadiusSpin")->setValue(0.8);
  page.findChild<QDoubleSpinBox*>("turnsSpin")->setValue(1000);
  page.findChild<QPushButton*>("writeHeadButton")->click();
  EXPECT_TRUE(wait_until([&] { return page.head()->snapshot().values["start_radius_mm"] == 0.8; }));
  page.findChild<QPushButton*>("runHeadButton")->setChecked(true);
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return page.findChild<QLabel*>("headStateLabel")->text() == "scanning";
  })) << page.findChild<QLabel*>("headStateLabel")->text().toStdString();
  page.findChild<QDoubleSpinBox*>("startRadiusSpin")->setValue(1.5);
  page.findChild<QPushButton*>("writeHeadButton")->click();
  EXPECT_TRUE(wait_until([&] {
    page.refresh();
    return page.message().contains("Refused: head");
  })) << page.message().toStdString();
  EXPECT_EQ(page.head()->snapshot().values["start_radius_mm"], 0.8);  // nothing of it stored
  page.findChild<QPushButton*>("runHeadButton")->setChecked(false);
  // the terminal counts what went over the wire
  page.refresh();
  EXPECT_GT(links->item(0, 2)->text().toInt(), 10);
  EXPECT_EQ(links->item(0, 3)->text().toInt(), 0);
}

TEST(AdjustScreen, ADeviceNotConfiguredOrGoneSaysSo) {
  AdjustPage page({});
  page.refresh();
  EXPECT_EQ(page.links()->item(0, 1)->text(), "not configured");
  drivers::Endpoint nowhere;
  nowhere.port = 1;  // nothing listens on port 1
  AdjustPage gone({nowhere, std::nullopt, std::nullopt});
  EXPECT_TRUE(wait_until([&] {
    gone.refresh();
    return gone.links()->item(0, 1)->text() == "down" && !gone.links()->item(0, 5)->text().isEmpty();
  })) << gone.links()->item(0, 1)->text().toStdString();
  EXPECT_EQ(gone.findChild<QLabel*>("laserStateLabel")->text(), "no link");
}

}  // namespace
}  // namespace lcnc::hmi
