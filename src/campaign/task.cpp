#include "rigid/campaign/task.hpp"

#include <chrono>
#include <cmath>

namespace rigid::campaign {

TaskResult run_task(const job::Job& job, const scenario::Model& model, std::int64_t task, bool noop) {
  TaskResult out;
  out.task = task;
  out.failure_time_s = std::nan("");
  out.max_tilt_deg = std::nan("");
  out.max_slip_m = std::nan("");
  if (noop) {
    out.outcome = static_cast<std::int32_t>(scenario::CellOutcome::survived);
    return out;
  }
  const auto start = std::chrono::steady_clock::now();
  const scenario::CaseOutcome c = scenario::simulate_case(model, job::case_of(job, job.cells().cell(task)));
  out.outcome = static_cast<std::int32_t>(c.outcome);
  out.reason = static_cast<std::int32_t>(c.reason);
  set_message(out, c.message);
  if (c.outcome != scenario::CellOutcome::failed) {
    if (c.run.failure_time_s) out.failure_time_s = *c.run.failure_time_s;
    out.max_tilt_deg = c.run.max_tilt_rad * 180.0 / kPi;
    out.max_slip_m = c.run.max_slip_m;
    out.unconverged_steps = c.run.unconverged_steps;
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rigid::campaign
