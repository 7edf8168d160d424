// Rank 0's main thread does all MPI, checkpoints and progress while a second thread simulates
// tasks from the same plan, so on 2 ranks both cores simulate. Every result is journalled at once
// and the cube is rewritten atomically every checkpoint interval.
#include "rigid/campaign/master.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/log.hpp"
#include "rigid/campaign/stop_signal.hpp"
#include "rigid/campaign/task.hpp"
#include "rigid/campaign/transport.hpp"

namespace rigid::campaign {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// What follows an InputError's "FILE: " prefix, when FILE is `file`.
std::string reason_of(const std::exception& e, const std::string& file) {
  const std::string what = e.what();
  const std::string prefix = file + ": ";
  return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
}

struct Master {
  Master(const CampaignContext& c, const CampaignOptions& o, Plan& p, int n)
      : context(c), job(c.job), options(o), plan(&p), output(c.job.output), ranks(n) {}

  const CampaignContext& context;
  const scenario::Job& job;
  const CampaignOptions& options;
  MasterTransport transport;

  Plan* plan;  // guarded by mutex, like journal and failure
  std::string output;
  int ranks = 1;
  std::mutex mutex;
  std::unique_ptr<Journal> journal;
  bool journal_ok = false;
  // The first failed write, as printed. A failure ends the campaign, not the process: dispatch
  // stops, every rank is told to stop, the local thread is joined, and the last good cube and the
  // journal stay as they were (both are only ever replaced by a rename).
  std::string failure;
  std::atomic<bool> stopping{false};
  std::atomic<bool> local_done{false};
  double mean_wall = 0.05;  // running mean task wall time, for batch sizes (unit: s)
  long remote_tasks = 0, remote_messages = 0;  // handed to other ranks
  int active_workers = ranks - 1;              // worker ranks not yet told to stop
  std::vector<TaskResult> inbox;               // one worker message
  const double grace = options.grace >= 0 ? options.grace : job.grace;
  std::optional<Clock::time_point> stop_since;
  Clock::time_point started, last_progress;
  long done_at_start = 0;

  std::vector<TaskResult> since_snapshot;  // results not in the cube being written

  // caller holds the mutex
  void fail(const std::string& message) {
    if (failure.empty()) failure = message;
    stopping = true;
  }
  void journal_failed(const std::exception& e) {
    journal_ok = false;
    fail(std::string(e.what()) + " (the cube and the journal keep what was written; run again to resume)");
  }
  void flush_journal() {
    if (!journal_ok) return;
    try {
      journal->flush();
    } catch (const std::exception& e) {
      journal_failed(e);
    }
  }

  void record(const TaskResult& r) {
    plan->complete(r);
    since_snapshot.push_back(r);
    mean_wall = 0.9 * mean_wall + 0.1 * r.wall_s;
    // after a failed cube write the journal still takes results: they are kept for the resume
    if (!journal_ok) return;
    try {
      journal->append(r);
    } catch (const std::exception& e) {
      journal_failed(e);
    }
  }

  // the master's own simulations, on a second thread that never calls MPI; with --noop on
  // several ranks it stays idle, so the run measures what the master alone can hand out
  void local_worker() {
    const bool idle = options.noop && ranks > 1;
    for (;;) {
      if (idle) break;
      std::optional<long> t;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (stopping || plan->finished()) break;
        t = plan->next();
      }
      if (!t) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        continue;
      }
      const TaskResult r = run_task(job, context.model, *t, options.noop);
      std::lock_guard<std::mutex> lock(mutex);
      record(r);
    }
    local_done = true;
  }

  // tasks for one request: about a quarter second of work, fewer near the end
  std::vector<std::int64_t> batch() {
    const long left = plan->size() - plan->done() - plan->in_flight();
    const long want = std::clamp(long(0.25 / std::max(mean_wall, 1e-6)), 1L,
                                 std::max(1L, std::min(256L, left / (2L * ranks))));
    std::vector<std::int64_t> ids;
    while (long(ids.size()) < want) {
      const auto t = plan->next();
      if (!t) break;
      ids.push_back(*t);
    }
    return ids;
  }

  // Writes the cube, then restarts the journal. False after a failure (recorded in `failure`);
  // nothing is written once one has happened.
  bool checkpoint() {
    io::Cube cube;
    {
      std::lock_guard<std::mutex> lock(mutex);
      flush_journal();
      if (!failure.empty()) return false;
      cube = make_cube(context, *plan);
      since_snapshot.clear();
    }
    try {
      io::write_cube(output, cube);  // to OUT.tmp, renamed over OUT: the previous cube stays on failure
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      fail(output + ": checkpoint failed: " + reason_of(e, output) +
           " (results kept in the journal; run again to resume)");
      return false;
    }
    std::lock_guard<std::mutex> lock(mutex);
    // the cube now holds everything but what arrived while it was written: journal only that
    try {
      journal->reset(since_snapshot);
    } catch (const std::exception& e) {
      journal_failed(e);  // the old journal, a superset, is still in place
      return false;
    }
    return true;
  }

  // One pass of the dispatch loop's receiving end: every pending worker message is recorded and
  // its rank queued for an answer. True when something arrived.
  bool receive_results(std::vector<int>& waiting) {
    bool busy = false;
    int rank = 0;
    while (transport.receive(inbox, rank)) {
      busy = true;
      std::lock_guard<std::mutex> lock(mutex);
      for (const auto& r : inbox) record(r);
      flush_journal();
      waiting.push_back(rank);
    }
    return busy;
  }

  // Hands out work, or stops workers that will get none; a worker with nothing to do now keeps
  // waiting (tasks in flight may unblock more).
  void answer_requests(std::vector<int>& waiting) {
    for (auto it = waiting.begin(); it != waiting.end();) {
      std::vector<std::int64_t> ids;
      bool stop = false;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (!stopping) ids = batch();
        stop = ids.empty() && (stopping || plan->finished());
      }
      if (!ids.empty()) {
        transport.send_tasks(*it, ids);
        remote_tasks += long(ids.size());
        ++remote_messages;
        it = waiting.erase(it);
      } else if (stop) {
        transport.send_stop(*it);
        --active_workers;
        it = waiting.erase(it);
      } else {
        ++it;
      }
    }
  }

  // A stop signal: no new tasks, and a checkpoint at once. mpirun and batch systems follow a
  // SIGTERM with a SIGKILL within seconds, often before the in-flight tasks could finish; what
  // they finish in the grace period goes into the final checkpoint.
  // True when a checkpoint was written here.
  bool notice_stop_signal() {
    if (!stop_signal() || stopping) return false;
    {
      std::lock_guard<std::mutex> lock(mutex);
      stopping = true;
      stop_since = Clock::now();
      std::fprintf(stderr, "\n");  // after a progress bar
      log_status("signal {}: no new tasks; checkpoint now, then up to {:g} s for {} in flight", stop_signal(), grace,
                 plan->in_flight());
    }
    return checkpoint();
  }

  // caller holds the mutex
  void report_progress(bool final) {
    if (!options.on_progress) return;
    if (!final && seconds_since(last_progress) < options.progress_interval) return;
    last_progress = Clock::now();
    ProgressReport p;
    p.done = plan->done();
    p.remaining = plan->remaining();
    p.failures = plan->failures();
    p.done_at_start = done_at_start;
    p.total = plan->size();
    p.elapsed_s = seconds_since(started);
    p.final = final;
    options.on_progress(p);
  }

  bool everyone_done() {
    std::lock_guard<std::mutex> lock(mutex);
    return active_workers == 0 && local_done && (stopping || plan->finished());
  }

  // The grace period after a stop is over: in-flight work is given up, what is done is
  // checkpointed and every rank ends.
  [[noreturn]] void abandon() {
    stopping = true;
    const bool written = checkpoint();
    {
      std::lock_guard<std::mutex> lock(mutex);  // the local thread may still be recording
      log_status("grace period over; {} tasks abandoned (redone on resume)", plan->in_flight());
      if (!written) std::fprintf(stderr, "rigid: error: %s\n", failure.c_str());
    }
    std::fflush(stderr);
    abort_all_ranks(written ? kExitInterrupted : kExitIoFailure);
  }

  MasterResult run(const std::vector<TaskResult>& carried) {
    started = last_progress = Clock::now();
    done_at_start = plan->done();
    try {
      journal = std::make_unique<Journal>(output + ".journal", context.inputs.combined, carried);
      journal_ok = true;
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      journal_failed(e);
    }
    // the restored results go into the cube at once, which also proves the output writable; on a
    // failure the loop below only tells the workers to stop
    if (checkpoint()) {
      log_status("{} tasks, {} already done, {} ranks, output {}", plan->size(), plan->done(), ranks, output);
    }
    std::thread local([this] { local_worker(); });
    std::vector<int> waiting;  // worker ranks whose request is unanswered
    auto last_checkpoint = Clock::now();
    const double checkpoint_interval = options.checkpoint_interval > 0 ? options.checkpoint_interval : job.checkpoint_interval;
    for (;;) {
      const bool busy = receive_results(waiting);
      if (notice_stop_signal()) last_checkpoint = Clock::now();
      answer_requests(waiting);
      {
        std::lock_guard<std::mutex> lock(mutex);
        flush_journal();
        report_progress(false);
      }
      if (seconds_since(last_checkpoint) >= checkpoint_interval) {
        checkpoint();
        last_checkpoint = Clock::now();
      }
      if (everyone_done()) break;
      if (stopping && !stop_since) stop_since = Clock::now();  // stopped by a failed write
      if (stopping && seconds_since(*stop_since) > grace) abandon();
      if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    local.join();
    return finish();
  }

  // After the loop: the last checkpoint, and the status.
  MasterResult finish() {
    checkpoint();
    MasterResult result;
    {
      std::lock_guard<std::mutex> lock(mutex);
      report_progress(true);
      if (!failure.empty()) {
        std::fprintf(stderr, "rigid: error: %s\n", failure.c_str());
        result.status = kExitIoFailure;
        return result;
      }
      result.cube = make_cube(context, *plan);
    }
    if (ranks > 1) {
      log_status("{} tasks sent to {} worker ranks in {} messages ({:.0f} tasks/s over {:.2f} s)", remote_tasks, ranks - 1,
                 remote_messages, double(remote_tasks) / seconds_since(started), seconds_since(started));
    }
    if (stopping) {
      log_status("stopped; checkpoint written to {}; run the same command to resume", output);
      result.status = kExitInterrupted;
      result.cube.reset();
      return result;
    }
    std::filesystem::remove(output + ".journal");
    return result;
  }
};

}  // namespace

MasterResult run_master(const CampaignContext& context, const CampaignOptions& options, Plan& plan,
                        const std::vector<TaskResult>& carried, int ranks) {
  Master master(context, options, plan, ranks);
  return master.run(carried);
}

}  // namespace rigid::campaign
