#pragma once
/// Three-component ground motions in SI units and the operations a campaign applies to them:
/// alignment of components, time windows, scaling, rotation about z, resampling, integration to
/// velocity and displacement, and the ground-velocity series that drives the DEM pedestal.
/// No file I/O here (rigid::io reads and writes AT2 files).
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rigid::motion {

/// One recorded or synthetic acceleration component.
struct Component {
  std::vector<double> acc;  ///< ground acceleration (unit: m/s^2), sample i at t = i*dt
  double dt = 0.0;          ///< time step (unit: s), > 0
  std::string label;        ///< component label as written in the source (e.g. "N", "090", "UP")
};

/// A ground motion: one or two horizontal components and an optional vertical one, all sharing
/// one time step and one length. x is the first horizontal (H1), y the second (H2), z vertical
/// (positive up). Absent components are empty vectors with has_y/has_z false.
struct GroundMotion {
  std::string name;       ///< set name (e.g. "CHY028" or the first file's stem)
  double dt = 0.0;        ///< time step (unit: s)
  std::vector<double> x;  ///< H1 acceleration (unit: m/s^2)
  std::vector<double> y;  ///< H2 acceleration (unit: m/s^2), empty unless has_y
  std::vector<double> z;  ///< vertical acceleration (unit: m/s^2), empty unless has_z
  bool has_y = false;
  bool has_z = false;
  std::string label_x, label_y, label_z;  ///< component labels from the sources
  std::vector<std::string> sources;       ///< source files or generator description, x,y,z order
  /// How the components were aligned to a common length, "" when they matched: e.g.
  /// "H2 zero-padded by 12 samples (0.24 s)" (make_ground_motion)
  std::string alignment;

  /// Number of samples (of every component).
  std::size_t npts() const { return x.size(); }
  /// Duration (npts-1)*dt (unit: s); 0 for fewer than two samples.
  double duration() const { return x.size() < 2 ? 0.0 : double(x.size() - 1) * dt; }
};

/// Components of equal dt differing in length by up to this fraction of the longest are
/// zero-padded without being asked (records end in quiet; 1 % of a 40 s record is 0.4 s).
inline constexpr double kAutoPadFraction = 0.01;

/// What to do with components of unequal time step or length.
struct AlignOptions {
  /// false: unequal dt or npts is an InputError. true: resample every component (linear
  /// interpolation) to a common dt and pad the shorter ones with zeros at the end.
  bool resample = false;
  /// Common time step when resampling (unit: s); 0 = the smallest dt of the components.
  double dt = 0.0;
};

/// The largest ground acceleration a drive may reach (unit: g). The strongest recorded peaks are
/// near 4 g; beyond 50 g a record, a lab recording or a scale is a unit or scale mistake, and a
/// simulation of it would answer "survived" or "overturned" about nothing physical.
inline constexpr double kMaxDriveAccelerationG = 50.0;

/// The one rule for a sample of a ground drive (a read record, a processed lab recording, a
/// scaled motion): "" when the acceleration a (unit: m/s^2) may be one; otherwise why not: "not
/// a finite number" or "beyond 50 g, more than any ground motion (a unit or scale mistake?)" (the
/// caller names the value, in the units its user knows).
std::string drive_sample_problem(double a);

/// A sample that drive_sample_problem refuses: its component ('x', 'y', 'z'), index and problem.
struct BadDriveSample {
  char axis = 'x';
  std::size_t index = 0;
  std::string problem;
};

/// The first sample (lowest index; x, y, z at one index) of the motion times `factor` that
/// drive_sample_problem refuses; nothing when every sample may drive a pedestal.
std::optional<BadDriveSample> first_bad_drive_sample(const GroundMotion& m, double factor = 1.0);

/// Builds a GroundMotion from 1, 2 or 3 components in the order H1, H2, V.
/// Throws rigid::InputError (naming `name`) for 0 or more than 3 components, empty components,
/// non-positive dt, or (unless options.resample) unequal dt (relative difference > 1e-9) or npts
/// differing by more than kAutoPadFraction of the longest. Components of equal dt whose lengths
/// differ by less (real NGA pairs often differ by a few samples) are zero-padded at the end to the
/// longest, and `alignment` says so.
GroundMotion make_ground_motion(std::string name, std::vector<Component> components, const AlignOptions& options = {});

/// Linear interpolation of a series sampled at dt_in onto dt_out; the result covers
/// [0, (n-1)*dt_in] (last sample at or before the end). Exact for piecewise-linear input.
std::vector<double> resample_linear(const std::vector<double>& a, double dt_in, double dt_out);

/// Returns the motion resampled to dt_out (unit: s) by linear interpolation.
GroundMotion resampled(const GroundMotion& m, double dt_out);

/// The samples with start <= t <= end (unit: s, t measured from the first sample; a tolerance of
/// 1e-6*dt absorbs decimal round-off); the window's first sample becomes t = 0. An end past the
/// record is clamped to the last sample. Throws InputError if start < 0, end <= start or the
/// window holds fewer than 2 samples.
GroundMotion windowed(const GroundMotion& m, double start, double end);

/// All components multiplied by factor (unit: 1).
GroundMotion scaled(const GroundMotion& m, double factor);

/// Horizontal components rotated about z by angle (unit: rad), counter-clockwise seen from
/// above (x toward y): x' = x cos(angle) - y sin(angle), y' = x sin(angle) + y cos(angle); the
/// ground-motion vector is turned, the axes stay. A one-horizontal motion gains a y component
/// (y = 0 before rotation). z is unchanged.
GroundMotion rotated(const GroundMotion& m, double angle);

/// Baseline correction applied when integrating (physics.md §6). PEER-processed records are
/// already filtered and baseline-corrected, so `none` is the default and the one the GMRotI
/// table comparison uses.
enum class Baseline {
  none,               ///< plain trapezoid integration
  velocity_linear,    ///< subtract the least-squares line c1*t (through v(0)=0) from velocity
  velocity_quadratic  ///< subtract the least-squares c1*t + c2*t^2 (through v(0)=0) from velocity
};

/// Cumulative trapezoid integral with out[0] = 0: out[i] = out[i-1] + dt/2 (f[i-1] + f[i]).
std::vector<double> integrate_trapezoid(const std::vector<double>& f, double dt);

/// Acceleration, velocity and displacement of one component after a baseline correction.
struct Kinematics {
  std::vector<double> acc;   ///< corrected acceleration (unit: m/s^2)
  std::vector<double> vel;   ///< velocity (unit: m/s), vel[0] = 0
  std::vector<double> disp;  ///< displacement (unit: m), disp[0] = 0
};

/// Integrates acc (unit: m/s^2) twice by the trapezoid rule. With a velocity baseline, the
/// fitted polynomial p(t) (p(0) = 0) is removed from the velocity and p'(t) from the
/// acceleration, so the returned acc, vel and disp stay consistent under the trapezoid rule.
Kinematics integrate(const std::vector<double>& acc, double dt, Baseline baseline = Baseline::none);

/// max |a_i|; 0 for an empty series.
double peak_abs(const std::vector<double>& a);

/// Peak values of one component.
struct Peaks {
  double pga = 0.0;  ///< peak |acceleration| (unit: m/s^2)
  double pgv = 0.0;  ///< peak |velocity| (unit: m/s)
  double pgd = 0.0;  ///< peak |displacement| (unit: m)
};

/// PGA, PGV and PGD of one acceleration series (trapezoid integration, optional baseline).
Peaks peaks(const std::vector<double>& acc, double dt, Baseline baseline = Baseline::none);

/// Ground velocity of all three axes, the series the DEM drives its pedestal with.
struct GroundVelocity {
  double dt = 0.0;                 ///< time step (unit: s)
  std::vector<double> vx, vy, vz;  ///< velocity (unit: m/s), each npts long (zeros if absent)
};

/// Trapezoid-integrated velocity of every component (absent components give zeros), v(0) = 0.
GroundVelocity ground_velocity(const GroundMotion& m, Baseline baseline = Baseline::none);

/// The transformation a campaign case applies to its record, in this order: window, scale
/// (by factor, times target_pga_factor when target_pga_g > 0), rotate.
struct MotionTransform {
  double start = 0.0;                                    ///< window start (unit: s)
  double end = std::numeric_limits<double>::infinity();  ///< window end (unit: s), inf = to end
  double factor = 1.0;        ///< scale factor (unit: 1), applied on top of the target scaling
  double target_pga_g = 0.0;  ///< if > 0: scale so the GMRotI50 PGA is this (unit: g)
  /// target_pga_factor(windowed motion, 1.0) if the caller has it (campaigns scale one record many
  /// times); 0 = computed here. The scale is this factor times target_pga_g either way.
  double pga_factor_per_g = 0.0;
  double rotation = 0.0;  ///< rotation about z (unit: rad), convention of rotated()
};

/// Applies a MotionTransform (window, then scaling, then rotation). Throws InputError (no file:
/// the caller names the scale) when a sample of the result breaks drive_sample_problem.
GroundMotion transformed(const GroundMotion& m, const MotionTransform& t);

/// Factor that makes the motion's GMRotI50 PGA (its PGA with one horizontal component) equal to
/// target_pga_g (unit: g): factor = target_pga_g * g / measure. Throws InputError if the motion
/// has zero horizontal acceleration or the target is not positive.
double target_pga_factor(const GroundMotion& m, double target_pga_g);

/// The motion with all three components scaled by target_pga_factor(m, target_pga_g), as the
/// study did (the vertical is scaled by the horizontal measure too).
GroundMotion scaled_to_pga(const GroundMotion& m, double target_pga_g);

}  // namespace rigid::motion
