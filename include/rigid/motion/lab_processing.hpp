#pragma once
/// Processing of raw laboratory (shake-table) signals into a ground acceleration: baseline
/// correction, a zero-phase Butterworth band-pass, and double differentiation of a displacement
/// channel. No file I/O here (rigid::io reads the recordings, io/lab_recording.hpp).
///
/// The band-pass is designed in double precision as scipy.signal.butter designs it
/// (motion/butterworth.hpp), applied forward then backward exactly as scipy.signal.sosfiltfilt
/// does with its defaults (padtype "odd", padlen 3 (2 n_sections + 1), each pass started from the
/// sections' steady state scaled by its first sample), so that scipy checks the whole chain.
#include <array>
#include <string>
#include <vector>

#include "rigid/motion/butterworth.hpp"

namespace rigid::motion {

/// What is subtracted from a raw signal before filtering.
enum class LabBaseline {
  none,       ///< nothing
  mean,       ///< the mean (the default: a constant offset of the transducer)
  linear,     ///< the least-squares line a + b t (an offset and a drift)
  polynomial  ///< the least-squares polynomial of LabProcessing::baseline_degree
};

/// The lab signal processing options (defaults: mean removed, band-pass 0.1-25 Hz, order 4).
struct LabProcessing {
  LabBaseline baseline = LabBaseline::mean;
  int baseline_degree = 2;  ///< degree of the `polynomial` baseline, 0..10
  bool band_pass = true;    ///< false: no filter (the signal is used as recorded, baseline removed)
  double low_hz = 0.1;      ///< lower corner (unit: Hz), -3 dB of the one-way filter, > 0
  double high_hz = 25.0;    ///< upper corner (unit: Hz), > low_hz, < Nyquist
  int order = 4;            ///< Butterworth order of the low-pass prototype, 1..8 (band-pass: 2 order poles)
  /// The combined channel's crossover (unit: Hz), inside the band: the displacement below it,
  /// the accelerometer above it (merge_complementary, same order as the band-pass)
  double crossover_hz = 2.0;
};

/// filtfilt(low-pass, low) + filtfilt(high-pass, high) at one corner and order. Zero-phase
/// Butterworth filters of one order and corner are power complementary, |H_lp|^2 + |H_hp|^2 = 1 at
/// every frequency, so what both inputs share passes unchanged and each input contributes only
/// on its side of the crossover. Inputs of equal length.
std::vector<double> merge_complementary(const std::vector<double>& low, const std::vector<double>& high,
                                        double crossover_hz, int order, double dt);

/// |H(f)| of the cascade at frequency f (unit: Hz) for time step dt (one pass; the
/// forward-backward filter has |H|^2).
double gain_at(const std::vector<Biquad>& sections, double f_hz, double dt);

/// One causal pass of the cascade (transposed direct form II, double precision) from the given
/// initial state (2 values per section; empty = at rest).
std::vector<double> sos_filter(const std::vector<Biquad>& sections, const std::vector<double>& x,
                               const std::vector<std::array<double, 2>>& state = {});

/// Zero-phase filtering, scipy.signal.sosfiltfilt with its defaults: the signal is extended at
/// each end by padlen = 3 (2 sections + 1 - m) samples, m the smaller of the numbers of sections
/// with b2 = 0 and with a2 = 0, of odd reflection (2 x[0] - x[padlen..1] before,
/// 2 x[n-1] - x[n-2..n-1-padlen] after), filtered forward from the steady-state section states
/// (scipy.signal.sosfilt_zi) times the first extended sample, reversed, filtered again from the
/// steady state times its first sample, reversed, and the padding removed. Throws
/// std::invalid_argument if the signal has padlen samples or fewer.
std::vector<double> filtfilt(const std::vector<Biquad>& sections, const std::vector<double>& x);

/// The signal minus its baseline (least squares over t = i dt; polynomial degree `degree` when
/// kind is polynomial), solved with Eigen's column-pivoting QR on a scaled time.
std::vector<double> remove_baseline(const std::vector<double>& x, LabBaseline kind, int degree = 2);

/// Second derivative by central differences, (x[i+1] - 2 x[i] + x[i-1]) / dt^2, exact for a
/// quadratic; the first and last samples take their neighbour's value. At frequency f the
/// operator's gain is (2 - 2 cos(2 pi f dt)) / dt^2 instead of (2 pi f)^2: 0.3 % low at 25 Hz
/// and 800 Hz sampling.
std::vector<double> second_derivative(const std::vector<double>& x, double dt);

/// Baseline then band-pass (when enabled) of an acceleration series (any unit; the result has it).
std::vector<double> process_acceleration(const std::vector<double>& acc, double dt, const LabProcessing& p);

/// The acceleration of a displacement series: baseline, band-pass (when enabled), then
/// second_derivative (unit: the displacement's per s^2). Filtering first keeps the
/// differentiation's amplification of high-frequency transducer noise out of the band.
std::vector<double> acceleration_from_displacement(const std::vector<double>& disp, double dt, const LabProcessing& p);

/// "none", "mean", "linear", "polynomial".
const char* lab_baseline_name(LabBaseline b);

}  // namespace rigid::motion
