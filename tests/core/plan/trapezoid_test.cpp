#include "plan/trapezoid.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lcnc {
namespace {

TEST(Trapezoid, ReachesCruiseWhenLongEnough) {
  const Trapezoid p = Trapezoid::plan(100.0, 1000.0, 0.0, 100.0, 0.0);
  EXPECT_DOUBLE_EQ(p.vc, 100.0);
  EXPECT_NEAR(p.t_acc, 0.1, 1e-12);
  EXPECT_NEAR(p.duration(), 100.0 / 100.0 + 100.0 / 1000.0, 1e-12);
  EXPECT_NEAR(p.position(p.duration()), 100.0, 1e-12);
  EXPECT_NEAR(p.position(p.t_acc), 5.0, 1e-12);  // v²/2a
}

TEST(Trapezoid, TriangleWhenTooShort) {
  const Trapezoid p = Trapezoid::plan(1.0, 1000.0, 0.0, 100.0, 0.0);
  EXPECT_NEAR(p.vc, std::sqrt(1000.0), 1e-9);
  EXPECT_NEAR(p.t_cruise, 0.0, 1e-12);
  EXPECT_NEAR(p.position(p.duration()), 1.0, 1e-12);
}

TEST(Trapezoid, NonZeroEndSpeeds) {
  const Trapezoid p = Trapezoid::plan(10.0, 100.0, 10.0, 50.0, 20.0);
  EXPECT_NEAR(p.speed(0.0), 10.0, 1e-12);
  EXPECT_NEAR(p.speed(p.duration()), 20.0, 1e-12);
  EXPECT_NEAR(p.position(p.duration()), 10.0, 1e-9);
  // position is monotone and speed never exceeds vc
  double prev = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const double t = p.duration() * k / 1000.0;
    EXPECT_GE(p.position(t), prev - 1e-12);
    EXPECT_LE(p.speed(t), p.vc + 1e-12);
    prev = p.position(t);
  }
}

TEST(Trapezoid, SampleIsPositionAndSpeedTogether) {
  // accelerate, cruise and decelerate, with different a and d, and a triangle
  for (const Trapezoid& p : {Trapezoid::plan(10.0, 100.0, 60.0, 10.0, 20.0, 5.0),
                             Trapezoid::plan(0.5, 100.0, 60.0, 10.0, 50.0, 5.0)}) {
    for (int k = -1; k <= 1001; ++k) {
      const double t = p.duration() * k / 1000.0;
      double s = -1.0, v = -1.0;
      p.sample(t, s, v);
      EXPECT_EQ(s, p.position(t)) << t;
      EXPECT_EQ(v, p.speed(t)) << t;
    }
  }
}

// set() replans a profile in place (the look-ahead's ring reuses them):
// every field as plan() gives it, whatever the profile held before —
// nothing to move after a cruise included.
TEST(Trapezoid, SetOverAUsedProfileIsAFreshOne) {
  struct Args {
    double length, accel, decel, v0, v_target, v1;
  };
  const Args cases[] = {{10.0, 100.0, 60.0, 10.0, 20.0, 5.0},
                        {0.5, 100.0, 60.0, 10.0, 50.0, 5.0},
                        {0.0, 100.0, 60.0, 0.0, 50.0, 0.0},
                        {3.0, 100.0, 100.0, 0.0, 0.0, 0.0}};
  for (const Args& before : cases) {
    for (const Args& a : cases) {
      Trapezoid p =
          Trapezoid::plan(before.length, before.accel, before.decel, before.v0, before.v_target, before.v1);
      p.set(a.length, a.accel, a.decel, a.v0, a.v_target, a.v1);
      const Trapezoid q = Trapezoid::plan(a.length, a.accel, a.decel, a.v0, a.v_target, a.v1);
      for (const auto f : {&Trapezoid::length, &Trapezoid::accel, &Trapezoid::decel, &Trapezoid::v0,
                           &Trapezoid::vc, &Trapezoid::v1, &Trapezoid::t_acc, &Trapezoid::t_cruise,
                           &Trapezoid::t_dec, &Trapezoid::s_acc, &Trapezoid::s_cruise})
        EXPECT_EQ(p.*f, q.*f);
    }
  }
  // nothing to move: no time, no path
  const Trapezoid none = Trapezoid::plan(0.0, 100.0, 60.0, 0.0, 50.0, 0.0);
  EXPECT_EQ(none.duration(), 0.0);
  EXPECT_EQ(none.vc, 0.0);
}

// A move whose target speed is at or below standing still (a feed of
// 1e-9 mm/min, or none) still takes time for its length: dropping it as
// "nothing to move" made the next move start a whole length away, a jump.
TEST(Trapezoid, AMoveWithLengthNeverTakesNoTime) {
  for (const double v_target : {0.0, 1e-20, 1.0 / 6e10, -1.0, std::nan("")}) {
    const Trapezoid p = Trapezoid::plan(10.0, 5000.0, 0.0, v_target, 0.0);
    EXPECT_GT(p.duration(), 1e9) << v_target;  // 10 mm at no more than 1e-9 mm/s
    EXPECT_TRUE(std::isfinite(p.duration())) << v_target;
    EXPECT_LE(p.vc, 1e-9) << v_target;
    EXPECT_NEAR(p.position(p.duration()), 10.0, 1e-9) << v_target;
    EXPECT_LT(p.position(1.0), 1e-8) << v_target;  // a second moves it no more than the crawl
  }
}

TEST(Trapezoid, HoldHasDurationAndNoPath) {
  const Trapezoid p = Trapezoid::hold(0.25);
  EXPECT_DOUBLE_EQ(p.duration(), 0.25);
  EXPECT_DOUBLE_EQ(p.position(0.2), 0.0);
}

}  // namespace
}  // namespace lcnc
