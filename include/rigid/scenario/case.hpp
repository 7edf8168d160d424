#pragma once
/// The unit of work of Rigid: one case, (object, record, scale, rotation), simulated on an
/// immutable Model. `rigid run`, campaigns and the dry-run estimate all go through simulate_case(),
/// so a case means the same thing whichever command runs it. No I/O: job::load_model builds a
/// Model from files.
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/motion/ground_motion.hpp"
#include "rigid/rocking/housner.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

/// Which model simulates a case.
enum class Engine {
  dem3d,      ///< the 3D engine (dynamics::World)
  rocking2d,  ///< the 2D Housner reference, driven by the record's unrotated x component
};
const char* engine_name(Engine engine);
/// "dem3d" or "rocking2d"; nothing for any other text.
std::optional<Engine> parse_engine(std::string_view text);

/// Everything cases share: the scenes, the records (windowed, unscaled), how to simulate.
/// Built once, then only read, so any number of threads may simulate on it.
class Model {
 public:
  /// `pga_factor_per_g`: per record, motion::target_pga_factor(record, 1.0) when the caller has
  /// it (a campaign computes it once per record, since cases scale one record many times); empty
  /// or 0 = computed by each case that asks for a target PGA. Throws rigid::InputError when engine
  /// = rocking2d and a scene is not a box block on a box pedestal, and (no file named) when a run
  /// would break the bounds of run_bounds.hpp (step above the contact model's, too many steps).
  Model(Engine engine, std::vector<Scene> scenes, std::vector<motion::GroundMotion> records, RunSettings run,
        std::vector<double> pga_factor_per_g = {});

  Engine engine() const { return engine_; }
  int objects() const { return int(scenes_.size()); }
  int records() const { return int(records_.size()); }
  const Scene& scene(int object) const { return scenes_[std::size_t(object)]; }
  const motion::GroundMotion& record(int r) const { return records_[std::size_t(r)]; }
  const RunSettings& run_settings() const { return run_; }
  /// Simulated time of a case on record r (unit: s): run.duration, or the record plus free time.
  double simulated_time(int r) const;
  /// The factor that brings record r's GMRotI50 PGA to 1 g, or 0 when not given.
  double pga_factor_per_g(int r) const { return pga_factor_per_g_[std::size_t(r)]; }
  /// The 2D block of an object (rocking2d models only).
  const rocking::RockingBlock& block2d(int object) const { return blocks2d_[std::size_t(object)]; }

 private:
  void check_bounds() const;
  Engine engine_;
  std::vector<Scene> scenes_;
  std::vector<motion::GroundMotion> records_;
  RunSettings run_;
  std::vector<double> pga_factor_per_g_;         // per record; 0 = not given
  std::vector<rocking::RockingBlock> blocks2d_;  // per scene, for rocking2d
};

/// One case of a model.
struct Case {
  int object = 0;
  int record = 0;
  /// Target GMRotI50 PGA (unit: g); 0 = the record as it is.
  double target_pga_g = 0;
  /// Rotation of the horizontal components about z (unit: deg; motion::rotated's convention).
  /// The 2D model ignores it: a 2D fragility depends on the record's PGA and PGV alone.
  double rotation_deg = 0;
};

/// Outcome of one cell of a fragility cube (the values stored in its `outcome` dataset).
enum class CellOutcome : std::int8_t {
  not_run = 0,     ///< not simulated yet
  survived = 1,    ///< simulated, did not overturn
  overturned = 2,  ///< simulated, overturned
  inferred = 3,    ///< not simulated: above N consecutive fully overturned scales (stop rule)
  failed = 4,      ///< the simulation failed (exception, non-finite state); see FailureReason
};

/// Why a case failed (the cube's failure_reason).
enum class FailureReason : std::int32_t {
  none = 0,
  exception = 1,    ///< the simulation threw (bad motion, internal error)
  non_finite = 2,   ///< NaN or Inf in the state
  worker_lost = 3,  ///< reserved: the rank running it died (the task is redone on resume)
};

/// What a case produced.
struct CaseOutcome {
  CellOutcome outcome = CellOutcome::failed;  ///< survived, overturned or failed
  FailureReason reason = FailureReason::none;
  std::string message;       ///< the error's text when reason = exception
  std::exception_ptr error;  ///< the error itself when reason = exception (to rethrow)
  RunOutcome run;            ///< the run's details (valid unless reason = exception)
};

/// The motion of a case: record `c.record` scaled to `c.target_pga_g` and, for the 3D model,
/// rotated by `c.rotation_deg` (motion::transformed).
motion::GroundMotion case_motion(const Model& model, const Case& c);

/// Simulates a case. Never throws: an error inside the simulation becomes outcome = failed with
/// its reason and message.
CaseOutcome simulate_case(const Model& model, const Case& c);

}  // namespace rigid::scenario
