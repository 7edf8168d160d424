#pragma once
/// A campaign task: its cell as a scenario::Case, simulated, as the plain result ranks exchange.
#include <cstdint>

#include "rigid/campaign/plan.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/job.hpp"

namespace rigid::campaign {

/// The case of a cell: the job's scale as target PGA, the cell's rotation.
scenario::Case case_of(const scenario::Job& job, const Cell& cell);

/// Simulates task `task` of the job. `noop` returns a survived result at once (to measure
/// dispatch overhead). A failed simulation is a result with a reason, never an exception.
TaskResult run_task(const scenario::Job& job, const scenario::Model& model, std::int64_t task, bool noop = false);

}  // namespace rigid::campaign
