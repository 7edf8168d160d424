#pragma once
/// A campaign task: its cell as a scenario::Case (job::case_of), simulated, as the plain result ranks exchange.
#include <cstdint>

#include "rigid/campaign/plan.hpp"
#include "rigid/job/job.hpp"
#include "rigid/scenario/case.hpp"

namespace rigid::campaign {

/// Simulates task `task` of the job. `noop` returns a survived result at once (to measure
/// dispatch overhead). A failed simulation is a result with a reason, never an exception.
TaskResult run_task(const job::Job& job, const scenario::Model& model, std::int64_t task, bool noop = false);

}  // namespace rigid::campaign
