// Synthetic motions against their closed forms, and reproducibility of the stochastic model.
#include "rigid/motion/synth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::motion {
namespace {

TEST(Pulses, OneSineHasClosedFormPeaks) {
  // a = A sin(w t) on [0, Tp]: v = A/w (1 - cos w t), PGV = 2A/w at Tp/2, v(Tp) = 0
  PulseParams p;
  p.amplitude_g = 1.0;
  p.period = 0.5;
  p.dt = 0.0005;
  const GroundMotion m = pulse_motion("s", p);
  const double A = kGravity, w = 2 * kPi / p.period;
  EXPECT_FALSE(m.has_y);
  EXPECT_NEAR(peak_abs(m.x), A, 1e-12 * A);
  const Kinematics k = integrate(m.x, m.dt);
  EXPECT_NEAR(peak_abs(k.vel) / (2 * A / w), 1.0, 1e-5);
  EXPECT_NEAR(k.vel.back(), 0.0, 1e-4 * A / w);
  // net displacement of a one-sine pulse: A Tp / w
  EXPECT_NEAR(k.disp.back() / (A * p.period / w), 1.0, 1e-4);
}

TEST(Pulses, OneCosineReturnsToRest) {
  // a = A cos(w t) on [0, Tp]: v = A/w sin(w t), d = A/w^2 (1 - cos w t) -> both 0 at Tp
  PulseParams p;
  p.kind = PulseKind::one_cosine;
  p.amplitude_g = 0.4;
  p.period = 1.0;
  p.dt = 0.001;
  const GroundMotion m = pulse_motion("c", p);
  const double A = 0.4 * kGravity, w = 2 * kPi;
  const Kinematics k = integrate(m.x, m.dt);
  EXPECT_NEAR(peak_abs(k.vel) / (A / w), 1.0, 1e-3);
  EXPECT_NEAR(k.vel.back() / (A / w), 0.0, 1e-6);
  EXPECT_NEAR(k.disp.back() / (A / (w * w)), 0.0, 1e-4);
}

TEST(Pulses, RickerPeakAndZeroNetVelocity) {
  PulseParams p;
  p.kind = PulseKind::ricker;
  p.amplitude_g = 0.3;
  p.period = 0.4;
  p.dt = 0.001;
  const GroundMotion m = pulse_motion("r", p);
  EXPECT_NEAR(peak_abs(m.x), 0.3 * kGravity, 1e-9);
  EXPECT_NEAR(integrate(m.x, m.dt).vel.back(), 0.0, 1e-6);
}

TEST(Pulses, AzimuthSplitsIntoTwoHorizontals) {
  PulseParams p;
  p.two_horizontals = true;
  p.azimuth_deg = 30;
  const GroundMotion m = pulse_motion("a", p);
  ASSERT_TRUE(m.has_y);
  EXPECT_NEAR(peak_abs(m.y) / peak_abs(m.x), std::tan(kPi / 6), 1e-12);
}

TEST(Mavroeidis, AccelerationIsTheDerivativeOfTheVelocityPulse) {
  MavroeidisParams p;
  p.pgv = 0.8;
  p.period = 1.2;
  p.gamma = 2.5;
  p.nu_deg = 40;
  p.dt = 0.0005;
  const GroundMotion m = mavroeidis_motion("mp", p);
  // central differences of the closed-form velocity
  for (double t = 1.1; t < 4.0; t += 0.137) {
    const double h = 1e-5;
    const double fd = (mavroeidis_velocity(p, t + h) - mavroeidis_velocity(p, t - h)) / (2 * h);
    EXPECT_NEAR(mavroeidis_acceleration(p, t), fd, 1e-6 * 2 * kPi / p.period) << t;
  }
  // integrating the sampled acceleration recovers the closed-form velocity
  const auto v = integrate(m.x, m.dt).vel;
  double err = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    err = std::max(err, std::abs(v[i] - mavroeidis_velocity(p, double(i) * m.dt)));
  EXPECT_LT(err, 1e-5 * p.pgv);
}

TEST(Mavroeidis, ZeroPhasePeakVelocityIsTheAmplitude) {
  MavroeidisParams p;
  p.pgv = 0.6;
  p.period = 0.8;
  p.gamma = 3.0;
  p.dt = 0.001;
  const GroundMotion m = mavroeidis_motion("mp", p);
  EXPECT_NEAR(peak_abs(integrate(m.x, m.dt).vel), 0.6, 1e-4);
  EXPECT_THROW(
      [] {
        MavroeidisParams q;
        q.gamma = 1.0;
        mavroeidis_motion("bad", q);
      }(),
      InputError);
}

TEST(Random, Mt19937_64IsTheStandardSequence) {
  // [rand.predef]: the 10000th output of a default-constructed mt19937_64
  std::mt19937_64 e;
  e.discard(9999);
  EXPECT_EQ(e(), 9981545732273789042ULL);
}

TEST(Random, NormalStreamHasUnitMoments) {
  NormalStream s(42);
  double m1 = 0, m2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = s.next();
    m1 += x;
    m2 += x * x;
  }
  m1 /= n;
  m2 /= n;
  EXPECT_NEAR(m1, 0.0, 0.01);   // 4.5 sigma
  EXPECT_NEAR(m2, 1.0, 0.015);  // 4.7 sigma
}

TEST(Stochastic, SameSeedSameBitsDifferentSeedDifferentRecord) {
  StochasticParams p;
  p.duration = 10;
  p.seed = 7;
  const GroundMotion a = stochastic_motion("a", p), b = stochastic_motion("b", p);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
  p.seed = 8;
  const GroundMotion c = stochastic_motion("c", p);
  EXPECT_NE(a.x, c.x);
  EXPECT_NE(a.x, a.y);  // independent components
}

TEST(Stochastic, ScaledToTargetAndReturnsToRest) {
  StochasticParams p;
  p.duration = 20;
  p.pga_g = 0.4;
  const GroundMotion m = stochastic_motion("s", p);
  ASSERT_TRUE(m.has_y && m.has_z);
  EXPECT_NEAR(peak_abs(m.x), 0.4 * kGravity, 1e-12);
  EXPECT_NEAR(peak_abs(m.y), 0.4 * kGravity, 1e-12);
  EXPECT_NEAR(peak_abs(m.z), 0.6 * 0.4 * kGravity, 1e-12);
  for (const auto* a : {&m.x, &m.y, &m.z}) {
    for (double v : *a) ASSERT_TRUE(std::isfinite(v));
    // the high-pass filter leaves little residual velocity at the end
    const auto v = integrate(*a, m.dt).vel;
    EXPECT_LT(std::abs(v.back()), 0.1 * peak_abs(v));
  }
}

TEST(Stochastic, RejectsBadParameters) {
  StochasticParams p;
  p.dt = 0;
  EXPECT_THROW(stochastic_motion("x", p), InputError);
  p = {};
  p.zeta_f = 1.5;
  EXPECT_THROW(stochastic_motion("x", p), InputError);
  p = {};
  p.duration = 1e9;
  EXPECT_THROW(stochastic_motion("x", p), InputError);
}

}  // namespace
}  // namespace rigid::motion
