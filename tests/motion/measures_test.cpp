// GMRotD/GMRotI/RotD against the closed form for a pair of sinusoids, and the Nigam-Jennings
// oscillator against closed-form SDOF solutions.
#include "rigid/motion/measures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "rigid/core/types.hpp"

namespace rigid::motion {
namespace {

// a1 = A cos(w t), a2 = B cos(w t + phi) over whole periods
struct SinePair {
  double A, B, phi;
  std::vector<double> a1, a2;
  SinePair(double A_, double B_, double phi_, double f = 1.0, double dt = 5e-4, double dur = 10.0)
      : A(A_), B(B_), phi(phi_) {
    const std::size_t n = std::size_t(std::lround(dur / dt)) + 1;
    a1.resize(n);
    a2.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double t = double(i) * dt;
      a1[i] = A * std::cos(2 * kPi * f * t);
      a2[i] = B * std::cos(2 * kPi * f * t + phi);
    }
  }
  // closed form: a1 cos(th) + a2 sin(th) = Re[(A cos th + B e^{i phi} sin th) e^{i w t}],
  // whose peak over t is the modulus of the complex amplitude
  double peak(double th) const { return std::abs(A * std::cos(th) + B * std::polar(1.0, phi) * std::sin(th)); }
  double gm(double th_deg) const {
    const double th = th_deg * kPi / 180;
    return std::sqrt(peak(th) * peak(th + kPi / 2));
  }
};

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

TEST(GmRotD, SinusoidPairMatchesClosedFormEllipse) {
  for (const double phi_deg : {0.0, 37.0, 60.0, 90.0, 150.0}) {
    const SinePair s(1.0, 0.45, phi_deg * kPi / 180);
    std::vector<double> gm_cf, p_cf;
    for (int k = 0; k < 90; ++k) gm_cf.push_back(s.gm(k));
    for (int k = 0; k < 180; ++k) p_cf.push_back(s.peak(k * kPi / 180));
    const double tol = 1e-5;  // sampling of the peak, (w dt)^2/8 ~ 1.2e-6
    EXPECT_NEAR(gmrotd(s.a1, s.a2) / median_of(gm_cf), 1.0, tol) << phi_deg;
    EXPECT_NEAR(rotd(s.a1, s.a2, 50) / median_of(p_cf), 1.0, tol) << phi_deg;
    EXPECT_NEAR(rotd(s.a1, s.a2, 100) / *std::max_element(p_cf.begin(), p_cf.end()), 1.0, tol);
    // RotD100 vs the ellipse's semi-major axis sqrt(lambda_max) of [[A^2, AB cos], [., B^2]]
    const double c = s.A * s.B * std::cos(s.phi);
    const double lmax = 0.5 * (s.A * s.A + s.B * s.B) + std::sqrt(0.25 * std::pow(s.A * s.A - s.B * s.B, 2) + c * c);
    EXPECT_NEAR(rotd(s.a1, s.a2, 100) / std::sqrt(lmax), 1.0, 2e-4);  // 1-degree grid
  }
}

TEST(GmRotD, CircularMotionIsTheSameInEveryDirection) {
  const SinePair s(0.7, 0.7, kPi / 2);
  EXPECT_NEAR(gmrotd(s.a1, s.a2), 0.7, 1e-5);
  EXPECT_NEAR(rotd(s.a1, s.a2, 50), 0.7, 1e-5);
  EXPECT_NEAR(rotd(s.a1, s.a2, 100), 0.7, 1e-5);
}

TEST(GmRotD, IsInvariantUnderRotationOfTheRecordByWholeDegrees) {
  const SinePair s(1.0, 0.3, 0.4);
  GroundMotion m = make_ground_motion("p", {{s.a1, 5e-4, "1"}, {s.a2, 5e-4, "2"}});
  const double d0 = gmrotd(m.x, m.y);
  const GroundMotion r = rotated(m, 23.0 * kPi / 180);
  EXPECT_NEAR(gmrotd(r.x, r.y) / d0, 1.0, 1e-9);
}

TEST(GmRotI, SingleComponentMotionPicksTheMedianAngle) {
  // a2 = 0: GM(theta) = A sqrt(|cos th sin th|) for acceleration and velocity alike, so one
  // angle serves both measures and GMRotI50 equals GMRotD50 up to the 1-degree grid
  const SinePair s(1.0, 0.0, 0.0);
  std::vector<double> gm_cf;
  for (int k = 0; k < 90; ++k) {
    const double th = k * kPi / 180;
    gm_cf.push_back(std::sqrt(std::abs(std::cos(th) * std::sin(th))));
  }
  GroundMotion m = make_ground_motion("p", {{s.a1, 5e-4, "1"}, {s.a2, 5e-4, "2"}});
  const HorizontalMeasures h = horizontal_measures(m);
  EXPECT_NEAR(h.gmrotd50_pga, median_of(gm_cf), 1e-5);
  EXPECT_NEAR(h.gmroti50_pga / h.gmrotd50_pga, 1.0, 0.03);
  const double th = h.gmroti50_angle_deg * kPi / 180;
  EXPECT_NEAR(h.gmroti50_pga, std::sqrt(std::abs(std::cos(th) * std::sin(th))), 1e-5);
}

TEST(Percentile, LinearInterpolationBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 50), 2.5);
  EXPECT_DOUBLE_EQ(percentile({5, 1, 3}, 50), 3.0);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3, 4, 5}, 100), 5.0);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3, 4, 5}, 25), 2.0);
}

TEST(Sdof, StepAccelerationPeakIsOnePlusOvershoot) {
  // constant ground acceleration a0 from rest: u = -(a0/w^2)[1 - e^{-z w t}(cos wd t +
  // z/sqrt(1-z^2) sin wd t)], first peak at t = pi/wd: PSA = a0 (1 + exp(-pi z/sqrt(1-z^2))).
  // The input is exactly piecewise linear, so the recursion is exact.
  for (const double T : {0.1, 1.0, 2.0}) {
    const double z = 0.05, w = 2 * kPi / T, wd = w * std::sqrt(1 - z * z);
    const double dt = (kPi / wd) / 400;
    const std::vector<double> a(2000, 1.7);
    const double sa = response_spectrum(a, dt, {T}, z)[0];
    EXPECT_NEAR(sa / (1.7 * (1 + std::exp(-kPi * z / std::sqrt(1 - z * z)))), 1.0, 1e-10) << T;
  }
}

TEST(Sdof, RampAccelerationMatchesClosedFormAtEverySample) {
  // a_g = r t: u'' + 2 z w u' + w^2 u = -r t from rest.
  // u = -r t/w^2 + 2 z r/w^3 + e^{-z w t}(C1 cos wd t + C2 sin wd t),
  // C1 = -2 z r/w^3, C2 = (r/w^2 + z w C1)/wd.
  const double r = 0.8, T = 0.7, z = 0.05, dt = 0.013;
  const double w = 2 * kPi / T, wd = w * std::sqrt(1 - z * z);
  const double C1 = -2 * z * r / (w * w * w), C2 = (r / (w * w) + z * w * C1) / wd;
  std::vector<double> a(800);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = r * double(i) * dt;
  const SdofResponse s = sdof_response(a, dt, T, z);
  double scale = 0, err = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = double(i) * dt;
    const double u = -r * t / (w * w) + 2 * z * r / (w * w * w) +
                     std::exp(-z * w * t) * (C1 * std::cos(wd * t) + C2 * std::sin(wd * t));
    scale = std::max(scale, std::abs(u));
    err = std::max(err, std::abs(s.u[i] - u));
  }
  EXPECT_LT(err / scale, 1e-10);
}

TEST(Sdof, HarmonicInputReachesSteadyStateAmplitude) {
  // a_g = A sin(W t): steady-state |u| = A / sqrt((w^2 - W^2)^2 + (2 z w W)^2)
  const double A = 2.0, z = 0.05, T = 1.0, w = 2 * kPi / T, dt = 0.002;
  for (const double Tg : {0.4, 1.0, 2.5}) {
    const double W = 2 * kPi / Tg;
    const std::size_t n = std::size_t(200.0 / dt);
    std::vector<double> a(n);
    for (std::size_t i = 0; i < n; ++i) a[i] = A * std::sin(W * double(i) * dt);
    const SdofResponse s = sdof_response(a, dt, T, z);
    double tail = 0;  // transient e^{-z w t} < e^{-47} after 150 s
    for (std::size_t i = n * 3 / 4; i < n; ++i) tail = std::max(tail, std::abs(s.u[i]));
    const double U = A / std::sqrt(std::pow(w * w - W * W, 2) + std::pow(2 * z * w * W, 2));
    EXPECT_NEAR(tail / U, 1.0, 1e-3) << Tg;
    // Sa with a slow Hann ramp-up (no transient overshoot) equals w^2 U
    std::vector<double> b = a;
    const std::size_t nr = std::size_t(40.0 / dt);
    for (std::size_t i = 0; i < nr; ++i) b[i] *= 0.5 * (1 - std::cos(kPi * double(i) / double(nr)));
    EXPECT_NEAR(response_spectrum(b, dt, {T}, z)[0] / (w * w * U), 1.0, 2e-3) << Tg;
  }
}

TEST(Sdof, ZeroPeriodGivesPga) { EXPECT_DOUBLE_EQ(response_spectrum({0.0, -3.0, 1.0}, 0.01, {0.0})[0], 3.0); }

}  // namespace
}  // namespace rigid::motion
