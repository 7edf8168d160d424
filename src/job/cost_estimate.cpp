#include "rigid/job/cost_estimate.hpp"

#include <chrono>

#include "rigid/dynamics/world.hpp"

namespace rigid::job {

double CostEstimate::steps() const {
  double sum = 0;
  for (const ObjectCost& o : objects) sum += o.steps;
  return sum;
}

double CostEstimate::core_seconds() const {
  double sum = 0;
  for (const ObjectCost& o : objects) sum += o.core_seconds;
  return sum;
}

CostEstimate estimate_cost(const Job& job, const scenario::Model& model) {
  using Clock = std::chrono::steady_clock;
  CostEstimate e;
  e.cells_per_object = job.cells().per_object();
  e.cells = job.cells().size();
  for (int r = 0; r < model.records(); ++r) e.simulated_per_object_s += model.simulated_time(r);
  e.simulated_per_object_s *= double(job.scales_g.size()) * job.rotations;
  // this machine's cost per step on each object (each variant: stiffness, size and contact model
  // change the step): a short real case, not its whole record
  scenario::RunSettings probe = model.run_settings();
  probe.duration = kProbeDuration;
  e.probe_duration_s = probe.duration;
  for (int o = 0; o < model.objects(); ++o) {
    scenario::Model short_model(model.engine(), {model.scene(o)},
                                {model.records() ? model.record(0) : motion::GroundMotion{}}, probe,
                                {model.records() ? model.pga_factor_per_g(0) : 0.0});
    const scenario::Case c{0, 0, job.scales_g.empty() ? 0.0 : job.scales_g.front(), 0.0};
    const auto start = Clock::now();
    const scenario::CaseOutcome out = scenario::simulate_case(short_model, c);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    ObjectCost cost;
    cost.dt_s =
        out.run.dt_s > 0 ? out.run.dt_s : dynamics::time_step(model.scene(o).bodies, model.scene(o).law, probe.step);
    cost.seconds_per_step = out.run.steps > 0 ? seconds / double(out.run.steps) : 0.0;
    cost.steps = e.simulated_per_object_s / cost.dt_s;
    cost.core_seconds = cost.steps * cost.seconds_per_step;
    e.objects.push_back(cost);
  }
  return e;
}

}  // namespace rigid::job
