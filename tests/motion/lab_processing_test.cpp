// Lab signal processing against closed forms: the band-, low- and high-pass designs of every
// order have the Butterworth magnitude through the bilinear transform; a sine inside the band
// passes the zero-phase band-pass with that magnitude squared and no lag, one outside is
// attenuated by it, the second difference of a sine is -w^2 times it (to the
// operator's known gain), and the baselines remove exactly the polynomials they fit.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "rigid/motion/lab_processing.hpp"

namespace {

using namespace rigid::motion;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDt = 1.0 / 800.0;  // the lab's sampling

std::vector<double> sine(double f, double amplitude, double seconds, double phase = 0.0) {
  std::vector<double> x(std::size_t(seconds / kDt) + 1);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = amplitude * std::sin(2 * kPi * f * double(i) * kDt + phase);
  return x;
}

// The sine with 5 s cosine ramps at both ends, as a table motion starts and ends at rest: an
// abrupt start holds energy near the 0.1 Hz corner that rings for tens of seconds
std::vector<double> tapered_sine(double f, double amplitude, double seconds) {
  std::vector<double> x = sine(f, amplitude, seconds);
  const double ramp = 5.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = double(i) * kDt, edge = std::min(t, seconds - t);
    if (edge < ramp) x[i] *= 0.5 * (1 - std::cos(kPi * std::max(edge, 0.0) / ramp));
  }
  return x;
}

// max |a - b| over the middle of the record (the filter's edge transients excluded)
double middle_error(const std::vector<double>& a, const std::vector<double>& b, double keep = 0.5) {
  const std::size_t n = a.size(), from = std::size_t(double(n) * (1 - keep) / 2), to = n - from;
  double e = 0;
  for (std::size_t i = from; i < to; ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

double middle_peak(const std::vector<double>& a, double keep = 0.5) {
  return middle_error(a, std::vector<double>(a.size(), 0.0), keep);
}

// least-squares A, B of y = A sin(2 pi f t) + B cos(2 pi f t) over the middle half
std::pair<double, double> sine_fit(const std::vector<double>& y, double f) {
  double ss = 0, sc = 0, cc = 0, ys = 0, yc = 0;
  for (std::size_t i = y.size() / 4; i < 3 * y.size() / 4; ++i) {
    const double si = std::sin(2 * kPi * f * double(i) * kDt), co = std::cos(2 * kPi * f * double(i) * kDt);
    ss += si * si, sc += si * co, cc += co * co, ys += y[i] * si, yc += y[i] * co;
  }
  const double det = ss * cc - sc * sc;
  return {(ys * cc - yc * sc) / det, (yc * ss - ys * sc) / det};
}

// Butterworth band-pass magnitude (analog prototype through the bilinear transform's prewarping):
// |H|^2 = 1 / (1 + ((W^2 - W1 W2) / (W (W2 - W1)))^(2n)), W = tan(pi f dt)
double butterworth_gain(double f, double lo, double hi, int n) {
  const double w = std::tan(kPi * f * kDt), w1 = std::tan(kPi * lo * kDt), w2 = std::tan(kPi * hi * kDt);
  const double x = (w * w - w1 * w2) / (w * (w2 - w1));
  return 1.0 / std::sqrt(1.0 + std::pow(x, 2 * n));
}

TEST(LabBandPass, ASineInsideTheBandPassesWithItsAmplitudeAndNoLag) {
  const std::vector<Biquad> s = butterworth_bandpass(0.1, 25.0, 4, kDt);
  for (double f : {1.0, 3.0, 8.0}) {
    const std::vector<double> x = tapered_sine(f, 1.0, 40.0);
    const std::vector<double> y = filtfilt(s, x);
    // the forward-backward filter's gain is the Butterworth |H|^2: 1 - 1.7e-10 at 1 Hz but
    // 1 - 8e-5 at 8 Hz. What else is left is the 0.1 Hz corner's slow response to the ramps
    // (up to 6e-5 at 1 Hz, 1e-6 in the fitted amplitude); a single-precision design would lift
    // the pass band by 2.3e-3 at 1 Hz
    const double expected = std::pow(butterworth_gain(f, 0.1, 25.0, 4), 2);
    std::vector<double> scaled = x;
    for (double& v : scaled) v *= expected;
    EXPECT_LT(middle_error(y, scaled), 1e-4) << f << " Hz";
    // no lag: y fitted as A sin + B cos over the middle has phase atan2(B, A) = 0
    const auto [amp_sin, amp_cos] = sine_fit(y, f);
    EXPECT_NEAR(std::atan2(amp_cos, amp_sin), 0.0, 1e-7) << f << " Hz";
    EXPECT_NEAR(std::hypot(amp_sin, amp_cos), expected, 2e-6) << f << " Hz";
  }
}

TEST(LabBandPass, ASineOutsideTheBandIsAttenuatedAsTheButterworthMagnitudeSquared) {
  const std::vector<Biquad> s = butterworth_bandpass(0.1, 25.0, 4, kDt);
  for (double f : {25.0, 40.0, 50.0, 80.0}) {
    const std::vector<double> y = filtfilt(s, tapered_sine(f, 1.0, 40.0));
    const double expected = std::pow(butterworth_gain(f, 0.1, 25.0, 4), 2);
    // the one-pass design agrees with the closed form to double round-off
    EXPECT_NEAR(gain_at(s, f, kDt), butterworth_gain(f, 0.1, 25.0, 4), 1e-10) << f << " Hz";
    const auto [amp_sin, amp_cos] = sine_fit(y, f);
    EXPECT_NEAR(std::hypot(amp_sin, amp_cos), expected, 1e-3 * expected) << f << " Hz";
  }
  // below the band: a 0.02 Hz sine over 250 s (5 periods), |H|^2 = 1 / (1 + 5^8) = 2.6e-6
  const std::vector<double> y = filtfilt(s, sine(0.02, 1.0, 250.0));
  EXPECT_LT(middle_peak(y), 1e-3);
}

// The low- and high-pass of every order against the Butterworth magnitudes through the bilinear
// transform, 1 / sqrt(1 + r^2n) and r^n / sqrt(1 + r^2n), r = tan(pi f dt) / tan(pi fc dt), with a
// corner next to z = 1 (0.15 Hz at 800 Hz), where a single-precision design is off by ~1 %. The
// tolerance, 1e-6 relative, is that of evaluating the sections next to z = 1: a double zero at
// z = 1 gives |1 - z^-1|^2 ~ (2 pi f dt)^2 = 1e-8 at 0.015 Hz, computed from coefficients of order 1.
TEST(LabLowHighPass, EveryOrderHasTheButterworthMagnitude) {
  for (double fc : {0.15, 2.0, 60.0}) {
    for (int n = 1; n <= 8; ++n) {
      const std::vector<Biquad> low = butterworth_lowpass(fc, n, kDt), high = butterworth_highpass(fc, n, kDt);
      EXPECT_EQ(low.size(), std::size_t((n + 1) / 2));
      EXPECT_EQ(high.size(), std::size_t((n + 1) / 2));
      for (double ratio : {0.1, 0.5, 0.9, 1.0, 1.2, 3.0}) {
        const double f = ratio * fc;
        const double r = std::tan(kPi * f * kDt) / std::tan(kPi * fc * kDt), rn = std::pow(r, n);
        const double lp = 1.0 / std::sqrt(1.0 + rn * rn), hp = rn * lp;
        EXPECT_NEAR(gain_at(low, f, kDt), lp, 1e-6 * lp)
            << "low-pass " << fc << " Hz order " << n << " at " << f << " Hz";
        EXPECT_NEAR(gain_at(high, f, kDt), hp, 1e-6 * hp)
            << "high-pass " << fc << " Hz order " << n << " at " << f << " Hz";
      }
    }
  }
  EXPECT_THROW(butterworth_lowpass(0.0, 4, kDt), std::invalid_argument);
  EXPECT_THROW(butterworth_highpass(400.0, 4, kDt), std::invalid_argument);
  EXPECT_THROW(butterworth_lowpass(2.0, 9, kDt), std::invalid_argument);
}

// The band-pass of every order against the closed form at a low corner next to z = 1 (tolerance
// as for the low- and high-pass above)
TEST(LabBandPass, EveryOrderHasTheButterworthMagnitude) {
  for (int n = 1; n <= 8; ++n) {
    const std::vector<Biquad> s = butterworth_bandpass(0.1, 25.0, n, kDt);
    EXPECT_EQ(s.size(), std::size_t(n));
    for (double f : {0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 5.0, 25.0, 60.0}) {
      const double expected = butterworth_gain(f, 0.1, 25.0, n);
      EXPECT_NEAR(gain_at(s, f, kDt), expected, 1e-6 * expected) << "order " << n << " at " << f << " Hz";
    }
  }
}

TEST(LabBandPass, RefusesABandOutsideNyquistOrAnImpossibleOrder) {
  EXPECT_THROW(butterworth_bandpass(0.1, 400.0, 4, kDt), std::invalid_argument);
  EXPECT_THROW(butterworth_bandpass(5.0, 1.0, 4, kDt), std::invalid_argument);
  EXPECT_THROW(butterworth_bandpass(0.0, 1.0, 4, kDt), std::invalid_argument);
  EXPECT_THROW(butterworth_bandpass(0.1, 25.0, 0, kDt), std::invalid_argument);
  EXPECT_THROW(filtfilt(butterworth_bandpass(0.1, 25.0, 4, kDt), std::vector<double>(27, 1.0)), std::invalid_argument);
}

// |H_lp|^2 + |H_hp|^2 = 1 for Butterworth filters of one order and corner: 1 / (1 + x^2n) and
// x^2n / (1 + x^2n), x = tan(pi f dt) / tan(pi fc dt)
TEST(LabMerge, ASignalBothChannelsShareIsKeptAndEachChannelOnlyCountsOnItsSide) {
  const double fc = 2.0;
  for (double f : {0.5, 2.0, 6.0}) {
    const std::vector<double> x = tapered_sine(f, 1.0, 40.0);
    EXPECT_LT(middle_error(merge_complementary(x, x, fc, 4, kDt), x), 1e-3) << f << " Hz";
  }
  for (double f : {0.5, 1.0, 4.0, 8.0}) {
    const double r = std::tan(kPi * f * kDt) / std::tan(kPi * fc * kDt), hp = std::pow(r, 8) / (1 + std::pow(r, 8));
    const std::vector<double> x = tapered_sine(f, 1.0, 40.0), zero(x.size(), 0.0);
    const auto [s1, c1] = sine_fit(merge_complementary(zero, x, fc, 4, kDt), f);  // the high side alone
    EXPECT_NEAR(std::hypot(s1, c1), hp, 1e-3 * hp + 1e-5) << f << " Hz";
    const auto [s2, c2] = sine_fit(merge_complementary(x, zero, fc, 4, kDt), f);  // the low side alone
    EXPECT_NEAR(std::hypot(s2, c2), 1 - hp, 1e-3 * (1 - hp) + 1e-5) << f << " Hz";
  }
}

TEST(LabDifferentiation, TheSecondDifferenceOfASineIsMinusOmegaSquaredTimesIt) {
  const double f = 2.0, w = 2 * kPi * f, a = 0.01;
  const std::vector<double> x = sine(f, a, 5.0, 0.3);
  const std::vector<double> d = second_derivative(x, kDt);
  // the central difference's gain is (2 - 2 cos(w dt)) / dt^2 = w^2 (1 - (w dt)^2 / 12 + ...)
  const double gain = (2 - 2 * std::cos(w * kDt)) / (kDt * kDt);
  EXPECT_NEAR(gain / (w * w), 1.0, 1e-4);
  for (std::size_t i = 1; i + 1 < x.size(); ++i) ASSERT_NEAR(d[i], -gain * x[i], 1e-9 * w * w * a) << i;
  EXPECT_EQ(d.front(), d[1]);
  EXPECT_EQ(d.back(), d[d.size() - 2]);
}

TEST(LabDifferentiation, ADisplacementSineBecomesItsAccelerationThroughTheWholeChain) {
  const double f = 2.0, w = 2 * kPi * f, a = 0.01;
  const std::vector<double> x = sine(f, a, 60.0);
  const std::vector<double> acc = acceleration_from_displacement(x, kDt, LabProcessing{});
  std::vector<double> expected(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) expected[i] = -w * w * x[i];
  EXPECT_LT(middle_error(acc, expected), 1e-3 * w * w * a);
}

TEST(LabBaseline, EachBaselineRemovesThePolynomialItFits) {
  const std::size_t n = 1000;
  std::vector<double> c(n), line(n), cubic(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i) * kDt;
    c[i] = 3.0;
    line[i] = 3.0 - 2.0 * t;
    cubic[i] = 1.0 + t - 4.0 * t * t + 2.5 * t * t * t;
  }
  for (double v : remove_baseline(c, LabBaseline::mean)) EXPECT_NEAR(v, 0.0, 1e-12);
  for (double v : remove_baseline(line, LabBaseline::linear)) EXPECT_NEAR(v, 0.0, 1e-12);
  for (double v : remove_baseline(cubic, LabBaseline::polynomial, 3)) EXPECT_NEAR(v, 0.0, 1e-11);
  EXPECT_EQ(remove_baseline(line, LabBaseline::none), line);
}

}  // namespace
