// Butterworth design in double precision (include/rigid/motion/butterworth.hpp). The steps are the
// textbook ones: the analog prototype, the analog frequency transformations s -> s/Wc, Wc/s and
// (s^2 + W0^2) / (B s), and the bilinear transform with prewarped corners (Oppenheim & Schafer,
// Discrete-Time Signal Processing, 3rd ed., sec. 7.2, for the bilinear transform; Parks & Burrus,
// Digital Filter Design, 1987, for the analog transformations). Each step works on poles and
// zeros rather than on polynomial coefficients, whose round-off would move the poles that a
// 0.1 Hz corner at 800 Hz puts next to z = 1.
#include "rigid/motion/butterworth.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>

#include "rigid/core/types.hpp"

namespace rigid::motion {

namespace {

using Complex = std::complex<double>;

// k prod(s - zeros) / prod(s - poles)
struct Zpk {
  std::vector<Complex> zeros, poles;
  double gain = 1.0;
};

// poles minus finite zeros: the zeros at infinity (a Butterworth prototype has only those)
std::size_t relative_degree(const Zpk& f) { return f.poles.size() - f.zeros.size(); }

// prod over the roots of (shift - root)
Complex product_of_differences(Complex shift, const std::vector<Complex>& roots) {
  Complex p = 1.0;
  for (Complex r : roots) p *= shift - r;
  return p;
}

// The order-n Butterworth low-pass of corner 1 rad/s: n poles evenly spaced on the left half of
// the unit circle, no finite zeros. m = 1-n, 3-n, ..., n-1 puts an odd order's middle pole exactly
// on the real axis.
Zpk analog_prototype(int n) {
  Zpk f;
  for (int m = 1 - n; m < n; m += 2) f.poles.push_back(-std::polar(1.0, kPi * m / (2.0 * n)));
  return f;
}

// The analog corner (rad/s) that the bilinear transform s = (2/dt) (z - 1) / (z + 1) maps onto
// the digital corner f_hz: the transform squeezes the whole analog axis into the Nyquist band
// through W = (2/dt) tan(pi f dt), so the corners are set on that curve beforehand.
double prewarped(double f_hz, double dt) { return 2.0 / dt * std::tan(kPi * f_hz * dt); }

// s -> s / wc: every root scaled by wc; the gain keeps the response at DC
Zpk to_lowpass(Zpk f, double wc) {
  for (Complex& z : f.zeros) z *= wc;
  for (Complex& p : f.poles) p *= wc;
  f.gain *= std::pow(wc, double(relative_degree(f)));
  return f;
}

// s -> wc / s: every root inverted and scaled; the zeros at infinity come to the origin; the gain
// keeps the high-frequency response equal to the prototype's at DC
Zpk to_highpass(Zpk f, double wc) {
  const std::size_t degree = relative_degree(f);
  f.gain *= (product_of_differences(0.0, f.zeros) / product_of_differences(0.0, f.poles)).real();
  for (Complex& z : f.zeros) z = wc / z;
  for (Complex& p : f.poles) p = wc / p;
  f.zeros.insert(f.zeros.end(), degree, Complex(0.0));
  return f;
}

// s -> (s^2 + w0^2) / (bw s): each root r becomes the two roots of s^2 - r bw s + w0^2, one above
// and one below the centre; of the prototype's zeros at infinity, half come to the origin
Zpk to_bandpass(const Zpk& f, double w0, double bw) {
  auto split = [&](const std::vector<Complex>& roots) {
    std::vector<Complex> upper, lower;
    for (Complex r : roots) {
      const Complex half = r * (bw / 2.0), offset = std::sqrt(half * half - w0 * w0);
      upper.push_back(half + offset);
      lower.push_back(half - offset);
    }
    upper.insert(upper.end(), lower.begin(), lower.end());
    return upper;
  };
  const std::size_t degree = relative_degree(f);
  Zpk g{split(f.zeros), split(f.poles), f.gain * std::pow(bw, double(degree))};
  g.zeros.insert(g.zeros.end(), degree, Complex(0.0));
  return g;
}

// s = (2/dt) (z - 1) / (z + 1): each root r goes to (c + r) / (c - r), c = 2/dt; the zeros at
// infinity go to the Nyquist frequency z = -1; the gain keeps the response at the mapped frequencies
Zpk bilinear(const Zpk& f, double dt) {
  const double c = 2.0 / dt;
  Zpk g;
  for (Complex z : f.zeros) g.zeros.push_back((c + z) / (c - z));
  for (Complex p : f.poles) g.poles.push_back((c + p) / (c - p));
  g.zeros.insert(g.zeros.end(), relative_degree(f), Complex(-1.0));
  g.gain = f.gain * (product_of_differences(c, f.zeros) / product_of_differences(c, f.poles)).real();
  return g;
}

bool is_real(Complex r) { return r.imag() == 0.0; }

// One root per conjugate pair (the one above the real axis, averaged with its partner so the
// pair is exactly conjugate), sorted by real part then imaginary part, followed by the real roots
// in increasing order. A root is real when its imaginary part is within 100 eps of its modulus,
// as scipy's zpk2sos decides it, so that both group the same roots.
std::vector<Complex> one_root_per_pair(const std::vector<Complex>& roots) {
  const double tol = 100.0 * std::numeric_limits<double>::epsilon();
  std::vector<Complex> upper, lower;
  std::vector<double> real;
  for (Complex r : roots) {
    if (std::abs(r.imag()) <= tol * std::abs(r))
      real.push_back(r.real());
    else
      (r.imag() > 0 ? upper : lower).push_back(r);
  }
  if (upper.size() != lower.size()) throw std::logic_error("Butterworth design: a complex root without its conjugate");
  std::sort(upper.begin(), upper.end(),
            [](Complex a, Complex b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  std::sort(real.begin(), real.end());
  std::vector<Complex> out;
  for (Complex u : upper) {
    auto partner = std::min_element(lower.begin(), lower.end(), [u](Complex a, Complex b) {
      return std::abs(u - std::conj(a)) < std::abs(u - std::conj(b));
    });
    out.push_back((u + std::conj(*partner)) / 2.0);
    lower.erase(partner);
  }
  for (double r : real) out.emplace_back(r, 0.0);
  return out;
}

constexpr std::size_t kNone = std::size_t(-1);

// The index of the root closest to the unit circle (the sharpest resonance), the first on a tie;
// real roots only when asked
std::size_t closest_to_unit_circle(const std::vector<Complex>& roots, bool real_only) {
  std::size_t best = kNone;
  for (std::size_t i = 0; i < roots.size(); ++i) {
    if (real_only && !is_real(roots[i])) continue;
    if (best == kNone || std::abs(1.0 - std::abs(roots[i])) < std::abs(1.0 - std::abs(roots[best]))) best = i;
  }
  return best;
}

// The index of the root nearest to `to`, the first on a tie; real roots only when asked
std::size_t nearest(const std::vector<Complex>& roots, Complex to, bool real_only) {
  std::size_t best = kNone;
  for (std::size_t i = 0; i < roots.size(); ++i) {
    if (real_only && !is_real(roots[i])) continue;
    if (best == kNone || std::abs(roots[i] - to) < std::abs(roots[best] - to)) best = i;
  }
  return best;
}

Complex take(std::vector<Complex>& roots, std::size_t i) {
  if (i == kNone) throw std::logic_error("Butterworth design: no root left to pair");
  const Complex r = roots[i];
  roots.erase(roots.begin() + std::ptrdiff_t(i));
  return r;
}

// (1 - z1 x)(1 - z2 x) / ((1 - p1 x)(1 - p2 x)), x = z^-1: each pair is conjugate or real, so the
// coefficients are real
Biquad section(Complex z1, Complex z2, Complex p1, Complex p2) {
  return {1.0, -(z1 + z2).real(), (z1 * z2).real(), -(p1 + p2).real(), (p1 * p2).real()};
}

// Poles and zeros grouped into second-order sections as scipy.signal.zpk2sos(pairing="nearest")
// groups them: the pole closest to the unit circle takes its conjugate (or the next real pole)
// and the zeros nearest to it, which keeps each section's peak gain low; sections are filled from
// the last, so the sharpest resonance is filtered last; the overall gain goes to the first.
std::vector<Biquad> to_sections(Zpk f) {
  // equal, even numbers of poles and zeros: the extra ones at the origin are z^-1 factors that
  // cancel
  if (f.poles.size() < f.zeros.size()) f.poles.resize(f.zeros.size(), Complex(0.0));
  if (f.zeros.size() < f.poles.size()) f.zeros.resize(f.poles.size(), Complex(0.0));
  if (f.poles.size() % 2 == 1) {
    f.poles.emplace_back(0.0);
    f.zeros.emplace_back(0.0);
  }
  std::vector<Complex> poles = one_root_per_pair(f.poles), zeros = one_root_per_pair(f.zeros);
  // an even number of real poles and of real zeros remains at every step (complex roots come in
  // pairs and the totals are even), so a real root always finds a real partner
  std::vector<Biquad> sections(f.poles.size() / 2);
  for (std::size_t s = sections.size(); s-- > 0;) {
    const Complex p1 = take(poles, closest_to_unit_circle(poles, false));
    const Complex p2 = is_real(p1) ? take(poles, closest_to_unit_circle(poles, true)) : std::conj(p1);
    const Complex z1 = take(zeros, nearest(zeros, p1, false));
    const Complex z2 = is_real(z1) ? take(zeros, nearest(zeros, p1, true)) : std::conj(z1);
    sections[s] = section(z1, z2, p1, p2);
  }
  Biquad& first = sections.front();
  first.b0 *= f.gain;
  first.b1 *= f.gain;
  first.b2 *= f.gain;
  return sections;
}

void check_step_and_order(double dt, int order) {
  if (!(dt > 0) || !std::isfinite(dt)) throw std::invalid_argument("the time step must be positive");
  if (order < 1 || order > 8) throw std::invalid_argument("the filter order must be 1 to 8");
}

void check_corner(double fc_hz, double dt) {
  if (!(fc_hz > 0) || !(fc_hz < 0.5 / dt))
    throw std::invalid_argument("the corner must lie in (0, Nyquist) (" + std::to_string(int(0.5 / dt)) + " Hz)");
}

}  // namespace

std::vector<Biquad> butterworth_bandpass(double low_hz, double high_hz, int order, double dt) {
  check_step_and_order(dt, order);
  const double nyquist = 0.5 / dt;
  if (!(low_hz > 0) || !(high_hz > low_hz) || !(high_hz < nyquist))
    throw std::invalid_argument("the band-pass needs 0 < low < high < Nyquist (" + std::to_string(int(nyquist)) +
                                " Hz at this time step)");
  // the band's geometric centre and width on the prewarped axis
  const double w1 = prewarped(low_hz, dt), w2 = prewarped(high_hz, dt);
  return to_sections(bilinear(to_bandpass(analog_prototype(order), std::sqrt(w1 * w2), w2 - w1), dt));
}

std::vector<Biquad> butterworth_lowpass(double fc_hz, int order, double dt) {
  check_step_and_order(dt, order);
  check_corner(fc_hz, dt);
  return to_sections(bilinear(to_lowpass(analog_prototype(order), prewarped(fc_hz, dt)), dt));
}

std::vector<Biquad> butterworth_highpass(double fc_hz, int order, double dt) {
  check_step_and_order(dt, order);
  check_corner(fc_hz, dt);
  return to_sections(bilinear(to_highpass(analog_prototype(order), prewarped(fc_hz, dt)), dt));
}

}  // namespace rigid::motion
