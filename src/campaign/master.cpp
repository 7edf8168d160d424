// Rank 0 of a campaign, wired from parts that each own their state and lock: the TaskPool (the
// plan, under its mutex) hands out tasks to the LocalWorker (a second thread that simulates, so on
// 2 ranks both cores do) and, through the Dispatcher (the main thread, the only one that calls
// MPI), to the worker ranks; every result goes to the pool and to the Checkpointer (journal and
// cube rewrites, under its own mutex), whose file work runs on the CheckpointWriter's thread.
// No lock is ever held while another part's is taken. The main thread also notices stop signals,
// reports progress and ends the campaign.
#include "rigid/campaign/master.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include "rigid/campaign/checkpoint_writer.hpp"
#include "rigid/campaign/checkpointer.hpp"
#include "rigid/campaign/dispatcher.hpp"
#include "rigid/campaign/local_worker.hpp"
#include "rigid/campaign/log.hpp"
#include "rigid/campaign/stop_signal.hpp"
#include "rigid/campaign/task.hpp"
#include "rigid/campaign/task_pool.hpp"
#include "rigid/campaign/transport.hpp"

namespace rigid::campaign {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

class Master {
 public:
  Master(const CampaignContext& context, const CampaignOptions& options, Plan& plan,
         const std::vector<TaskResult>& carried, int ranks)
      : context_(context),
        options_(options),
        ranks_(ranks),
        grace_s_(options.grace_s >= 0 ? options.grace_s : context.job.grace_s),
        pool_(plan, stopping_),
        checkpointer_(
            context.job.output, context.inputs.combined, plan,
            [&context](const Plan& p) { return make_cube(context, p); }, carried, stopping_),
        done_at_start_(plan.done()) {}

  // an exception out of run(): the threads end (after their current task) before the parts go
  ~Master() { stopping_ = true; }
  MasterResult run();

 private:
  // every result: the plan, then the journal (one lock after the other, never both)
  void deliver(std::span<const TaskResult> results) {
    pool_.complete(results);
    checkpointer_.record(results);
  }
  void notice_stop_signal();
  void report_progress(bool final);
  void ask_for_checkpoints(Clock::time_point& last_sync, double interval_s);
  [[noreturn]] void abandon();
  MasterResult finish(const Dispatcher& dispatcher);

  const CampaignContext& context_;
  const CampaignOptions& options_;
  const int ranks_;
  const double grace_s_;
  // Set on a stop signal (by the main thread) or a failed write (by the checkpointer): no new
  // tasks; the pool and the checkpointer read it.
  std::atomic<bool> stopping_{false};
  const Clock::time_point started_ = Clock::now();
  TaskPool pool_;
  Checkpointer checkpointer_;
  const long done_at_start_;
  Clock::time_point last_progress_ = started_;
  std::optional<Clock::time_point> stop_since_;
  // the threads, started by run() once the restored results are in the cube
  std::optional<CheckpointWriter> writer_;
  std::optional<LocalWorker> local_;
};

// A stop signal: no new tasks, and a checkpoint at once (the journal fsynced first, then a
// rewrite, both on the writer thread, so results of tasks in flight are still received).
// mpirun and batch systems follow a SIGTERM with a SIGKILL within seconds, often before the
// in-flight tasks could finish; what they finish in the grace period goes into the final
// checkpoint.
void Master::notice_stop_signal() {
  if (!stop_signal() || stopping_) return;
  stopping_ = true;
  stop_since_ = Clock::now();
  std::fprintf(stderr, "\n");  // after a progress bar
  log_status("signal {}: no new tasks; checkpoint now, then up to {:g} s for {} in flight", stop_signal(), grace_s_,
             pool_.in_flight());
  writer_->request(true, true);
}

void Master::report_progress(bool final) {
  if (!options_.on_progress) return;
  if (!final && seconds_since(last_progress_) < options_.progress_interval) return;
  last_progress_ = Clock::now();
  const PoolCounts c = pool_.counts();
  ProgressReport p;
  p.done = c.done;
  p.remaining = c.remaining;
  // a fixed denominator: every cell is settled at the end, inferred ones as the rule infers them
  p.settled = c.size - c.remaining - c.in_flight;
  p.failures = c.failures;
  p.done_at_start = done_at_start_;
  p.total = c.size;
  p.elapsed_s = seconds_since(started_);
  p.final = final;
  options_.on_progress(p);
}

// A journal sync every checkpoint interval; a rewrite when the checkpointer's schedule says so.
void Master::ask_for_checkpoints(Clock::time_point& last_sync, double interval_s) {
  const bool sync = seconds_since(last_sync) >= interval_s;
  if (sync) last_sync = Clock::now();
  const bool rewrite = !stopping_ && !writer_->rewrite_pending() && checkpointer_.rewrite_due(interval_s);
  if (sync || rewrite) writer_->request(sync, rewrite);
}

// The grace period after a stop is over: in-flight work is given up, what is done is
// checkpointed and every rank ends.
void Master::abandon() {
  stopping_ = true;
  writer_->stop();
  const bool written = checkpointer_.rewrite();
  log_status("grace period over; {} tasks abandoned (redone on resume)", pool_.in_flight());
  if (!written) std::fprintf(stderr, "rigid: error: %s\n", checkpointer_.failure().c_str());
  std::fflush(stderr);
  abort_all_ranks(written ? kExitInterrupted : kExitIoFailure);
}

MasterResult Master::run() {
  // the restored results go into the cube at once, which also proves the output writable; on a
  // failure the loop below only tells the workers to stop
  if (checkpointer_.rewrite()) {
    const PoolCounts c = pool_.counts();
    log_status("{} tasks, {} already done, {} ranks, output {}", c.size, c.done, ranks_, context_.job.output);
  }
  const job::Job& job = context_.job;
  const scenario::Model& model = context_.model;
  const bool noop = options_.noop;
  local_.emplace(
      pool_, [&job, &model, noop](std::int64_t t) { return run_task(job, model, t, noop); },
      [this](std::span<const TaskResult> r) { deliver(r); }, noop && ranks_ > 1);
  writer_.emplace(checkpointer_);
  Dispatcher dispatcher(
      pool_,
      [this](std::span<const TaskResult> r) {
        deliver(r);
        checkpointer_.flush();
      },
      ranks_);
  auto last_sync = Clock::now();
  const double interval_s =
      options_.checkpoint_interval_s > 0 ? options_.checkpoint_interval_s : job.checkpoint_interval_s;
  for (;;) {
    const bool busy = dispatcher.receive();
    notice_stop_signal();
    dispatcher.answer();
    checkpointer_.flush();
    report_progress(false);
    ask_for_checkpoints(last_sync, interval_s);
    if (dispatcher.active_workers() == 0 && local_->done() && pool_.over()) break;
    if (stopping_ && !stop_since_) stop_since_ = Clock::now();  // stopped by a failed write
    if (stopping_ && seconds_since(*stop_since_) > grace_s_) abandon();
    if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  local_->join();
  writer_->stop();
  return finish(dispatcher);
}

// After the loop: the last checkpoint, and the status.
MasterResult Master::finish(const Dispatcher& dispatcher) {
  checkpointer_.rewrite();
  MasterResult result;
  report_progress(true);
  if (const std::string failure = checkpointer_.failure(); !failure.empty()) {
    std::fprintf(stderr, "rigid: error: %s\n", failure.c_str());
    result.status = kExitIoFailure;
    return result;
  }
  result.cube = pool_.read([this](const Plan& p) { return make_cube(context_, p); });
  if (ranks_ > 1 && options_.verbose) {  // dispatch internals: for whoever tunes the dispatch
    log_status("{} tasks sent to {} worker ranks in {} messages ({:.0f} tasks/s over {:.2f} s)",
               dispatcher.tasks_sent(), ranks_ - 1, dispatcher.messages_sent(),
               double(dispatcher.tasks_sent()) / seconds_since(started_), seconds_since(started_));
    const CheckpointStats s = checkpointer_.stats();
    log_status(
        "checkpoints: {} journal syncs, {} cube rewrites (the last {:.2f} s), dispatch held at most {:.2f} ms by one",
        s.syncs, s.rewrites, s.last_rewrite_s, 1e3 * s.longest_stall_s);
  }
  if (stopping_) {
    log_status("stopped; checkpoint written to {}; run the same command to resume", context_.job.output);
    result.status = kExitInterrupted;
    result.cube.reset();
    return result;
  }
  std::filesystem::remove(context_.job.output + ".journal");
  return result;
}

}  // namespace

MasterResult run_master(const CampaignContext& context, const CampaignOptions& options, Plan& plan,
                        const std::vector<TaskResult>& carried, int ranks) {
  Master master(context, options, plan, carried, ranks);
  return master.run();
}

}  // namespace rigid::campaign
