#pragma once
/// Runs one task of a campaign: loads every object's scene and every record once, then turns a
/// cell into a scaled, rotated ground velocity and a simulation. A failed simulation becomes a
/// result with a reason, never an exception.
#include <vector>

#include "rigid/campaign/plan.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/scenario/rocking2d.hpp"
#include "rigid/scenario/job.hpp"

namespace rigid::campaign {

class TaskRunner {
 public:
  /// Reads scenes, states and records; throws rigid::InputError for bad input.
  explicit TaskRunner(const scenario::Job& job);

  /// Simulates a cell. `noop` returns at once (to measure dispatch overhead).
  TaskResult run(long task, const Cell& cell, bool noop = false) const;

  const std::vector<io::RecordMeta>& records() const { return meta_; }
  /// Simulated time of a task on record r (unit: s): the window plus the free time.
  double simulated_time(int r) const;
  const scenario::Scene& scene(int object) const { return scenes_[object]; }

 private:
  const scenario::Job& job_;
  std::vector<scenario::Scene> scenes_;
  std::vector<rocking::RockingBlock> rocking_;  // per object, for model = "rocking2d"
  std::vector<motion::GroundMotion> windowed_;  // per record, window applied
  std::vector<double> unit_factor_;             // per record: factor for a target of 1 g
  std::vector<io::RecordMeta> meta_;
};

}  // namespace rigid::campaign
