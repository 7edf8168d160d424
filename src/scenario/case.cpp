#include "rigid/scenario/case.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "rigid/core/error.hpp"
#include "rigid/scenario/rocking2d.hpp"
#include "rigid/scenario/run_bounds.hpp"

namespace rigid::scenario {

const char* engine_name(Engine engine) { return engine == Engine::rocking2d ? "rocking2d" : "dem3d"; }

std::optional<Engine> parse_engine(std::string_view text) {
  if (text == "dem3d") return Engine::dem3d;
  if (text == "rocking2d") return Engine::rocking2d;
  return std::nullopt;
}

Model::Model(Engine engine, std::vector<Scene> scenes, std::vector<motion::GroundMotion> records, RunSettings run,
             std::vector<double> pga_factor_per_g)
    : engine_(engine),
      scenes_(std::move(scenes)),
      records_(std::move(records)),
      run_(std::move(run)),
      pga_factor_per_g_(std::move(pga_factor_per_g)) {
  pga_factor_per_g_.resize(records_.size(), 0.0);
  if (engine_ == Engine::rocking2d) {
    for (const Scene& s : scenes_) blocks2d_.push_back(rocking_block_of(s));
  }
  check_bounds();
}

void Model::check_bounds() const {
  std::vector<double> times{run_.duration > 0 ? run_.duration : run_.free_time};  // a still pedestal
  for (int r = 0; r < records(); ++r) times.push_back(simulated_time(r));
  for (double t : times) {
    if (!std::isfinite(t) || t < 0) {
      throw InputError("", 0, "the simulated time must be finite and not negative (duration, free time)");
    }
  }
  if (engine_ != Engine::dem3d) return;  // the 2D model steps adaptively
  const double longest = *std::max_element(times.begin(), times.end());
  for (const Scene& s : scenes_) check_run_bounds(s, run_.step, longest);
}

double Model::simulated_time(int r) const {
  return run_.duration > 0 ? run_.duration : record(r).duration() + run_.free_time;
}

motion::GroundMotion case_motion(const Model& model, const Case& c) {
  motion::MotionTransform t;
  if (c.target_pga_g > 0) {
    t.target_pga_g = c.target_pga_g;
    t.pga_factor_per_g = model.pga_factor_per_g(c.record);
  }
  // The 2D reference takes the record's x component as scaled, whatever the rotation: a 2D
  // fragility (Purvance et al. 2008, physics.md §1) is a function of the
  // record's PGA and PGV alone. Projecting the rotated motion on x instead would weaken the
  // shaking by |cos| of a random angle that the 2D block cannot feel.
  if (model.engine() == Engine::dem3d) t.rotation = c.rotation_deg * kPi / 180.0;
  return motion::transformed(model.record(c.record), t);
}

CaseOutcome simulate_case(const Model& model, const Case& c) {
  CaseOutcome out;
  try {
    const motion::GroundMotion m = case_motion(model, c);
    if (model.engine() == Engine::rocking2d) {
      // no record: the block stands on a still pedestal for the run's duration
      static const std::vector<double> still{0.0, 0.0};
      out.run = m.x.empty() ? run_rocking2d(model.block2d(c.object), still, 0.01, model.run_settings())
                            : run_rocking2d(model.block2d(c.object), m.x, m.dt, model.run_settings());
    } else {
      out.run = run(model.scene(c.object), m.x.empty() ? GroundDrive{} : ground_drive(m), model.run_settings());
    }
  } catch (const std::exception& e) {
    out.outcome = CellOutcome::failed;
    out.reason = FailureReason::exception;
    out.message = e.what();
    out.error = std::current_exception();
    return out;
  }
  if (!out.run.finite) {
    out.outcome = CellOutcome::failed;
    out.reason = FailureReason::non_finite;
    out.message = "the simulation produced a non-finite state";
  } else {
    out.outcome = out.run.overturned ? CellOutcome::overturned : CellOutcome::survived;
  }
  return out;
}

}  // namespace rigid::scenario
