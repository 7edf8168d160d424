#pragma once
/// Orientation-independent ground-motion measures (physics.md §5): GMRotDpp and GMRotIpp of
/// Boore, Watson-Lazier & Abrahamson (2006), RotDpp of Boore (2010), and 5%-damped response
/// spectra by the exact piecewise-linear recursion of Nigam & Jennings (1969).
///
/// Conventions (documented choices where implementations differ, physics.md §5):
/// - Rotated pair at angle theta: a1' = a1 cos(theta) + a2 sin(theta),
///   a2' = -a1 sin(theta) + a2 cos(theta) (projection on axes turned by theta).
/// - GMRotD uses theta = 0, 1, ..., 89 deg (90 angles, Boore 2006); RotD uses 0..179 deg.
/// - Percentiles interpolate linearly between order statistics (np.percentile default), so the
///   median of the 90 GMRotD values is the mean of the 45th and 46th smallest.
/// - GMRotI: theta* minimises the penalty (1/N) sum_m [GM_m(theta)/GMRotDpp_m - 1]^2 over the
///   measures m in use (by default PGA and PGV; optionally oscillator periods too); ties go to
///   the smallest angle.
#include <string>
#include <vector>

#include "rigid/motion/ground_motion.hpp"

namespace rigid::motion {

/// Percentile pp (0..100) of values with linear interpolation between order statistics
/// (rank (pp/100)*(n-1)); NaN for an empty list.
double percentile(std::vector<double> values, double pp);

/// Peak |a1 cos(theta) + a2 sin(theta)| for theta = k*180/n_angles deg, k = 0..n_angles-1.
/// Equal lengths required (the shorter length is used otherwise).
std::vector<double> rotated_peaks(const std::vector<double>& a1, const std::vector<double>& a2, int n_angles = 180);

/// Geometric means GM(theta) = sqrt(peak|a1'| * peak|a2'|) for theta = 0..89 deg (90 values).
std::vector<double> gmrot_by_angle(const std::vector<double>& a1, const std::vector<double>& a2);

/// GMRotDpp of a pair: percentile pp of gmrot_by_angle (same unit as the input).
double gmrotd(const std::vector<double>& a1, const std::vector<double>& a2, double pp = 50.0);

/// RotDpp of a pair (Boore 2010): percentile pp over theta = 0..179 deg of the peak of the
/// single rotated component; RotD100 = maximum over directions.
double rotd(const std::vector<double>& a1, const std::vector<double>& a2, double pp = 50.0);

/// GMRotIpp over several measures (each one a pair of series, e.g. acceleration, velocity or
/// oscillator responses): the single angle theta* and each measure's GM(theta*).
struct GmRotI {
  double angle_deg = 0.0;      ///< theta* (unit: deg, 0..89)
  std::vector<double> values;  ///< GM_m(theta*) per measure (units of the inputs)
  std::vector<double> gmrotd;  ///< GMRotDpp per measure, for reference
  double penalty = 0.0;        ///< penalty at theta* (unit: 1)
};
GmRotI gmroti(const std::vector<std::pair<const std::vector<double>*, const std::vector<double>*>>& measures,
              double pp = 50.0);

/// Relative displacement u and velocity v of a damped SDOF oscillator (natural period T > 0,
/// damping ratio zeta in [0,1)) under ground acceleration acc: u'' + 2 zeta w u' + w^2 u = -acc,
/// from rest. Nigam & Jennings (1969) recursion, exact for acceleration linear between samples.
struct SdofResponse {
  std::vector<double> u;  ///< relative displacement (unit: m)
  std::vector<double> v;  ///< relative velocity (unit: m/s)
};
SdofResponse sdof_response(const std::vector<double>& acc, double dt, double period, double zeta = 0.05);

/// Pseudo-spectral acceleration PSA(T) = (2 pi/T)^2 max|u| (unit: m/s^2) for each period
/// (unit: s); a period <= 0 gives the PGA.
std::vector<double> response_spectrum(const std::vector<double>& acc, double dt, const std::vector<double>& periods,
                                      double zeta = 0.05);

/// Options for the orientation-independent measures of a motion.
struct MeasureOptions {
  Baseline baseline = Baseline::none;  ///< integration to velocity
  /// Oscillator periods (unit: s) added to the GMRotI penalty beside PGA and PGV (Boore 2006
  /// used a band of periods; empty = PGA and PGV only, the measures the fragilities use).
  std::vector<double> gmroti_periods;
  /// Include PGA and PGV in the GMRotI penalty (false: oscillator periods only, as in Boore et
  /// al. 2006 where PGA and PGV take the angle chosen over the spectral band).
  bool gmroti_use_peaks = true;
  double zeta = 0.05;  ///< damping ratio of those oscillators
};

/// Orientation-independent PGA and PGV of the two horizontals of a motion.
struct HorizontalMeasures {
  double gmrotd50_pga = 0.0;        ///< unit: m/s^2
  double gmrotd50_pgv = 0.0;        ///< unit: m/s
  double gmroti50_pga = 0.0;        ///< unit: m/s^2
  double gmroti50_pgv = 0.0;        ///< unit: m/s
  double gmroti50_angle_deg = 0.0;  ///< theta* (unit: deg)
  double rotd50_pga = 0.0;          ///< unit: m/s^2
  double rotd100_pga = 0.0;         ///< unit: m/s^2
  double rotd50_pgv = 0.0;          ///< unit: m/s
  double rotd100_pgv = 0.0;         ///< unit: m/s
};

/// Measures of the x/y pair; throws InputError if the motion lacks a second horizontal.
HorizontalMeasures horizontal_measures(const GroundMotion& m, const MeasureOptions& options = {});

/// Summary of one motion, as `rigid motion info` prints it.
struct MotionInfo {
  struct Axis {
    char axis = 'x';
    std::string label;
    Peaks peaks;  ///< SI
  };
  struct SpectralValue {
    double period = 0.0;                  ///< unit: s
    std::vector<double> per_axis;         ///< PSA per axis (unit: m/s^2)
    double gmrotd50 = 0.0, rotd50 = 0.0;  ///< unit: m/s^2 (two horizontals only)
  };
  std::string name;
  std::vector<std::string> sources;
  std::string alignment;  ///< GroundMotion::alignment ("" when the components matched)
  std::size_t npts = 0;
  double dt = 0.0;        ///< unit: s
  double duration = 0.0;  ///< unit: s
  std::vector<Axis> axes;
  bool two_horizontals = false;
  HorizontalMeasures horizontal;  ///< valid if two_horizontals
  double pgv_pga = 0.0;           ///< GMRotI50 PGV / GMRotI50 PGA (one horizontal: PGV/PGA of x) (unit: s)
  std::vector<SpectralValue> spectrum;
};

/// Computes the summary; spectral values for each of sa_periods (unit: s).
MotionInfo motion_info(const GroundMotion& m, const MeasureOptions& options = {},
                       const std::vector<double>& sa_periods = {});

/// Human-readable multi-line summary (ends with a newline).
std::string to_text(const MotionInfo& info);

}  // namespace rigid::motion
