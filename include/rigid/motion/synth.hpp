#pragma once
/// Synthetic ground motions: closed-form pulses and a seeded stochastic generator. Every
/// generator is deterministic: the same parameters (and seed) give bit-identical output on any
/// platform with IEEE doubles and the same libm (no std::normal_distribution, which is
/// implementation-defined).
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "rigid/motion/ground_motion.hpp"

namespace rigid::motion {

/// Explicitly seeded stream of standard normal deviates: std::mt19937_64 (whose output sequence
/// the C++ standard fixes) -> uniform doubles from the top 53 bits -> Box-Muller transform.
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed);
  /// Next N(0,1) deviate.
  double next();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// Shape of a closed-form acceleration pulse.
enum class PulseKind {
  one_sine,    ///< a(t) = A sin(2 pi (t-t0)/Tp) for t0 <= t <= t0+Tp, else 0
  one_cosine,  ///< a(t) = A cos(2 pi (t-t0)/Tp) for t0 <= t <= t0+Tp, else 0
  ricker       ///< a(t) = A (1 - 2 pi^2 f^2 s^2) exp(-pi^2 f^2 s^2), s = t-t0-1.5 Tp, f = 1/Tp
};

/// Parameters of a pulse record; one horizontal (x) unless azimuth is set.
struct PulseParams {
  PulseKind kind = PulseKind::one_sine;
  double amplitude_g = 1.0;      ///< A (unit: g)
  double period = 0.5;           ///< Tp (unit: s), > 0
  double t0 = 0.0;               ///< start delay (unit: s), >= 0
  double duration = 0.0;         ///< record length (unit: s); 0 = t0 + pulse length + 2 Tp of quiet
  double dt = 0.005;             ///< time step (unit: s)
  bool two_horizontals = false;  ///< if true, split along azimuth_deg into x and y
  double azimuth_deg = 0.0;      ///< pulse direction from x toward y (unit: deg)
};

/// Closed-form pulse acceleration at time t (unit: m/s^2).
double pulse_acceleration(const PulseParams& p, double t);

/// Samples a pulse into a GroundMotion named `name`. A sample that falls on an interior jump of
/// the one-cosine pulse takes the mean of the two one-sided values (trapezoid integration then
/// returns to rest). Throws InputError for bad parameters.
GroundMotion pulse_motion(const std::string& name, const PulseParams& p);

/// Mavroeidis & Papageorgiou (2003) near-fault velocity pulse:
/// v(t) = A/2 [1 + cos(2 pi fp (t-t0)/gamma)] cos(2 pi fp (t-t0) + nu) for
/// |t - t0| <= gamma/(2 fp), else 0; acceleration is its analytic derivative.
struct MavroeidisParams {
  double pgv = 0.5;       ///< A, velocity amplitude (unit: m/s)
  double period = 1.0;    ///< Tp = 1/fp (unit: s)
  double gamma = 2.0;     ///< oscillatory character (unit: 1), > 1
  double nu_deg = 0.0;    ///< phase nu (unit: deg)
  double t0 = 0.0;        ///< pulse centre (unit: s); 0 = gamma Tp/2 + 1 s (starts at 1 s)
  double duration = 0.0;  ///< record length (unit: s); 0 = pulse end + 2 s
  double dt = 0.005;      ///< time step (unit: s)
  bool two_horizontals = false;
  double azimuth_deg = 0.0;  ///< pulse direction from x toward y (unit: deg)
};

/// M&P velocity (unit: m/s) and acceleration (unit: m/s^2) at time t.
double mavroeidis_velocity(const MavroeidisParams& p, double t);
double mavroeidis_acceleration(const MavroeidisParams& p, double t);

/// Samples the M&P acceleration into a GroundMotion. Throws InputError for bad parameters.
GroundMotion mavroeidis_motion(const std::string& name, const MavroeidisParams& p);

/// Rezaeian & Der Kiureghian (2008) site-based stochastic model: a gamma-shaped modulating
/// function q(t) = t^(a2-1) exp(-a3 t) times unit-variance filtered white noise, the filter a
/// damped oscillator with linearly varying frequency w(tau) = 2 pi (f_mid + f_slope (tau -
/// t_mid)) and damping zeta_f, normalised by its standard deviation; then the critically damped
/// high-pass oscillator of Rezaeian & Der Kiureghian (2010) (corner fc) so that velocity and
/// displacement return to zero; finally scaled so the PGA of each horizontal is pga_g.
struct StochasticParams {
  std::uint64_t seed = 1;
  double duration = 20.0;            ///< unit: s
  double dt = 0.01;                  ///< unit: s
  double pga_g = 0.3;                ///< target PGA of each horizontal component (unit: g)
  double t_peak = 5.0;               ///< time of the modulating function's peak (unit: s), > 0
  double shape = 3.0;                ///< a2 (unit: 1), > 1; a3 = (a2-1)/t_peak
  double f_mid = 5.0;                ///< filter frequency at t_mid = t_peak (unit: Hz)
  double f_slope = -0.1;             ///< filter frequency change per second (unit: Hz/s)
  double f_min = 0.3;                ///< lower bound on the filter frequency (unit: Hz)
  double zeta_f = 0.3;               ///< filter damping ratio (unit: 1), in (0,1)
  double fc = 0.2;                   ///< high-pass corner (unit: Hz); 0 = none
  int components = 3;                ///< 1 = x, 2 = x,y, 3 = x,y,z
  double vertical_ratio = 0.6;       ///< PGA of z relative to the horizontals (unit: 1)
  double vertical_freq_ratio = 1.5;  ///< f_mid of z relative to the horizontals (unit: 1)
};

/// Generates one stochastic record; each component uses its own sub-seed (seed, component).
/// Throws InputError for bad parameters (non-positive duration or dt, more than 2^22 samples).
GroundMotion stochastic_motion(const std::string& name, const StochasticParams& p);

}  // namespace rigid::motion
