#pragma once
/// 2D rocking reference model (Housner 1963; physics.md §2): a rigid block rocking on a rigid base
/// about one of two base corners, no sliding and no free flight, one horizontal ground component,
/// impacts that conserve angular momentum about the new pivot. It is the oracle for the 3D engine
/// (the study's validation exercise, physics.md §11) and a selectable campaign model.
///
/// Sign convention (used everywhere in this header):
/// - x is the horizontal direction of the ground component; ü_g > 0 accelerates the ground
///   toward +x (unit: m/s^2).
/// - θ > 0 means the block rotates about its +x base corner (it tips toward +x); θ < 0 means it
///   rotates about its −x corner. θ = 0 is the block standing flat on its base.
/// - Equation of motion (physics.md §2), with s = sgn θ the active pivot:
///   θ̈ = −p² [ sin(α s − θ) + (ü_g/g) cos(α s − θ) ].
///   A ground acceleration toward −x (ü_g < 0) throws the block's inertia toward +x and makes θ
///   grow positive; from rest the block lifts toward θ > 0 when ü_g < −g tanα and toward θ < 0
///   when ü_g > g tanα (the quasi-static uplift condition). Below that it moves with the ground.
/// - The equation is invariant under (θ, ü_g) → (−θ, −ü_g): a motion and its mirror image give
///   mirrored responses, so the polarity of a pulse never changes whether the block overturns.
///
/// The engine core does no I/O: nothing here prints or reads files.
#include <functional>
#include <limits>
#include <span>
#include <vector>

namespace rigid::rocking {

/// The four numbers that define a symmetric 2D rocking block (physics.md §2). The block is assumed
/// symmetric: both base corners have the same α and R, so one restitution applies to every impact.
struct RockingBlock {
  /// Slenderness angle between the vertical and the line pivot → centre of mass (unit: rad).
  double alpha = 0.0;
  /// Distance from a pivot corner to the centre of mass (unit: m). Enters the dynamics only
  /// through p; kept so a block can be compared with its 3D counterpart.
  double R = 0.0;
  /// Frequency parameter p = sqrt(m g R / I_O) (unit: rad/s).
  double p = 0.0;
  /// Angular-velocity ratio θ̇⁺/θ̇⁻ across an impact (unit: 1). The factories set Housner's
  /// angular-momentum value; assign another value in [0, 1] to override it (e.g. to match the
  /// dissipation of a 3D contact model).
  double restitution = 1.0;

  /// Homogeneous rectangular block of half-width b and half-height h (unit: m):
  /// α = atan(b/h), R = sqrt(b² + h²), p = sqrt(3g/(4R)), r = 1 − 1.5 sin²α (physics.md §2).
  /// Throws std::invalid_argument unless both are finite and positive.
  static RockingBlock rectangular(double half_width, double half_height);

  /// Any symmetric 2D block from its geometry and mass properties: α (unit: rad), R (unit: m),
  /// mass (unit: kg) and the moment of inertia about the pivot axis I_O (unit: kg m^2);
  /// p² = m g R / I_O, r = 1 − (2 m R² / I_O) sin²α (physics.md §2). Throws std::invalid_argument
  /// unless 0 < α < π/2, R > 0, mass > 0 and I_O ≥ m R² (parallel-axis theorem). The returned r
  /// is negative for squat blocks, where Housner's no-bounce impact does not apply; simulate_rocking()
  /// rejects it, so override restitution deliberately in that case.
  static RockingBlock general(double alpha, double R, double mass, double inertia_pivot);
};

/// One horizontal ground-acceleration history, either sampled (a record) or analytic (a pulse).
/// Both forms are zero after end_time(). Breakpoints are the instants where the acceleration may
/// be non-smooth (samples, pulse ends); the integrator lands a step on each of them so RK4 never
/// straddles a kink or a jump, and it evaluates one-sided limits on either side of a jump.
/// (Named apart from rigid::motion::GroundMotion, the three-component record: rocking depends on
/// core only, so a caller passes one component, e.g. sampled(motion.x, motion.dt).)
class GroundAcceleration {
 public:
  /// No ground motion (ü_g ≡ 0); end_time() is 0.
  GroundAcceleration() = default;

  /// Uniformly sampled record: sample k (unit: m/s^2, multiplied by `scale`, unit: 1) holds at
  /// time start_time + k·dt (unit: s); linear interpolation between samples, zero before the
  /// first and after the last sample. The values are copied. Throws std::invalid_argument unless
  /// dt > 0, start_time and scale are finite and every sample is finite.
  static GroundAcceleration sampled(std::span<const double> accel, double dt, double start_time = 0.0,
                                    double scale = 1.0);

  /// Analytic history ü_g(t) (unit: m/s^2 as a function of s), used for t ≤ end_time (unit: s)
  /// and taken as zero after it. List every instant where `accel` jumps or has a kink in
  /// `breakpoints` (unit: s); end_time is added automatically. Throws std::invalid_argument if
  /// `accel` is empty or end_time or a breakpoint is not finite.
  static GroundAcceleration analytic(std::function<double(double)> accel, double end_time,
                                     std::vector<double> breakpoints = {});

  /// Ground acceleration at time t (unit: m/s^2); t in s.
  double operator()(double t) const;

  /// Time after which the ground is at rest (unit: s).
  double end_time() const { return end_; }

  /// Smallest breakpoint strictly later than t, or +∞ if none (unit: s).
  double next_breakpoint(double t) const;

 private:
  std::vector<double> samples_;       // sampled form (unit: m/s^2), already scaled
  double dt_ = 0.0;                   // sampling interval (unit: s)
  double start_ = 0.0;                // time of sample 0 (unit: s)
  std::function<double(double)> fn_;  // analytic form
  std::vector<double> breaks_;        // analytic form: sorted breakpoints (unit: s)
  double end_ = 0.0;                  // last instant of motion (unit: s)
};

/// Integration and modelling settings for simulate_rocking(). Defaults are for the reference use: an
/// accuracy well beyond that of the 3D engine at a cost of milliseconds per record.
struct RockingOptions {
  /// Largest RK4 step (unit: s). Steps are shortened so they end exactly on every breakpoint of
  /// the ground motion (each sample of a record). 1e-4 s keeps p·h ≲ 1e-3 for blocks down to
  /// R ≈ 0.1 m, so RK4's error is far below that of any ground record.
  double time_step = 1e-4;
  /// Use the linearised (slender-block) equation θ̈ = −p² [ (α s − θ) + ü_g/g ], for which
  /// physics.md §2 gives closed forms; its uplift threshold is g α instead of g tanα.
  bool linearised = false;
  /// |θ| at which the block is declared overturned (unit: rad); 0 selects α. Past α the gravity
  /// moment has reversed: once the ground is quiet a block crossing α outward always falls, so
  /// for pulses followed by free rocking and for records with a free tail the α criterion and a
  /// "lies on its side" criterion (π/2 for a rectangle) agree; they can differ only when α is
  /// crossed during strong shaking, which can bring the block back. α is a common criterion in
  /// Housner-type overturning studies and the one behind the closed forms of §2. The study's 3D
  /// rule (physics.md §11) is a full topple; use π/2 to mimic it. The choice matters for short
  /// pulses: for the §2 example block a one-cosine pulse with ωp/p = 4 needs about twice the
  /// amplitude to reach π/2 as to reach α, while for ωp/p ≤ 1 the two agree. Must be ≤ π/2.
  double overturn_angle = 0.0;
  /// After an impact the block returns to rest (θ = θ̇ = 0, moving with the ground) when |θ̇⁺|
  /// is below this fraction of the critical velocity sqrt(2 E_α), the speed at θ = 0 that just
  /// reaches α in free rocking (unit: 1). This stops the geometric (Zeno) sequence of ever
  /// shorter impacts; the rest state lifts the block again at once if the ground exceeds the
  /// uplift threshold. At 1e-4 the neglected rocking reaches at most ~1e-8 α.
  double rest_velocity_ratio = 1e-4;
  /// Record a trajectory (steps and events) in RockingResult::trajectory.
  bool record_trajectory = false;
  /// Minimum spacing of recorded step samples (unit: s); 0 records every step. Events (uplift,
  /// peaks, impacts, rest, overturn) are always recorded.
  double record_interval = 0.0;
};

/// State at the start of a simulation.
struct InitialState {
  double time = 0.0;       ///< unit: s
  double theta = 0.0;      ///< unit: rad, |θ| < overturn angle
  double theta_dot = 0.0;  ///< unit: rad/s
};

/// What a recorded trajectory sample marks.
enum class SampleKind {
  start,          ///< initial state
  step,           ///< end of an integration step
  uplift,         ///< the block leaves rest (ground exceeds the uplift threshold)
  peak,           ///< local extremum of θ (θ̇ = 0), located by root finding
  impact_before,  ///< θ = 0 just before an impact
  impact_after,   ///< θ = 0 just after an impact (θ̇ = r θ̇⁻, pivot switched)
  rest,           ///< the block returns to rest after an impact
  overturn,       ///< |θ| reaches the overturn angle
  end,            ///< final state
};

/// One point of a recorded trajectory.
struct TrajectorySample {
  double t = 0.0;          ///< unit: s
  double theta = 0.0;      ///< unit: rad
  double theta_dot = 0.0;  ///< unit: rad/s
  SampleKind kind = SampleKind::step;
};

/// Why simulate_rocking() stopped.
enum class StopReason {
  end_time,    ///< reached the requested end time
  overturned,  ///< |θ| reached the overturn angle
  at_rest,     ///< at rest after the ground motion ended: nothing more can happen
};

/// Outcome of one simulation (the engineering demand parameters of a case).
struct RockingResult {
  bool overturned = false;
  /// Time at which |θ| reached the overturn angle, located within the step (unit: s); NaN if
  /// the block did not overturn.
  double failure_time = std::numeric_limits<double>::quiet_NaN();
  /// Largest |θ| reached, peaks located within steps (unit: rad).
  double max_abs_theta = 0.0;
  /// Number of impacts (θ = 0 crossings with restitution applied).
  int impacts = 0;
  /// First time the block left rest (unit: s); NaN if it never rocked from rest.
  double uplift_time = std::numeric_limits<double>::quiet_NaN();
  /// Time at which the simulation stopped (unit: s).
  double end_time = 0.0;
  StopReason stop = StopReason::end_time;
  /// Recorded only when RockingOptions::record_trajectory is set.
  std::vector<TrajectorySample> trajectory;
};

/// Integrates the Housner equation from `initial` until `end_time` (unit: s), stopping early on
/// overturn or when the block is at rest after the ground motion ended. Fixed-step RK4 with
/// steps landing on the ground's breakpoints; impacts (θ = 0), overturning and peaks are located
/// inside a step by re-integrating from the step start to the root (safeguarded Newton), so the
/// restitution θ̇⁺ = r θ̇⁻ is applied at the located instant. From rest the uplift instant is
/// bisected on the ground history. Deterministic: same inputs, same bits. Throws
/// std::invalid_argument for an invalid block (α outside (0, π/2), p ≤ 0, r outside [0, 1]),
/// options or initial state, and std::logic_error if time stops advancing (an internal guard).
RockingResult simulate_rocking(const RockingBlock& block, const GroundAcceleration& ground, double end_time,
                               const RockingOptions& options = {}, const InitialState& initial = {});

/// Ground acceleration magnitude that lifts the block from rest (unit: m/s^2): g tanα, or g α for
/// the linearised equation (physics.md §2).
double uplift_acceleration(const RockingBlock& block, bool linearised = false);

/// Mechanical energy per unit I_O of the block on a quiet base, zero at rest (unit: rad^2/s^2):
/// ½θ̇² + p² [cos(α − |θ|) − cos α], or ½θ̇² + p² (α|θ| − θ²/2) for the linearised equation.
/// Conserved between impacts when ü_g = 0; an impact multiplies it by r².
double rocking_energy(const RockingBlock& block, double theta, double theta_dot, bool linearised = false);

/// Single pulses of physics.md §2 (Zhang & Makris 2001), starting at t = 0, zero outside:
enum class PulseShape {
  one_sine,     ///< a(t) = A sin(2π t/T) for 0 ≤ t ≤ T
  one_cosine,   ///< a(t) = A cos(2π t/T) for 0 ≤ t ≤ T (jumps at both ends)
  rectangular,  ///< a(t) = A for 0 ≤ t ≤ t1 (duration = t1)
};

/// Ground motion of one pulse of amplitude A (unit: m/s^2) and duration T or t1 (unit: s), with
/// its end (and start) as breakpoints. Throws std::invalid_argument unless duration > 0 and the
/// amplitude is finite.
GroundAcceleration make_pulse(PulseShape shape, double amplitude, double duration);

/// Search settings for min_overturning_amplitude().
struct ThresholdOptions {
  /// Free rocking after the pulse (unit: s). Just above the threshold the block creeps toward α
  /// for a time ~ (1/p) ln(1/excess), so 10 s resolves relative excesses down to ~e^(−10 p)
  /// (4e-10 for p = 2.2 rad/s, 5e-5 for p = 1 rad/s); lengthen it for large blocks.
  double free_time = 10.0;
  /// Bisection stops when the bracket is below this fraction of the amplitude (unit: 1).
  double relative_tolerance = 1e-5;
  /// Ratio between successive amplitudes of the upward scan that brackets the first overturning
  /// amplitude (unit: 1, > 1). Overturning is not monotone in the amplitude: above the minimum
  /// there are amplitudes the block survives (e.g. one-cosine, ωp/p = 1, §2 example block:
  /// overturns at 1.13 g tanα, survives at 1.135, overturns at 1.15), so a plain bisection between
  /// the uplift threshold and a large amplitude could converge to any of these boundaries. The
  /// scan only resolves overturning intervals wider than this ratio.
  double scan_ratio = 1.02;
  /// The scan gives up above this multiple of the uplift acceleration (unit: 1).
  double max_ratio = 100.0;
};

/// Smallest amplitude of a pulse (unit: m/s^2) that overturns the block, for a pulse of the given
/// shape and duration T or t1 (unit: s): upward scan from the uplift acceleration, then bisection
/// between the last surviving and the first overturning scan amplitude. The result is a boundary
/// between survival and overturning inside that bracket, to the tolerance; when several
/// boundaries fall within one scan step (see scan_ratio) it need not be the lowest.
/// The simulation runs until duration + free_time, so overturning after impacts during the pulse
/// (mode 2) and slow mode-1 overturning after it are both caught. One polarity suffices (see the
/// symmetry note at the top). Returns +∞ if nothing up to max_ratio · uplift_acceleration
/// overturns. Throws std::invalid_argument for invalid inputs.
double min_overturning_amplitude(const RockingBlock& block, PulseShape shape, double duration,
                                 const RockingOptions& options = {}, const ThresholdOptions& search = {});

}  // namespace rigid::rocking
