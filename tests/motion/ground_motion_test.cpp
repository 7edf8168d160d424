// Ground-motion operations against closed forms: integration, rotation, windows, scaling,
// resampling, alignment of components, baseline correction.
#include "rigid/motion/ground_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::motion {
namespace {

GroundMotion pair_motion(std::vector<double> x, std::vector<double> y, double dt) {
  return make_ground_motion("pair", {{std::move(x), dt, "1"}, {std::move(y), dt, "2"}});
}

TEST(Integration, SineAccelerationMatchesClosedFormVelocityAndDisplacement) {
  // a = A sin(w t) -> v = A/w (1 - cos w t), d = A/w (t - sin(w t)/w), from rest
  const double A = 3.0, w = 2.0 * kPi * 1.7, dt = 1e-3;
  const std::size_t n = 5001;
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = A * std::sin(w * double(i) * dt);
  const Kinematics k = integrate(a, dt);
  double ev = 0, ed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i) * dt;
    ev = std::max(ev, std::abs(k.vel[i] - A / w * (1 - std::cos(w * t))));
    ed = std::max(ed, std::abs(k.disp[i] - A / w * (t - std::sin(w * t) / w)));
  }
  // trapezoid rule: error O(dt^2 w^2) relative to the amplitudes
  EXPECT_LT(ev / (2 * A / w), 1e-5);
  EXPECT_LT(ed / (A / w * 5.0), 1e-5);
  EXPECT_EQ(k.vel[0], 0.0);
}

TEST(Integration, TrapezoidIsExactForLinearAcceleration) {
  const double dt = 0.01;
  std::vector<double> a(1001);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 2.5 * double(i) * dt - 1.0;
  const auto v = integrate_trapezoid(a, dt);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = double(i) * dt;
    EXPECT_NEAR(v[i], 1.25 * t * t - t, 1e-12);
  }
}

TEST(Integration, LinearVelocityBaselineRemovesConstantAccelerationOffset) {
  // a constant offset c gives v = c t: exactly the fitted line, so the corrected v vanishes
  const double c = 0.02, dt = 0.01;
  std::vector<double> a(2001, c);
  const Kinematics k = integrate(a, dt, Baseline::velocity_linear);
  EXPECT_LT(peak_abs(k.vel), 1e-12);
  EXPECT_LT(peak_abs(k.acc), 1e-12);
  // quadratic fit removes a linear drift of acceleration: a = c + b t -> v = c t + b t^2 / 2
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = c + 0.003 * double(i) * dt;
  const Kinematics q = integrate(a, dt, Baseline::velocity_quadratic);
  EXPECT_LT(peak_abs(q.vel), 1e-10);
}

TEST(Integration, PeaksOfHalfSineCycle) {
  // one-sine acceleration pulse: PGV = 2A/w at t = T/2
  const double A = 9.80665, T = 0.5, dt = T / 1000, w = 2 * kPi / T;
  std::vector<double> a(2001, 0.0);
  for (std::size_t i = 0; i <= 1000; ++i) a[i] = A * std::sin(w * double(i) * dt);
  const Peaks p = peaks(a, dt);
  EXPECT_NEAR(p.pga, A, 1e-12 * A);
  EXPECT_NEAR(p.pgv, 2 * A / w, 1e-5 * 2 * A / w);
}

TEST(Rotation, NinetyDegreesSwapsComponents) {
  const double dt = 0.01;
  GroundMotion m = pair_motion({1, 2, 3, -4}, {5, -6, 7, 8}, dt);
  const GroundMotion r = rotated(m, kPi / 2);
  // x' = x cos - y sin = -y, y' = x sin + y cos = x
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(r.x[i], -m.y[i], 1e-12);
    EXPECT_NEAR(r.y[i], m.x[i], 1e-12);
  }
}

TEST(Rotation, ConventionIsCounterClockwiseAndPreservesNorm) {
  GroundMotion m = pair_motion({1, 0}, {0, 1}, 0.01);
  const double th = 0.3;
  const GroundMotion r = rotated(m, th);
  EXPECT_NEAR(r.x[0], std::cos(th), 1e-15);
  EXPECT_NEAR(r.y[0], std::sin(th), 1e-15);
  EXPECT_NEAR(r.x[1], -std::sin(th), 1e-15);
  EXPECT_NEAR(r.y[1], std::cos(th), 1e-15);
  const GroundMotion back = rotated(r, -th);
  EXPECT_NEAR(back.x[0], 1.0, 1e-15);
  EXPECT_NEAR(back.y[1], 1.0, 1e-15);
}

TEST(Rotation, SingleHorizontalGainsSecondComponent) {
  GroundMotion m = make_ground_motion("one", {{{2.0, -1.0}, 0.01, "N"}});
  const GroundMotion r = rotated(m, kPi / 6);
  ASSERT_TRUE(r.has_y);
  EXPECT_NEAR(r.x[0], 2.0 * std::cos(kPi / 6), 1e-15);
  EXPECT_NEAR(r.y[0], 2.0 * std::sin(kPi / 6), 1e-15);
}

TEST(Window, SelectsSamplesAndRestartsTime) {
  std::vector<double> a(101);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = double(i);
  GroundMotion m = make_ground_motion("w", {{a, 0.01, "x"}});
  const GroundMotion w = windowed(m, 0.25, 0.5);
  ASSERT_EQ(w.npts(), 26u);
  EXPECT_EQ(w.x.front(), 25.0);
  EXPECT_EQ(w.x.back(), 50.0);
  // an end past the record is clamped
  EXPECT_EQ(windowed(m, 0.9, 100.0).npts(), 11u);
  EXPECT_THROW(windowed(m, 0.5, 0.2), InputError);
  EXPECT_THROW(windowed(m, 2.0, 3.0), InputError);
}

TEST(Scaling, TargetPgaWithOneHorizontalUsesItsPga) {
  GroundMotion m = make_ground_motion("s", {{{0.0, 0.5, -2.0, 1.0}, 0.01, "x"}, {{0.0, 0.0, 0.0, 3.0}, 0.01, "z"}});
  m.z = m.y;  // treat the second component as vertical
  m.y.clear();
  m.has_y = false;
  m.has_z = true;
  const GroundMotion s = scaled_to_pga(m, 0.5);
  EXPECT_NEAR(peak_abs(s.x), 0.5 * kGravity, 1e-12);
  // the vertical is scaled by the same factor
  EXPECT_NEAR(s.z[3], 3.0 * 0.5 * kGravity / 2.0, 1e-12);
  EXPECT_THROW(scaled_to_pga(m, -1.0), InputError);
}

TEST(Scaling, TargetPgaWithTwoHorizontalsSetsGmrotiPga) {
  const double dt = 0.002;
  std::vector<double> x(4001), y(4001);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = double(i) * dt;
    x[i] = 2.0 * std::sin(2 * kPi * 1.3 * t) * std::exp(-0.3 * t);
    y[i] = 1.1 * std::cos(2 * kPi * 0.9 * t) * std::exp(-0.2 * t);
  }
  const GroundMotion m = pair_motion(x, y, dt);
  const GroundMotion s = scaled_to_pga(m, 0.35);
  EXPECT_NEAR(horizontal_measures(s).gmroti50_pga / kGravity, 0.35, 1e-12);
  // the factor is linear: the ratio of component PGAs is kept
  EXPECT_NEAR(peak_abs(s.x) / peak_abs(s.y), peak_abs(x) / peak_abs(y), 1e-12);
}

TEST(Transform, WindowThenScaleThenRotate) {
  std::vector<double> x(201, 0.0), y(201, 0.0);
  x[150] = 1.0;
  y[50] = 7.0;  // outside the window
  const GroundMotion m = pair_motion(x, y, 0.01);
  MotionTransform t;
  t.start = 1.0;
  t.end = 2.0;
  t.factor = 3.0;
  t.rotation = kPi / 2;
  const GroundMotion r = transformed(m, t);
  ASSERT_EQ(r.npts(), 101u);
  EXPECT_NEAR(r.y[50], 3.0, 1e-12);  // x -> y under +90 deg
  EXPECT_NEAR(r.x[50], 0.0, 1e-12);
}

TEST(Alignment, UnequalLengthOrDtIsAnErrorUnlessResampling) {
  Component a{{0, 1, 2, 3, 4}, 0.01, "a"};
  Component b{{0, 1, 2}, 0.01, "b"};
  Component c{{0, 2, 4}, 0.02, "c"};
  EXPECT_THROW(make_ground_motion("m", {a, b}), InputError);
  EXPECT_THROW(make_ground_motion("m", {a, c}), InputError);
  try {
    make_ground_motion("m", {a, b});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("length"), std::string::npos) << e.what();
  }
  AlignOptions o;
  o.resample = true;
  const GroundMotion m = make_ground_motion("m", {a, b, c}, o);
  EXPECT_EQ(m.dt, 0.01);
  ASSERT_EQ(m.npts(), 5u);
  // b padded with zeros; c (linear) resampled exactly
  EXPECT_EQ(m.y[4], 0.0);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(m.z[i], double(i), 1e-12);
}

TEST(Alignment, LengthsWithinOnePercentAtEqualDtArePaddedAndNoted) {
  // 1,000 samples against 990 (1 %): padded, the data untouched; 989 (1.1 %): refused
  std::vector<double> long_one(1000), short_one(990), shorter(989);
  for (std::size_t i = 0; i < long_one.size(); ++i) long_one[i] = std::sin(0.01 * double(i));
  for (std::size_t i = 0; i < short_one.size(); ++i) short_one[i] = std::cos(0.01 * double(i));
  for (std::size_t i = 0; i < shorter.size(); ++i) shorter[i] = 1.0;
  const GroundMotion m = make_ground_motion("m", {{long_one, 0.02, "H1"}, {short_one, 0.02, "H2"}});
  ASSERT_EQ(m.npts(), 1000u);
  ASSERT_EQ(m.y.size(), 1000u);
  EXPECT_EQ(m.x, long_one);
  for (std::size_t i = 0; i < short_one.size(); ++i) EXPECT_EQ(m.y[i], short_one[i]);
  for (std::size_t i = short_one.size(); i < 1000; ++i) EXPECT_EQ(m.y[i], 0.0);
  EXPECT_NE(m.alignment.find("component H2 zero-padded by 10 samples (0.2 s)"), std::string::npos) << m.alignment;
  EXPECT_THROW(make_ground_motion("m", {{long_one, 0.02, "H1"}, {shorter, 0.02, "H2"}}), InputError);
  // equal lengths: nothing to note
  EXPECT_TRUE(make_ground_motion("m", {{long_one, 0.02, "H1"}, {long_one, 0.02, "H2"}}).alignment.empty());
}

TEST(Resampling, LinearInterpolationIsExactForLinearSeries) {
  std::vector<double> a(11);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 3.0 * double(i) * 0.02 + 1.0;
  const auto r = resample_linear(a, 0.02, 0.005);
  ASSERT_EQ(r.size(), 41u);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(r[i], 3.0 * double(i) * 0.005 + 1.0, 1e-12);
}

TEST(GroundVelocityTest, AllThreeAxesIntegratedAbsentOnesZero) {
  GroundMotion m = make_ground_motion("v", {{{1.0, 1.0, 1.0}, 0.5, "x"}});
  const GroundVelocity v = ground_velocity(m);
  ASSERT_EQ(v.vx.size(), 3u);
  EXPECT_DOUBLE_EQ(v.vx[2], 1.0);
  EXPECT_EQ(v.vy, std::vector<double>(3, 0.0));
  EXPECT_EQ(v.vz, std::vector<double>(3, 0.0));
  EXPECT_EQ(v.dt, 0.5);
}

}  // namespace
}  // namespace rigid::motion
