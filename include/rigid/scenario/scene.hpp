#pragma once
/// A scene (blocks, contact law, failure rule) and one shaking run of it: the unit of work of a
/// campaign. Depends only on its inputs, so a run is reproducible bit for bit.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rigid/dynamics/world.hpp"
#include "rigid/motion/ground_motion.hpp"

namespace rigid::scenario {

/// When a run counts as a failure (the rock overturned).
struct FailureRule {
  enum class Kind {
    /// The study's rule (physics.md §11): a free block's centroid is lower than the lowest
    /// vertex of every fixed block, i.e. it has fallen off its pedestal.
    below,
    /// A free block has tilted more than tilt_angle from its starting attitude (the angle
    /// between its initial vertical axis, carried with the block, and the vertical).
    tilt,
  };
  Kind kind = Kind::below;
  double tilt_angle = 0.5 * kPi;  ///< unit: rad (used by Kind::tilt)
};

/// Everything that defines a scene.
struct Scene {
  std::vector<dynamics::BodyDef> bodies;
  contact::ContactLaw law;
  FailureRule failure;
  double density = 2600;  ///< unit: kg/m^3 (already applied to the bodies' masses)
  std::string source;     ///< where it was read from, for messages
  /// Every file the scene was built from, in reading order (scene, model, STLs, state): what a
  /// campaign hashes to refuse a resume over changed inputs.
  std::vector<std::string> files;
  /// What the reader repaired and the user should hear of, one line each ("FILE: what"; e.g. an
  /// inward mesh flipped). Commands print them as `rigid: warning: ...`.
  std::vector<std::string> warnings;
};

/// Ground velocity that drives the fixed blocks, sampled every dt from t = 0 (unit: m/s),
/// linearly interpolated; after the last sample it keeps its last value (the pedestal coasts,
/// which exerts no force).
struct GroundDrive {
  double dt = 0.01;
  std::vector<Vec3> velocity;
  Vec3 at(double t) const;
  double duration() const { return velocity.empty() ? 0.0 : dt * double(velocity.size() - 1); }
  /// Exact integral of at(t) from t0 to t1 (unit: m): the ground's displacement.
  Vec3 displacement(double t0, double t1) const;
};

/// The trapezoid-integrated ground velocity of a motion (absent components are zero).
GroundDrive ground_drive(const motion::GroundMotion& m);

/// Settings of one run.
struct RunSettings {
  dynamics::StepSettings step;
  /// Simulated time (unit: s); 0 = the ground motion's duration plus `free_time`.
  double duration = 0;
  /// Time left to rock after the ground motion ends, when duration = 0 (unit: s).
  double free_time = 5.0;
  /// Stop once the ground motion has ended and every free block has stayed at rest this long.
  double rest_time = 0.5;
  /// At rest: every free block below these speeds (unit: m/s and rad/s).
  double rest_speed = 1e-3;
  double rest_angular_speed = 1e-3;
  /// Optional observer (e.g. a trajectory writer): called with the world at t = 0, then every
  /// observe_interval of simulated time, and once more when the run ends.
  std::function<void(const dynamics::World&)> observer;
  double observe_interval = 0.02;  ///< unit: s
  /// Simulate only the effects the scene and motion call for (no vertical work without a
  /// vertical component, pair culling, sleeping, sliding bookkeeping only where friction can be
  /// exceeded). false = every effect simulated, the reference the selection is checked against.
  bool select_effects = true;
  /// Sleeping (with select_effects; scenario::run says when): free blocks resting on fixed blocks
  /// sleep only while the ground acceleration stays below sleep_wake_fraction of the smallest
  /// quasi-static acceleration that could start them rocking or sliding, and (to the end of the
  /// record) of the largest acceleration already met (unit: 1); "still" blocks
  /// keep at least still_load_fraction of their mean subcontact load on every subcontact (unit: 1).
  double sleep_wake_fraction = 0.5;
  double still_load_fraction = 0.5;
};

/// Which effects a run simulated and what skipping the others saved (RunSettings::select_effects).
struct ActiveEffects {
  bool selected = false;        ///< select_effects was on
  bool vertical_motion = true;  ///< the ground moves vertically (else no z work for the pedestals)
  long pairs_total = 0;         ///< block pairs, n (n - 1) / 2
  long pairs_fixed_fixed = 0;   ///< pairs of two fixed blocks: never tested
  long pairs_never_tested = 0;  ///< other pairs never narrow-phase tested: always far apart
  long pair_steps_culled = 0;   ///< pair evaluations skipped by distance (sphere test or skin)
  bool sleep_possible = false;  ///< at some time every free block rested on fixed blocks only
  long sleep_intervals = 0;     ///< times the free blocks fell asleep
  double asleep_s = 0;          ///< simulated time spent asleep (unit: s)
  long steps_skipped = 0;       ///< steps not computed because the blocks were asleep
  bool sliding = false;         ///< some subcontact reached the Coulomb cap (slip bookkeeping ran)
  long contact_steps = 0;       ///< pair evaluations in contact
  long sliding_steps = 0;       ///< of those, evaluations that needed slip bookkeeping
  enum class End { full_duration, failure, at_rest };
  End end = End::full_duration;  ///< why the run stopped
  double time_saved_s = 0;       ///< requested duration minus simulated time (unit: s)
};

/// What one run produced.
struct RunOutcome {
  bool overturned = false;
  std::optional<double> failure_time_s;
  std::string failed_block;  ///< name of the first block that failed
  long steps = 0;            ///< steps computed (steps skipped asleep not counted)
  double dt_s = 0;
  double simulated_s = 0;      ///< simulated time
  double max_tilt_rad = 0;     ///< largest tilt of any free block
  double max_slip_m = 0;       ///< largest accumulated frictional slip of any free block
  double max_overlap_m = 0;    ///< deepest subcontact indentation seen
  bool ended_at_rest = false;  ///< stopped early because all blocks were at rest after the motion
  bool finite = true;          ///< false if a NaN or Inf appeared (the run stops there)
  /// Rigid contact model: steps whose contact solve stopped at its sweep cap without converging
  /// (dynamics::StepStats); 0 for penalty contact and the 2D model, which have no such solve.
  long unconverged_steps = 0;
  int max_solver_sweeps = 0;  ///< most sweeps one step's contact solve took (rigid contact model)
  long solver_solves = 0;     ///< steps with a contact to solve (rigid contact model)
  long solver_sweeps = 0;     ///< sweeps of those solves, in all (their mean: solver_sweeps / solver_solves)
  ActiveEffects effects;      ///< filled by run() (not by the 2D model)
};

/// Tilt of body i (unit: rad): the angle between its initial vertical axis, carried with the
/// block, and the world vertical.
double tilt(const Quat& initial, const Quat& current);

/// Moves the centre of mass of a free block by `offset_mesh` (the mesh's frame, unit: m: the
/// block's own coordinates before any state moved it) and keeps the block where it is: its shape
/// and pieces are re-expressed about the new centre (geometry::offset_mass_centre, which says
/// what happens to the inertia) and `position` follows. Offsets add up. Throws
/// std::invalid_argument for a fixed block, a non-finite offset or a centre outside the block.
void offset_centre_of_mass(dynamics::BodyDef& body, const Vec3& offset_mesh);

/// World position of a block's mesh centroid: `position` less the centre-of-mass offset (what
/// saved states and `rigid inspect` report; equal to `position` for a uniform block).
Vec3 centroid_position(const dynamics::BodyDef& body);

/// Runs one shaking case from the scene's initial state.
RunOutcome run(const Scene& scene, const GroundDrive& ground, const RunSettings& settings);

/// A free block that settling left with nothing under it.
struct LooseBlock {
  std::string name;
  double drop = 0;           ///< how far its centre of mass fell (unit: m)
  double turn = 0;           ///< how far it turned (unit: rad)
  bool below_fixed = false;  ///< it fell below the lowest point of every fixed block
};

/// What settling produced: the scene with the settled poses and zero velocities, and the first
/// free block that ended resting on nothing, if any.
struct Settled {
  Scene scene;
  std::optional<LooseBlock> loose;
};

/// Settles the scene with no ground motion and Itasca local damping until every free block is at
/// rest (or max_time passes). A free block whose centre falls below every fixed block by more
/// than its size can never be caught (settling stops there), and one whose weight no contact
/// carries at the end (under a tenth of it) rests on nothing: either is `loose`. The run bounds
/// (check_run_bounds over max_time) apply: throws rigid::InputError for a settling that would
/// take more than kMaxStepsPerRun steps.
Settled settle(const Scene& scene, const dynamics::StepSettings& step, double max_time = 20.0,
               double local_damping = 0.8);

/// settle's scene; throws rigid::InputError (no file; the message names the block, how far it
/// fell and turned) when a free block ends resting on nothing.
Scene equilibrate(const Scene& scene, const dynamics::StepSettings& step, double max_time = 20.0,
                  double local_damping = 0.8);

/// The one-line account of a loose block: "block 'NAME' rests on nothing after settling: it fell
/// D m (below every fixed block) and turned A deg".
std::string describe(const LooseBlock& loose);

}  // namespace rigid::scenario
