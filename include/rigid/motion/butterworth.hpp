#pragma once
/// Digital Butterworth filters as second-order sections, designed in double precision.
///
/// The design is the one scipy.signal.butter(N, Wn, btype, output="sos", fs=1/dt) computes, so
/// that its sections compare one to one with scipy's: the analog prototype's poles, the corners
/// prewarped for the bilinear transform, the analog low-pass to low-, high- or band-pass
/// transform of the poles and zeros, the bilinear transform of poles and zeros, then poles and
/// zeros grouped into sections by scipy.signal.zpk2sos's "nearest" pairing (sections ordered
/// from the poles farthest from the unit circle to the closest, the overall gain in the first).
/// Double precision matters: a 0.1 Hz corner at 800 Hz puts poles within 1e-3 of z = 1, where a
/// single-precision design lifts the pass band by ~1 % at 0.5 Hz.
#include <vector>

namespace rigid::motion {

/// One second-order section: y = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2) x.
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};

/// The Butterworth band-pass [low_hz, high_hz] (-3 dB corners of one pass) of the given prototype
/// order at time step dt (unit: s), as `order` second-order sections. Throws
/// std::invalid_argument unless 0 < low_hz < high_hz < 0.5/dt and 1 <= order <= 8.
std::vector<Biquad> butterworth_bandpass(double low_hz, double high_hz, int order, double dt);

/// Butterworth low-pass and high-pass of the given order at corner fc_hz, as ceil(order / 2)
/// sections. Throws std::invalid_argument unless 0 < fc_hz < 0.5/dt and 1 <= order <= 8.
std::vector<Biquad> butterworth_lowpass(double fc_hz, int order, double dt);
std::vector<Biquad> butterworth_highpass(double fc_hz, int order, double dt);

}  // namespace rigid::motion
