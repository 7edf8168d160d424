#pragma once
/// The accuracy study (docs/accuracy.md): what accuracy costs in time. Reference scenes
/// built in code are run with the settings that trade accuracy for time (time-step safety factor,
/// rotation integrator, the at-rest stop tolerances) with the default contact model, and with both
/// contact models (penalty at several stiffnesses, rigid at several time steps: a model axis, not a
/// numerical one: it changes the physics). Each run is measured against a converged reference run
/// of the same scene (outcome, failure time, max tilt, trajectory) and against the analytic oracles
/// where they exist (Housner one-sine thresholds, g tan(alpha), rigid-statics toppling of a stack,
/// Newmark rigid-plastic sliding, energy conservation). No I/O: `rigid study accuracy` reads the
/// record and writes the CSV.
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rigid/library/rock_library.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::study {

/// The study's contact stiffness K_N = K_S (physics.md §11) (unit: N/m).
inline constexpr double kStudyStiffness = 1e8;

/// A quantity that does not apply (an oracle a case lacks, a measure a run did not take).
inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

/// What the study sweeps.
struct StudyOptions {
  bool quick = false;               ///< a small subset (CI smoke test)
  int repeat = 3;                   ///< runs per timing (1 when quick); the median wall time is kept
  double reference_safety = 0.025;  ///< safety factor of the converged reference run
  std::vector<std::string> only;    ///< only these scenes or SCENE/MOTION cases (empty: all)
  std::string contact = "both";     ///< contact models on the model axis: rigid, penalty or both
};

/// One point of the sweep: numerical settings, or a contact model and its parameter.
struct Setting {
  std::string axis;    ///< converged | safety | tolerance | effects | stiffness | preset | rigid
  std::string label;   ///< unique within a case
  std::string preset;  ///< preset name (axis == preset)
  double safety = 0.2;
  dynamics::RotationIntegrator rotation = dynamics::RotationIntegrator::splitting;
  double stiffness = kStudyStiffness;
  /// the default model on the numerical axes; the model axis sets it explicitly, with stiffness
  contact::ContactMethod contact = contact::ContactLaw{}.method;
  double rest_speed = 1e-3;          ///< unit: m/s
  double rest_angular_speed = 1e-3;  ///< unit: rad/s
  double rest_time = 0.5;            ///< unit: s
  bool select_effects = true;        ///< RunSettings::select_effects (false: every effect simulated)
};

/// The run settings of a setting (durations and observers left at their defaults).
scenario::RunSettings run_settings(const Setting& s);

/// Every setting of the sweep, the converged reference first.
std::vector<Setting> study_settings(const StudyOptions& o);

/// The analytic answer a case is checked against.
enum class Oracle { none, housner_pulse, g_tan_alpha, rigid_statics, newmark_slide, energy_conservation };

/// Its column value in the CSV, e.g. "housner_one_sine_threshold_g"; "" for none.
const char* oracle_name(Oracle o);

/// A case: a scene, a motion, the oracle that applies.
struct Case {
  std::string scene;   ///< slender | stocky | stack | sliding | geode
  std::string motion;  ///< pulse | record | quasi-static | drop
  bool quasi_static = false;
  /// The unsettled scene for a contact law (stiffness set by the setting).
  std::function<scenario::Scene(const contact::ContactLaw&)> build;
  contact::ContactLaw law;
  bool settle = true;
  bool conservative = false;    ///< no friction, no damping: energy must be conserved
  motion::GroundMotion ground;  ///< x component only; empty: no ground motion
  double pulse_period = 0;      ///< > 0: one-sine pulse, amplitude from the threshold search
  double duration = 0;          ///< 0: motion + free time
  double free_time = 5.0;
  Oracle oracle = Oracle::none;
  double oracle_value = kNoValue;
  std::string model_quantity;                    ///< what a row's model_value is
  std::optional<library::LibraryModel> library;  ///< for the rigid-statics oracle
};

/// The study's cases: slender and stocky blocks (one-sine pulse, the record scaled, a quasi-static
/// ramp), a two-block stack, a sliding block and the geode drop; fewer when quick, filtered by
/// `only`. `record` is the real record, windowed; its x component drives the record cases.
std::vector<Case> study_cases(const StudyOptions& o, const motion::GroundMotion& record);

/// The oracle's value for a case, from its scene at build time (and its motion, for sliding);
/// the preset Case::oracle_value when the oracle needs no computation.
double oracle_value(const Case& c);

/// A one-sine ground pulse along x (unit: g, s), sampled every dt.
motion::GroundMotion one_sine(double amplitude_g, double period, double dt = 1e-3);

/// One run of one case with one setting, against the reference run and the oracle. NaN: not
/// measured for this case (an empty CSV cell).
struct Row {
  std::size_t case_index = 0, setting_index = 0;  ///< into StudyResult::cases and ::settings
  double dt = kNoValue;
  long steps = 0;
  double simulated = kNoValue;
  std::optional<bool> overturned;
  double failure_time = kNoValue, max_tilt_deg = kNoValue;
  std::optional<bool> outcome_match;
  double failure_time_err = kNoValue, max_tilt_err = kNoValue;
  double tilt_rms = kNoValue, pos_rms = kNoValue, traj_rel = kNoValue, error = kNoValue, energy_err = kNoValue;
  double model_value = kNoValue, model_ref_err = kNoValue, oracle_err = kNoValue;
  double wall = kNoValue, search_wall = kNoValue;
  int repeats = 0;
};

struct StudyResult {
  std::vector<Case> cases;  ///< with their oracle values (and the pulses the reference chose)
  std::vector<Setting> settings;
  std::vector<Row> rows;  ///< per case, per setting that applies to it
};

/// Runs every case with every setting that applies to it (settings.front() is the reference).
/// `case_done` is told each finished case and its wall time (unit: s), for progress.
StudyResult run_study(const StudyOptions& o, std::vector<Case> cases, std::vector<Setting> settings,
                      const std::function<void(const Case&, double)>& case_done = {});

}  // namespace rigid::study
