// Lab signal processing (include/rigid/motion/lab_processing.hpp): the band-pass design is
// motion/butterworth.cpp's; the filtering, its padding and initial states follow
// scipy.signal.sosfiltfilt so that scipy is an independent check of the whole chain.
#include "rigid/motion/lab_processing.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "rigid/core/types.hpp"

namespace rigid::motion {

namespace {

// scipy.signal.lfilter_zi of one section: the state a unit step leaves it in at steady state
std::array<double, 2> steady_state(const Biquad& s) {
  const double r0 = s.b1 - s.a1 * s.b0, r1 = s.b2 - s.a2 * s.b0;
  const double z0 = (r0 + r1) / (1.0 + s.a1 + s.a2);
  return {z0, r1 - s.a2 * z0};
}

// scipy.signal.sosfilt_zi: each section's steady state under the DC gain of the ones before it
std::vector<std::array<double, 2>> cascade_steady_state(const std::vector<Biquad>& sections) {
  std::vector<std::array<double, 2>> zi;
  double scale = 1.0;
  for (const Biquad& s : sections) {
    const std::array<double, 2> z = steady_state(s);
    zi.push_back({scale * z[0], scale * z[1]});
    scale *= (s.b0 + s.b1 + s.b2) / (1.0 + s.a1 + s.a2);
  }
  return zi;
}

std::vector<std::array<double, 2>> scaled(std::vector<std::array<double, 2>> zi, double k) {
  for (auto& z : zi) z = {z[0] * k, z[1] * k};
  return zi;
}

}  // namespace

std::vector<double> merge_complementary(const std::vector<double>& low, const std::vector<double>& high,
                                        double crossover_hz, int order, double dt) {
  if (low.size() != high.size()) throw std::invalid_argument("the two channels differ in length");
  std::vector<double> out = filtfilt(butterworth_lowpass(crossover_hz, order, dt), low);
  const std::vector<double> h = filtfilt(butterworth_highpass(crossover_hz, order, dt), high);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] += h[i];
  return out;
}

double gain_at(const std::vector<Biquad>& sections, double f_hz, double dt) {
  const std::complex<double> z1 = std::polar(1.0, -2.0 * kPi * f_hz * dt);  // z^-1
  std::complex<double> h = 1.0;
  for (const Biquad& s : sections) h *= (s.b0 + s.b1 * z1 + s.b2 * z1 * z1) / (1.0 + s.a1 * z1 + s.a2 * z1 * z1);
  return std::abs(h);
}

std::vector<double> sos_filter(const std::vector<Biquad>& sections, const std::vector<double>& x,
                               const std::vector<std::array<double, 2>>& state) {
  std::vector<double> y = x;
  for (std::size_t k = 0; k < sections.size(); ++k) {
    const Biquad& s = sections[k];
    double z0 = k < state.size() ? state[k][0] : 0.0, z1 = k < state.size() ? state[k][1] : 0.0;
    for (double& v : y) {
      const double in = v;
      const double out = s.b0 * in + z0;
      z0 = s.b1 * in - s.a1 * out + z1;
      z1 = s.b2 * in - s.a2 * out;
      v = out;
    }
  }
  return y;
}

std::vector<double> filtfilt(const std::vector<Biquad>& sections, const std::vector<double>& x) {
  // scipy's padlen: 3 (2 sections + 1), less the smaller count of sections with b2 = 0 and with
  // a2 = 0 (an odd order's extra pole and zero at the origin may sit in different sections)
  std::size_t no_b2 = 0, no_a2 = 0;
  for (const Biquad& s : sections) {
    no_b2 += s.b2 == 0.0;
    no_a2 += s.a2 == 0.0;
  }
  const std::size_t pad = 3 * (2 * sections.size() + 1 - std::min(no_b2, no_a2));
  const std::size_t n = x.size();
  if (n <= pad)
    throw std::invalid_argument("the signal needs more than " + std::to_string(pad) +
                                " samples for the zero-phase filter");
  std::vector<double> ext;
  ext.reserve(n + 2 * pad);
  for (std::size_t i = pad; i >= 1; --i) ext.push_back(2.0 * x[0] - x[i]);
  ext.insert(ext.end(), x.begin(), x.end());
  for (std::size_t i = 1; i <= pad; ++i) ext.push_back(2.0 * x[n - 1] - x[n - 1 - i]);
  const auto zi = cascade_steady_state(sections);
  std::vector<double> y = sos_filter(sections, ext, scaled(zi, ext.front()));
  std::reverse(y.begin(), y.end());
  y = sos_filter(sections, y, scaled(zi, y.front()));
  std::reverse(y.begin(), y.end());
  return std::vector<double>(y.begin() + std::ptrdiff_t(pad), y.end() - std::ptrdiff_t(pad));
}

std::vector<double> remove_baseline(const std::vector<double>& x, LabBaseline kind, int degree) {
  if (kind == LabBaseline::none || x.empty()) return x;
  std::vector<double> out = x;
  if (kind == LabBaseline::mean) {
    double sum = 0;
    for (double v : x) sum += v;
    const double mean = sum / double(x.size());
    for (double& v : out) v -= mean;
    return out;
  }
  const int p = kind == LabBaseline::linear ? 1 : degree;
  if (p < 0 || p > 10) throw std::invalid_argument("the baseline degree must be 0 to 10");
  const Eigen::Index n = Eigen::Index(x.size()), cols = std::min<Eigen::Index>(p + 1, n);
  // time scaled to [-1, 1] keeps the Vandermonde columns of one size
  Eigen::MatrixXd v(n, cols);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = n > 1 ? 2.0 * double(i) / double(n - 1) - 1.0 : 0.0;
    double tk = 1.0;
    for (Eigen::Index k = 0; k < cols; ++k, tk *= t) v(i, k) = tk;
  }
  const Eigen::Map<const Eigen::VectorXd> y(x.data(), n);
  const Eigen::VectorXd c = v.colPivHouseholderQr().solve(y);
  const Eigen::VectorXd fit = v * c;
  for (Eigen::Index i = 0; i < n; ++i) out[std::size_t(i)] -= fit(i);
  return out;
}

std::vector<double> second_derivative(const std::vector<double>& x, double dt) {
  const std::size_t n = x.size();
  if (n < 3) throw std::invalid_argument("differentiation needs at least 3 samples");
  std::vector<double> d(n);
  const double inv = 1.0 / (dt * dt);
  for (std::size_t i = 1; i + 1 < n; ++i) d[i] = (x[i + 1] - 2.0 * x[i] + x[i - 1]) * inv;
  d[0] = d[1];
  d[n - 1] = d[n - 2];
  return d;
}

std::vector<double> process_acceleration(const std::vector<double>& acc, double dt, const LabProcessing& p) {
  std::vector<double> a = remove_baseline(acc, p.baseline, p.baseline_degree);
  if (p.band_pass) a = filtfilt(butterworth_bandpass(p.low_hz, p.high_hz, p.order, dt), a);
  return a;
}

std::vector<double> acceleration_from_displacement(const std::vector<double>& disp, double dt, const LabProcessing& p) {
  return second_derivative(process_acceleration(disp, dt, p), dt);
}

const char* lab_baseline_name(LabBaseline b) {
  switch (b) {
    case LabBaseline::none:
      return "none";
    case LabBaseline::mean:
      return "mean";
    case LabBaseline::linear:
      return "linear";
    case LabBaseline::polynomial:
      return "polynomial";
  }
  return "?";
}

}  // namespace rigid::motion
