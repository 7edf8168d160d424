// Synthetic motions: closed-form pulses and the Rezaeian & Der Kiureghian stochastic model.
#include "rigid/motion/synth.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rigid/core/error.hpp"
#include "rigid/core/rng.hpp"
#include "rigid/core/types.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::motion {

namespace {

constexpr std::size_t kMaxSamples = std::size_t(1) << 22;

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

void require(bool ok, const std::string& name, const std::string& what) {
  if (!ok) throw InputError(name, 0, what);
}

std::size_t sample_count(const std::string& name, double duration, double dt) {
  require(dt > 0.0 && std::isfinite(dt), name, "dt must be positive, got " + num(dt));
  require(duration > 0.0 && std::isfinite(duration), name, "duration must be positive, got " + num(duration));
  const double n = std::floor(duration / dt + 1e-9) + 1.0;
  require(n <= double(kMaxSamples), name, "too many samples (" + num(n) + " > " + std::to_string(kMaxSamples) + ")");
  return std::size_t(n);
}

// puts one horizontal series on x, or along an azimuth on x and y
GroundMotion directional(const std::string& name, std::vector<double> a, double dt, bool two, double azimuth_deg,
                         const std::string& source) {
  GroundMotion m;
  m.name = name;
  m.dt = dt;
  m.sources = {source};
  if (!two) {
    m.x = std::move(a);
    m.label_x.assign(1, 'X');
    return m;
  }
  const double th = azimuth_deg * kPi / 180.0;
  m.x.resize(a.size());
  m.y.resize(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    m.x[i] = a[i] * std::cos(th);
    m.y[i] = a[i] * std::sin(th);
  }
  m.has_y = true;
  m.label_x.assign(1, 'X');
  m.label_y.assign(1, 'Y');
  return m;
}

}  // namespace

NormalStream::NormalStream(std::uint64_t seed) : engine_(seed) {}

double NormalStream::next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Box-Muller on two 53-bit uniforms; u1 in (0, 1] keeps the log finite
  const double u1 = double((engine_() >> 11) + 1) * 0x1.0p-53;
  const double u2 = double(engine_() >> 11) * 0x1.0p-53;
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 2.0 * kPi * u2;
  spare_ = r * std::sin(a);
  has_spare_ = true;
  return r * std::cos(a);
}

double pulse_acceleration(const PulseParams& p, double t) {
  const double A = p.amplitude_g * kGravity;
  const double s = t - p.t0;
  switch (p.kind) {
    case PulseKind::one_sine:
      return (s >= 0.0 && s <= p.period) ? A * std::sin(2.0 * kPi * s / p.period) : 0.0;
    case PulseKind::one_cosine:
      return (s >= 0.0 && s <= p.period) ? A * std::cos(2.0 * kPi * s / p.period) : 0.0;
    case PulseKind::ricker: {
      const double f = 1.0 / p.period;
      const double x = kPi * f * (s - 1.5 * p.period);
      return A * (1.0 - 2.0 * x * x) * std::exp(-x * x);
    }
  }
  return 0.0;
}

GroundMotion pulse_motion(const std::string& name, const PulseParams& p) {
  require(p.period > 0.0 && std::isfinite(p.period), name, "pulse period must be positive");
  require(std::isfinite(p.amplitude_g), name, "pulse amplitude must be finite");
  require(p.t0 >= 0.0 && std::isfinite(p.t0), name, "pulse start must be >= 0");
  const double length = p.kind == PulseKind::ricker ? 3.0 * p.period : p.period;
  const double duration = p.duration > 0.0 ? p.duration : p.t0 + length + 2.0 * p.period;
  const std::size_t n = sample_count(name, duration, p.dt);
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i) * p.dt;
    a[i] = pulse_acceleration(p, t);
    // a sample on an interior jump of the one-cosine pulse takes the mean of the one-sided
    // limits, so trapezoid integration keeps v and d of the closed form (no O(dt) drift)
    const double tol = 1e-6 * p.dt;
    if (p.kind == PulseKind::one_cosine && t > tol && (std::abs(t - p.t0) < tol || std::abs(t - p.t0 - p.period) < tol))
      a[i] *= 0.5;
  }
  const char* kind = p.kind == PulseKind::one_sine     ? "one-sine"
                     : p.kind == PulseKind::one_cosine ? "one-cosine"
                                                       : "Ricker";
  return directional(
      name, std::move(a), p.dt, p.two_horizontals, p.azimuth_deg,
      std::string(kind) + " pulse, amplitude " + num(p.amplitude_g) + " g, period " + num(p.period) + " s");
}

namespace {

double mp_t0(const MavroeidisParams& p) { return p.t0 > 0.0 ? p.t0 : 0.5 * p.gamma * p.period + 1.0; }

}  // namespace

double mavroeidis_velocity(const MavroeidisParams& p, double t) {
  const double fp = 1.0 / p.period;
  const double s = t - mp_t0(p);
  if (std::abs(s) > p.gamma / (2.0 * fp)) return 0.0;
  const double nu = p.nu_deg * kPi / 180.0;
  return 0.5 * p.pgv * (1.0 + std::cos(2.0 * kPi * fp * s / p.gamma)) * std::cos(2.0 * kPi * fp * s + nu);
}

double mavroeidis_acceleration(const MavroeidisParams& p, double t) {
  // analytic derivative of mavroeidis_velocity (Mavroeidis & Papageorgiou 2003, eq. for a(t))
  const double fp = 1.0 / p.period;
  const double s = t - mp_t0(p);
  if (std::abs(s) > p.gamma / (2.0 * fp)) return 0.0;
  const double nu = p.nu_deg * kPi / 180.0;
  const double W = 2.0 * kPi * fp;
  return -0.5 * p.pgv * W *
         (std::sin(W * s / p.gamma) * std::cos(W * s + nu) / p.gamma +
          (1.0 + std::cos(W * s / p.gamma)) * std::sin(W * s + nu));
}

GroundMotion mavroeidis_motion(const std::string& name, const MavroeidisParams& p) {
  require(p.period > 0.0 && std::isfinite(p.period), name, "pulse period must be positive");
  require(p.gamma > 1.0 && std::isfinite(p.gamma), name, "gamma must be > 1");
  require(std::isfinite(p.pgv) && std::isfinite(p.nu_deg), name, "pgv and nu must be finite");
  require(p.t0 >= 0.0 && std::isfinite(p.t0), name, "pulse centre must be >= 0");
  const double end = mp_t0(p) + 0.5 * p.gamma * p.period;
  const double duration = p.duration > 0.0 ? p.duration : end + 2.0;
  const std::size_t n = sample_count(name, duration, p.dt);
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = mavroeidis_acceleration(p, double(i) * p.dt);
  return directional(name, std::move(a), p.dt, p.two_horizontals, p.azimuth_deg,
                     "Mavroeidis-Papageorgiou pulse, A " + num(p.pgv) + " m/s, Tp " + num(p.period) + " s, gamma " +
                         num(p.gamma) + ", nu " + num(p.nu_deg) + " deg");
}

namespace {

// one component of the RD08 model before scaling (unit: arbitrary)
std::vector<double> rd_component(const StochasticParams& p, std::size_t n, double f_mid, std::uint64_t seed) {
  NormalStream noise(seed);
  std::vector<double> u(n);
  for (double& v : u) v = noise.next();
  const double a3 = (p.shape - 1.0) / p.t_peak;
  const double zf = p.zeta_f;
  const double sq = std::sqrt(1.0 - zf * zf);
  // filter parameters at each pulse time tau_j (RD08: the filter is evaluated at tau)
  std::vector<double> w(n), decay_len(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double f = std::max(p.f_min, f_mid + p.f_slope * (double(j) * p.dt - p.t_peak));
    w[j] = 2.0 * kPi * f;
  }
  // impulse responses decay as exp(-zeta w s); beyond exp(-25) they are dropped
  const double w_min = 2.0 * kPi * p.f_min;
  const std::size_t reach = std::min<std::size_t>(n, std::size_t(std::ceil(25.0 / (zf * w_min) / p.dt)) + 1);
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double t = double(i) * p.dt;
    double x = 0.0, var = 0.0;
    const std::size_t j0 = i >= reach ? i - reach + 1 : 0;
    for (std::size_t j = j0; j <= i; ++j) {
      const double s = t - double(j) * p.dt;
      const double h = w[j] / sq * std::exp(-zf * w[j] * s) * std::sin(w[j] * sq * s);
      x += h * u[j];
      var += h * h;
    }
    const double q = std::pow(t, p.shape - 1.0) * std::exp(-a3 * t);
    a[i] = var > 0.0 ? q * x / std::sqrt(var) : 0.0;
  }
  if (p.fc > 0.0) {
    // RD10 high-pass: y'' + 2 wc y' + wc^2 y = a (critically damped; zeta 0.999 keeps the
    // exact under-damped recursion usable); the output is y'' = a - 2 zeta wc y' - wc^2 y,
    // whose velocity and displacement return to rest. sdof_response solves for u = -y.
    const double zc = 0.999;
    const double wc = 2.0 * kPi * p.fc;
    const SdofResponse r = sdof_response(a, p.dt, 1.0 / p.fc, zc);
    for (std::size_t i = 0; i < n; ++i) a[i] += 2.0 * zc * wc * r.v[i] + wc * wc * r.u[i];
  }
  return a;
}

}  // namespace

GroundMotion stochastic_motion(const std::string& name, const StochasticParams& p) {
  const std::size_t n = sample_count(name, p.duration, p.dt);
  require(p.components >= 1 && p.components <= 3, name, "components must be 1, 2 or 3");
  require(p.t_peak > 0.0 && std::isfinite(p.t_peak), name, "t_peak must be positive");
  require(p.shape > 1.0 && std::isfinite(p.shape), name, "shape must be > 1");
  require(p.zeta_f > 0.0 && p.zeta_f < 1.0, name, "zeta_f must be in (0, 1)");
  require(p.f_min > 0.0 && std::isfinite(p.f_min), name, "f_min must be positive");
  require(std::isfinite(p.f_mid) && std::isfinite(p.f_slope), name, "f_mid, f_slope finite");
  require(p.fc >= 0.0 && std::isfinite(p.fc), name, "fc must be >= 0");
  require(p.pga_g > 0.0 && std::isfinite(p.pga_g), name, "pga must be positive");
  require(p.vertical_ratio >= 0.0 && std::isfinite(p.vertical_ratio) && p.vertical_freq_ratio > 0.0 &&
              std::isfinite(p.vertical_freq_ratio),
          name, "vertical ratios must be >= 0");
  // bound the O(n * reach) work so no parameter set can hang the generator
  const double reach = std::min(double(n), 25.0 / (p.zeta_f * 2.0 * kPi * p.f_min) / p.dt);
  require(double(n) * reach < 2e10, name, "record too long for the stochastic generator");

  GroundMotion m;
  m.name = name;
  m.dt = p.dt;
  std::ostringstream src;
  src << "Rezaeian-Der Kiureghian stochastic, seed " << p.seed << ", PGA " << p.pga_g << " g, f_mid " << p.f_mid
      << " Hz, f_slope " << p.f_slope << " Hz/s, zeta_f " << p.zeta_f << ", t_peak " << p.t_peak << " s, shape "
      << p.shape << ", fc " << p.fc << " Hz";
  for (int c = 0; c < p.components; ++c) {
    const bool vertical = c == 2;
    const double f = vertical ? p.f_mid * p.vertical_freq_ratio : p.f_mid;
    std::vector<double> a = rd_component(p, n, f, splitmix64(p.seed ^ splitmix64(std::uint64_t(c) + 1)));
    const double pk = peak_abs(a);
    const double target = (vertical ? p.vertical_ratio : 1.0) * p.pga_g * kGravity;
    for (double& v : a) v = pk > 0.0 ? v * target / pk : 0.0;
    if (c == 0) m.x = std::move(a), m.label_x.assign(1, 'X');
    if (c == 1) m.y = std::move(a), m.label_y.assign(1, 'Y'), m.has_y = true;
    if (c == 2) m.z = std::move(a), m.label_z.assign(1, 'Z'), m.has_z = true;
  }
  m.sources.assign(std::size_t(p.components), src.str());
  return m;
}

}  // namespace rigid::motion
