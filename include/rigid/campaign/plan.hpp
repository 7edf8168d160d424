#pragma once
/// The task grid of a campaign and the order of work: tasks are cells (object, record, scale,
/// rotation); each cell's rotation angle comes from a counter-based hash of its coordinates and
/// the job seed, and the study's stop rule decides which cells are inferred from outcomes alone,
/// so results never depend on dispatch order, rank count or restarts. No I/O, no MPI.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/job/cells.hpp"
#include "rigid/job/job.hpp"
#include "rigid/scenario/case.hpp"

namespace rigid::campaign {

/// Coordinates of a cell (job/cells.hpp numbers them).
using job::Cell;
using job::cell_rotation_deg;
using job::rotation_angle_deg;

/// Bytes kept of a failed task's error text (with its terminating NUL): the text travels in the
/// fixed-size TaskResult, so a longer message is cut.
inline constexpr std::size_t kTaskMessageBytes = 232;

/// Result of one task, as sent between ranks and written to the journal (plain data).
struct TaskResult {
  std::int64_t task = -1;
  std::int32_t outcome = 0;   ///< scenario::CellOutcome
  std::int32_t reason = 0;    ///< scenario::FailureReason
  double failure_time_s = 0;  ///< NaN if none
  double max_tilt_deg = 0;
  double max_slip_m = 0;
  double wall_s = 0;
  /// A failed task's error text, NUL-terminated. Fields are only ever added at the end, so that
  /// each older journal format is a prefix of this one (campaign/journal.hpp).
  char message[kTaskMessageBytes] = {};
  /// Steps whose rigid contact solve stopped at its sweep cap (scenario::RunOutcome); -1 when
  /// not simulated or not recorded (a record of an older journal).
  std::int64_t unconverged_steps = -1;
};
static_assert(sizeof(TaskResult) == 288, "TaskResult is written raw: no padding, a layout the journal names");

/// Stores `text` in r.message, cut to fit.
void set_message(TaskResult& r, std::string_view text);
/// The text of r.message.
std::string message_of(const TaskResult& r);

class Plan {
 public:
  /// record_cost: relative expected cost of each record (e.g. its simulated duration), used to
  /// hand out the longest tasks first within a scale. stop_after = 0 disables the stop rule.
  Plan(int objects, int records, int scales, int rotations, int stop_after, std::vector<double> record_cost);

  long size() const { return static_cast<long>(outcome_.size()); }
  Cell cell(long task) const;
  long task(const Cell& c) const;

  /// Marks a task already known (resume). Call before dispatching.
  void restore(const TaskResult& r);
  /// The next task worth running, or nothing when every remaining cell is done, in flight or
  /// known to be inferred. Marks it in flight.
  std::optional<long> next();
  /// Records a finished task.
  void complete(const TaskResult& r);
  /// Returns a task that will not finish (abandoned) to the pool.
  void release(long task);

  long done() const { return done_; }  ///< simulated (any outcome) or known failed
  long in_flight() const { return in_flight_; }
  long failures() const { return failures_; }
  /// True when no task remains to dispatch and none is in flight. Skips, once and for all,
  /// dispatch positions that can never be handed out (done or inferred).
  bool finished();
  /// Tasks that still need a simulation, counting nothing known to be inferred.
  long remaining() const;

  /// Final outcome of every cell: simulated outcomes, inferred where the stop rule applies
  /// (results simulated beyond the cut-off are replaced by inferred), not_run elsewhere.
  std::vector<std::int8_t> final_outcomes() const;
  /// Whether a finished cell's simulated result is kept (false when the stop rule infers it).
  std::vector<bool> kept_mask() const;
  const std::vector<TaskResult>& results() const { return results_; }

 private:
  // first scale index that the stop rule infers for (object, record), from known outcomes; -1
  // when not (yet) known (cached; see update_cutoff)
  int cutoff(int object, int record) const { return cutoff_[std::size_t(object) * records_ + record]; }
  // recomputes the cut-off of the task's (object, record) after its outcome changed
  void update_cutoff(long task, std::int8_t before);
  // not run and not inferred: can be handed out
  bool available(long task) const;

  int objects_, records_, scales_, rotations_, stop_after_;
  std::vector<std::int8_t> outcome_;  // per task: CellOutcome or -1 in flight
  std::vector<TaskResult> results_;   // per task
  std::vector<long> order_;           // dispatch order
  std::size_t cursor_ = 0;            // first position of order_ not yet handed out
  std::vector<long> returned_;        // released tasks, handed out again first
  std::vector<int> overturned_;       // per (object, record, scale): overturned rotations
  std::vector<int> cutoff_;           // per (object, record)
  long done_ = 0, in_flight_ = 0, failures_ = 0;
};

}  // namespace rigid::campaign
