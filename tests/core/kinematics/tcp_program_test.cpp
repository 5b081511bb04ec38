// Tool-centre-point control of programs: the tip follows the programmed line
// while A and C move, by the configured orientation interpolator; arcs at a
// constant orientation keep their shape; what cannot be followed is an error
// naming the line.
#include "kinematics/tcp_program.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gcode/program_reader.h"
#include "kinematics/orientation_interpolation.h"
#include "kinematics_test_util.h"
#include "machine/machine_config.h"
#include "path/segment_geometry.h"
#include "plan/program_source.h"

namespace lcnc {
namespace {

MachineConfig tcp_machine(OrientationMethod method) {
  auto m = load_machine_config(std::string(LCNC_SOURCE_DIR) + "/share/machines/default.toml");
  EXPECT_TRUE(m) << m.error().to_string();
  m->tcp.enabled = true;
  m->tcp.orientation = method;
  return *m;
}

// The joint segments of a TCP program, from joints `start`.
Result<std::vector<Segment>> expand(const std::string& text, const MachineConfig& m, const Pose& start) {
  const FiveAxisKinematics kin = kinematics_from(m);
  ReaderOptions o;
  o.start = TcpExpander::tip_start(kin, start);
  std::unique_ptr<ProgramReader> r = ProgramReader::from_string(text, "tcp.ngc", m, o);
  TcpExpander x(
      kin, m.tcp,
      [&](Segment& s) {
        switch (r->next(s)) {
          case ProgramReader::Next::Segment: return SourceStatus::Item;
          case ProgramReader::Next::End: return SourceStatus::End;
          case ProgramReader::Next::Error: return SourceStatus::Error;
        }
        return SourceStatus::Error;
      },
      start);
  std::vector<Segment> out;
  Segment s;
  SourceStatus st;
  while ((st = x.next(s)) == SourceStatus::Item) out.push_back(s);
  if (st == SourceStatus::Error) return x.error() ? *x.error() : r->error();
  return out;
}

using testing::joints;

// Distance of p from the segment a–b.
double to_line(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

TEST(TcpProgram, TipFollowsTheLineWhileAAndCMove) {
  const MachineConfig m = tcp_machine(OrientationMethod::PoleSmoothed);
  const FiveAxisKinematics kin = kinematics_from(m);
  const Pose start = joints(300, 200, 300, 0, 0);
  const Vec3 a = kin.forward(start).tip_mm;
  const Vec3 b = a + Vec3(40, 10, -5);
  char prog[200];
  std::snprintf(prog, sizeof prog, "G21 G90\nG1 X%.6f Y%.6f Z%.6f A30 C60 F600\nM2\n", b.x(), b.y(), b.z());
  Result<std::vector<Segment>> segs = expand(prog, m, start);
  ASSERT_TRUE(static_cast<bool>(segs)) << segs.error().to_string();
  ASSERT_GT(segs->size(), 3u);  // split into pieces
  EXPECT_EQ(segs->front().start, start);
  // leaving the pole (A = 0) the path's C may differ from the machine's: a
  // turn of C alone comes first, laser off — the orientation is the same
  if (segs->front().kind == MotionKind::Rapid) {
    const Segment& turn = segs->front();
    EXPECT_EQ(turn.laser, LaserMode::Off);
    for (int i : {0, 1, 2, 3}) EXPECT_EQ(turn.end[i], turn.start[i]);
    segs->erase(segs->begin());
  }
  double worst = 0.0;
  for (const Segment& s : *segs) {
    EXPECT_EQ(s.kind, MotionKind::Linear);
    EXPECT_TRUE(s.curve);
    EXPECT_EQ(s.line, 2u);
    const SegmentGeometry geo(s);  // the curve the planner runs
    for (int k = 0; k <= 8; ++k)
      worst = std::max(worst, to_line(kin.forward(geo.at(geo.length() * k / 8.0)).tip_mm, a, b));
  }
  EXPECT_LE(worst, m.tcp.tip_tolerance_mm + 1e-9);
  const Pose end = segs->back().end;
  EXPECT_NEAR(end[3], 30.0, 1e-9);
  EXPECT_NEAR(end[5], 60.0, 1e-9);
  EXPECT_LT((kin.forward(end).tip_mm - b).norm(), 1e-9);
}

// A G0 that turns the tool is split like a G1, and each piece stays a rapid
// (every joint at its own limit). Pieces made feed moves of feed 0 crawled:
// the program never finished.
TEST(TcpProgram, ARapidThatTurnsTheToolStaysARapidInEveryPiece) {
  const MachineConfig m = tcp_machine(OrientationMethod::PoleSmoothed);
  const FiveAxisKinematics kin = kinematics_from(m);
  const Pose start = joints(300, 200, 300, 0, 0);
  const Vec3 a = kin.forward(start).tip_mm;
  const Vec3 b = a + Vec3(60, -20, 10);
  char prog[200];
  std::snprintf(prog, sizeof prog, "G21 G90\nG0 X%.6f Y%.6f Z%.6f A-30 C40\nM2\n", b.x(), b.y(), b.z());
  Result<std::vector<Segment>> segs = expand(prog, m, start);
  ASSERT_TRUE(static_cast<bool>(segs)) << segs.error().to_string();
  ASSERT_GT(segs->size(), 3u);
  double worst = 0.0;
  for (const Segment& s : *segs) {
    EXPECT_EQ(s.kind, MotionKind::Rapid);
    EXPECT_EQ(s.laser, LaserMode::Off);
    EXPECT_EQ(s.feed_mm_s, 0.0);
    worst = std::max(worst, to_line(kin.forward(s.end).tip_mm, a, b));
  }
  EXPECT_LE(worst, m.tcp.tip_tolerance_mm + 1e-9);
  EXPECT_NEAR(segs->back().end[3], -30.0, 1e-9);
}

// (A, C) and (−A, C + 180°) point the tool alike. A program that names the
// other branch than the machine stands on (as one written after a vector
// move may) must not flip the joints while cutting: on a table-table
// machine the flip swung the tip 7.5 mm off the line. The machine stays on
// its branch and the tip on the line.
TEST(TcpProgram, TheMachineStaysOnItsBranchWhateverBranchTheProgramNames) {
  for (OrientationMethod method : {OrientationMethod::Vector, OrientationMethod::PoleSmoothed}) {
    MachineConfig m = tcp_machine(method);
    m.kinematics.variant = MachineVariant::TableTable;
    const FiveAxisKinematics kin = kinematics_from(m);
    const Pose start = joints(450, 200, 200, -15, 20);
    const Vec3 a = kin.forward(start).tip_mm;
    const Vec3 b = a + Vec3(20, 5, 0);
    const Vec3 c = b + Vec3(20, -5, 0);
    char prog[300];
    std::snprintf(prog, sizeof prog,
                  "G21 G90\nG1 X%.6f Y%.6f Z%.6f A15 C200 F600\nG1 X%.6f Y%.6f Z%.6f\nM2\n", b.x(), b.y(),
                  b.z(), c.x(), c.y(), c.z());
    Result<std::vector<Segment>> segs = expand(prog, m, start);
    ASSERT_TRUE(static_cast<bool>(segs)) << segs.error().to_string();
    double worst = 0.0, worst_corner = 0.0;
    for (std::size_t i = 0; i < segs->size(); ++i) {
      const Segment& s = (*segs)[i];
      EXPECT_NEAR(s.end[3], -15.0, 1e-9) << "line " << s.line;
      EXPECT_NEAR(s.end[5], 20.0, 1e-9) << "line " << s.line;
      // the corner of the two lines (G64: the startup code's), rounded by
      // the piece that starts on line 2 and ends on line 3
      const bool corner = i > 0 && s.line == 3 && (*segs)[i - 1].line == 2;
      const SegmentGeometry geo(s);
      for (int k = 0; k <= 8; ++k) {
        const Vec3 tip = kin.forward(geo.at(geo.length() * k / 8.0)).tip_mm;
        const double d = corner ? std::min(to_line(tip, a, b), to_line(tip, b, c))
                                : to_line(tip, s.line == 2 ? a : b, s.line == 2 ? b : c);
        (corner ? worst_corner : worst) = std::max(corner ? worst_corner : worst, d);
      }
    }
    EXPECT_LE(worst, m.tcp.tip_tolerance_mm + 1e-9) << method_name(method);
    EXPECT_LE(worst_corner, 0.5 * m.path_tolerance_mm + 1e-9) << method_name(method);
    EXPECT_LT((kin.forward(segs->back().end).tip_mm - c).norm(), 1e-6);
  }
}

TEST(TcpProgram, ConstantOrientationArcIsTheSameArcOnAHeadHeadMachine) {
  const MachineConfig m = tcp_machine(OrientationMethod::PoleSmoothed);
  const FiveAxisKinematics kin = kinematics_from(m);
  const Pose start = joints(300, 200, 300, 20, 90);
  const Vec3 tip = kin.forward(start).tip_mm;
  char prog[240];
  std::snprintf(prog, sizeof prog, "G21 G90 G17\nG2 X%.6f Y%.6f I5 J0 F600\nM2\n", tip.x() + 10.0, tip.y());
  Result<std::vector<Segment>> segs = expand(prog, m, start);
  ASSERT_TRUE(static_cast<bool>(segs)) << segs.error().to_string();
  ASSERT_EQ(segs->size(), 1u);
  const Segment& s = segs->front();
  EXPECT_EQ(s.kind, MotionKind::Arc);
  EXPECT_EQ(s.plane, Plane::XY);
  EXPECT_NEAR(SegmentGeometry(s).radius(), 5.0, 1e-9);
  EXPECT_LT((s.start - start).norm(), 1e-9);
  EXPECT_LT((kin.forward(s.end).tip_mm - (tip + Vec3(10, 0, 0))).norm(), 1e-6);  // %.6f in the program
}

TEST(TcpProgram, TheConfiguredInterpolatorDecidesThePathThroughThePole) {
  // from A 30 C 0 to A 30 C 180: the great circle runs over the pole
  const Pose start = joints(300, 200, 300, 30, 0);
  double min_abs_a[3] = {90, 90, 90};
  const OrientationMethod methods[3] = {OrientationMethod::JointLinear, OrientationMethod::PoleSmoothed,
                                        OrientationMethod::Vector};
  for (int k = 0; k < 2; ++k) {
    const MachineConfig m = tcp_machine(methods[k]);
    const Vec3 tip = kinematics_from(m).forward(start).tip_mm;
    char prog[200];
    std::snprintf(prog, sizeof prog, "G21 G90\nG1 X%.6f Y%.6f Z%.6f A30 C180 F600\nM2\n", tip.x() + 20,
                  tip.y(), tip.z());
    Result<std::vector<Segment>> segs = expand(prog, m, start);
    ASSERT_TRUE(static_cast<bool>(segs)) << method_name(methods[k]) << ": " << segs.error().to_string();
    for (const Segment& s : *segs) {
      min_abs_a[k] = std::min(min_abs_a[k], std::abs(s.end[3]));
    }
  }
  // joint-linear keeps A at 30° (and sweeps the tool through 30°-off
  // orientations); pole-smoothed tips the tool over the pole: A passes 0
  EXPECT_NEAR(min_abs_a[0], 30.0, 1e-9);
  EXPECT_LT(min_abs_a[1], 0.5);
}

TEST(TcpProgram, AnArcAlongWhichARotaryAxisMovesIsAnErrorNamingTheLine) {
  const MachineConfig m = tcp_machine(OrientationMethod::PoleSmoothed);
  const Pose start = joints(300, 200, 300, 0, 0);
  const Vec3 tip = kinematics_from(m).forward(start).tip_mm;
  char prog[240];
  std::snprintf(prog, sizeof prog, "G21 G90 G17\nG1 X%.6f F600\nG2 X%.6f Y%.6f I5 J0 A10\nM2\n", tip.x() + 1,
                tip.x() + 11, tip.y());
  Result<std::vector<Segment>> segs = expand(prog, m, start);
  ASSERT_FALSE(static_cast<bool>(segs));
  EXPECT_EQ(segs.error().code, ErrorCode::GcodeUnsupported);
  EXPECT_EQ(segs.error().line, 3u);
  EXPECT_NE(segs.error().message.find("split it into lines"), std::string::npos);
}

TEST(TcpProgram, CheckRefusesJointsBeyondTheTravelThatTheTipAloneWouldNotShow) {
  MachineConfig m = tcp_machine(OrientationMethod::PoleSmoothed);
  // the tip 250 mm up: the head's reference point (200 mm above the tip at
  // A = 0 on the default head) would be at Z 450 + … beyond the 500 mm travel
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/tcp_high.ngc";
  {
    FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("G21 G90\nG1 X100 Y100 Z250 F600\nG1 Z320\nM2\n", f);
    std::fclose(f);
  }
  ReaderOptions o;
  o.start = joints(100, 100, 300, 0, 0);
  Result<ProgramSummary> r = check_job_program(path, m, o);
  ASSERT_FALSE(static_cast<bool>(r));
  EXPECT_EQ(r.error().code, ErrorCode::GcodeBeyondTravel);
  EXPECT_EQ(r.error().line, 3u);
  EXPECT_NE(r.error().message.find("axis Z"), std::string::npos) << r.error().message;
  // without TCP the same program is within the travel (X Y Z are joints)
  m.tcp.enabled = false;
  EXPECT_TRUE(static_cast<bool>(check_job_program(path, m, o)));
}

TEST(TcpConfig, KeysAreReadAndChecked) {
  const std::string axis = "[axes.X]\nmin = 0\nmax = 100\nmax_velocity = 10\nmax_acceleration = 100\n";
  auto m = parse_machine_config(axis +
                                    "[kinematics]\ntcp = true\norientation = \"vector\"\n"
                                    "tip_tolerance_mm = 0.002\norientation_tolerance_deg = 0.05\n",
                                "k.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_TRUE(m->tcp.enabled);
  EXPECT_EQ(m->tcp.orientation, OrientationMethod::Vector);
  EXPECT_EQ(m->tcp.tip_tolerance_mm, 0.002);
  EXPECT_EQ(m->tcp.orientation_tolerance_deg, 0.05);
  auto bad = parse_machine_config(axis + "[kinematics]\norientation = \"slerp\"\n", "k.toml");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("allowed \"joint_linear\", \"vector\" or \"pole_smoothed\""),
            std::string::npos);
  bad = parse_machine_config(axis + "[kinematics]\ntip_tolerance_mm = 0\n", "k.toml");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("allowed > 0 … 0.1 mm"), std::string::npos);
  EXPECT_FALSE(parse_machine_config(axis + "[kinematics]\ntcp = 1\n", "k.toml"));
}

}  // namespace
}  // namespace lcnc
