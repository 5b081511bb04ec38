// A decomposed part cut on the simulated machine as two axis groups (main X,
// Y; auxiliary P, Q), each with its own RT kernel on one time base: the
// steps are exact per group, the beam X + P, Y + Q is on the contour at the
// same instant (a group one period behind would be vk·T = 7.5 µm off), and
// the main group stays within its limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "app/decompose_run.h"
#include "app/machine_files.h"
#include "app/run_job.h"
#include "decompose/part_decomposition.h"
#include "dxf/dxf_reader.h"

namespace lcnc::app {
namespace {

const std::string kStar = std::string(LCNC_SOURCE_DIR) + "/share/examples/star_decompose.dxf";

struct StarPart {
  MachineConfig main, aux;
  decompose::Options opt;
  decompose::PartResult part;
  StarPart() {
    main = load_machine_config(default_machine_file()).value();
    aux = load_machine_config(shipped_machine_file("aux_stage")).value();
    opt.speed_mm_s = 100.0;  // 6 m/min
    opt = group_limits(main, aux, opt).value();
    Result<dxf::ReadResult> read = dxf::read_dxf_file(kStar, {});
    EXPECT_TRUE(static_cast<bool>(read));
    Result<decompose::PartResult> r = decompose::decompose_part(read->drawing, 0.05, opt);
    EXPECT_TRUE(static_cast<bool>(r)) << (r ? "" : r.error().to_string());
    part = std::move(r).value();
  }
};

TEST(DecomposeRun, TwoAxisGroupsCutThePartExactlyOnOneTimeBase) {
  StarPart s;
  DecomposeRunOptions o;
  o.realtime = false;
  o.origin_x_mm = 200.0;
  o.origin_y_mm = 100.0;
  const Result<DecomposeRunReport> r = run_decomposition(s.part, s.main, s.aux, o);
  ASSERT_TRUE(static_cast<bool>(r)) << r.error().to_string();
  EXPECT_EQ(r->main.steps_sent, r->main.steps_commanded);
  EXPECT_EQ(r->aux.steps_sent, r->aux.steps_commanded);
  EXPECT_EQ(r->aux.steps_commanded, (std::array<std::int64_t, 2>{0, 0}));  // back at the centre
  EXPECT_EQ(r->main.underruns + r->aux.underruns, 0u);
  EXPECT_FALSE(r->main.fault || r->aux.fault);
  EXPECT_EQ(r->traced_periods, r->periods);
  // each coordinate off by at most half a step per group: ≤ √2 µm
  EXPECT_LE(r->beam_deviation_mm, 0.0015);
  EXPECT_GT(r->beam_deviation_mm, 0.0);
  // the cutting time is the contours' length at the contour speed
  double length = 0;
  for (const decompose::ContourResult& c : s.part.contours) length += c.polyline.length_mm;
  const double T = s.main.period_s();
  EXPECT_NEAR(r->cutting_time_s, length / s.opt.speed_mm_s,
              2.0 * T * static_cast<double>(s.part.contours.size()));
  EXPECT_GT(r->cycle_time_s, r->cutting_time_s);
  // main limits, with the windows' quantization (2 µm over the window)
  const double w = kAccelWindow * T;
  EXPECT_LE(r->main.peak_accel, s.main.axis(Axis::X).max_acceleration + r->main.accel_resolution);
  EXPECT_LT(r->main.accel_resolution, 2.9e-3 / (w * w));
  EXPECT_LE(r->main.peak_speed, s.main.axis(Axis::X).max_velocity + r->main.speed_resolution);
  EXPECT_GT(r->main.peak_accel, 0.1 * s.opt.main_accel_mm_s2);  // it moved, measured
  // while cutting: what the decomposition planned, to the windows' resolution
  double planned_a = 0, planned_v_aux = 0;
  for (const decompose::ContourResult& c : s.part.contours) {
    planned_a = std::max(planned_a, c.peaks.a_main);
    planned_v_aux = std::max(planned_v_aux, c.peaks.v_aux);
  }
  EXPECT_LE(r->main.cutting_accel, planned_a + r->main.accel_resolution);
  EXPECT_GT(r->main.cutting_accel, 0.5 * planned_a);
  EXPECT_LE(r->aux.cutting_speed, planned_v_aux + r->aux.speed_resolution);
  // the auxiliary group moved within its field and speed
  EXPECT_GT(r->aux.peak_speed, 0.5 * s.opt.speed_mm_s);
  EXPECT_LE(r->aux.peak_speed, s.aux.axis(Axis::X).max_velocity + 1e-3 / (kSpeedWindow * T));
  // the picture's samples: cutting and traversing
  ASSERT_GT(r->curves.t_s.size(), 100u);
  std::size_t on = 0;
  for (bool b : r->curves.laser) on += b ? 1 : 0;
  EXPECT_GT(on, 0u);
  EXPECT_LT(on, r->curves.laser.size());
  const std::string svg = decompose::axes_svg(r->curves, "star");
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("#fff2cc"), std::string::npos);  // laser-on spans
}

TEST(DecomposeRun, APartBeyondTheTravelIsRefusedBeforeAnythingMoves) {
  StarPart s;
  DecomposeRunOptions o;
  o.realtime = false;
  o.origin_x_mm = 990.0;  // the star is wider than 10 mm
  const Result<DecomposeRunReport> r = run_decomposition(s.part, s.main, s.aux, o);
  ASSERT_FALSE(static_cast<bool>(r));
  EXPECT_EQ(r.error().code, ErrorCode::DecomposeBeyondTravel);
  EXPECT_NE(r.error().message.find("contour"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("X = "), std::string::npos) << r.error().message;
  // a field wider than the stage's travel
  decompose::Options wide = s.opt;
  wide.aux_half_field_mm = 20.0;
  EXPECT_EQ(group_limits(s.main, s.aux, wide)->aux_half_field_mm, 5.0);
}

TEST(DecomposeRun, GroupsOnDifferentPeriodsAreRefused) {
  StarPart s;
  s.aux.period_ns = 50'000;
  const Result<DecomposeRunReport> r = run_decomposition(s.part, s.main, s.aux, {});
  ASSERT_FALSE(static_cast<bool>(r));
  EXPECT_EQ(r.error().code, ErrorCode::DecomposeBadOption);
  EXPECT_NE(r.error().message.find("one period"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace lcnc::app
