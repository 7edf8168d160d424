#pragma once
/// What a job will cost (`rigid campaign JOB --dry-run`): its cells, and this machine's time per
/// step on each object, measured by simulating a short case of it, times the steps of all its
/// cells if every run reached the end of its record.
#include <vector>

#include "rigid/job/job.hpp"
#include "rigid/scenario/case.hpp"

namespace rigid::job {

/// One object's cost (one per Job::objects, variants included).
struct ObjectCost {
  double dt_s = 0;              ///< its time step
  double seconds_per_step = 0;  ///< measured on this machine (unit: s of wall time per step)
  double steps = 0;             ///< steps of all its cells run to their end
  double core_seconds = 0;      ///< steps x seconds_per_step (unit: s of one core)
};

struct CostEstimate {
  long cells = 0;             ///< of the job: objects x records x scales x rotations
  long cells_per_object = 0;  ///< records x scales x rotations
  /// Simulated time of one object's cells if every run reaches the end of its record (unit: s).
  double simulated_per_object_s = 0;
  /// The simulated time of each object's probe: one case, its first record at its smallest scale
  /// (unit: s).
  double probe_duration_s = 0;
  std::vector<ObjectCost> objects;
  double simulated_total_s() const { return simulated_per_object_s * double(objects.size()); }
  double steps() const;         ///< of every cell
  double core_seconds() const;  ///< of every cell (unit: s of one core)
};

/// The time a probe simulates of each object (unit: s): short, a real case rather than its whole
/// record.
inline constexpr double kProbeDuration = 2.0;

/// Estimates the job's cost on `model` (job::load_model's): simulates one probe case per object.
/// An upper bound: overturned runs stop early and the stop rule skips scales.
CostEstimate estimate_cost(const Job& job, const scenario::Model& model);

}  // namespace rigid::job
