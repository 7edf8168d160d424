// Rank 0's main thread does all MPI and progress while a second thread simulates tasks from the
// same plan, so on 2 ranks both cores simulate, and a third (the writer) does the file work.
//
// Checkpoints cost what changed. The journal is the durability layer: every result is appended
// and flushed to the kernel as it arrives (a kill loses nothing) and the journal is fsynced every
// checkpoint interval (a node crash loses at most one interval); that is the checkpoint, and its
// cost is the results since the last one, whatever the cube's size. The whole-cube rewrite
// (io::write_cube: OUT.tmp, fsync, rename) is only a compaction that lets the journal start over:
// the writer thread builds it from a shadow plan (the results up to a snapshot, taken by swapping
// one vector under the mutex, so dispatch never waits for the cube), and runs it only when the
// time since the last one started is at least max(checkpoint interval, K x its duration), K = 20
// (rewrites then take at most 1/K = 5 % of the wall time, of the disk's bandwidth and of the core
// the thread shares with a simulating rank), when the journal holds more records than the plan has
// cells (at least 64 MiB), on a stop signal and at the end. That size bound keeps the journal
// finite whatever happens, and costs nothing in a normal run: every cell is simulated once, so
// between two rewrites the journal holds at most one record per cell unless tasks are redone
// (after abandonments); a journal that reaches it outweighs the cube (292 bytes per record
// against about 87 per cell), and the master holds its records in memory too (as much as the
// plan's results). A tighter bound (say the cube's file size, as Redis rewrites its append-only
// file at 100 % growth) made the writer thread rewrite without pause when results arrive fast
// (no-op tasks: 1e5 per s), taking a core from dispatch on a shared node. The journal is reset
// to the results that arrived after the snapshot only once the new cube is renamed into place.
//
// Why not chunked in-place HDF5 updates: a kill (or a full disk) during an in-place write of the
// file's metadata (B-trees, heaps, superblock) can corrupt the only copy of the cube; HDF5 has no
// journaling of its own, and SWMR only protects concurrent readers from a live writer, not the
// file from a killed one. Why not per-rank shards merged at the end: the master already holds
// every result (it receives them to hand out the next batch), shards would multiply files by the
// rank count on shared file systems (metadata load, quotas) and need a merge step that can itself
// be interrupted. A log plus an atomically replaced snapshot keeps the one-file, valid-at-any-
// instant cube and makes its cost amortized.
#include "rigid/campaign/master.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
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

// Rewrites take at most 1/kRewriteFactor of the wall time (see the top of the file).
constexpr double kRewriteFactor = 20;
// The journal's size that forces a rewrite: the larger of this and one record per cell of the
// plan (unit: bytes; see the top of the file).
constexpr std::uint64_t kJournalFloorBytes = 64u << 20;

struct Master {
  Master(const CampaignContext& c, const CampaignOptions& o, Plan& p, int n)
      : context(c), job(c.job), options(o), plan(&p), output(c.job.output), ranks(n), shadow(p) {}

  const CampaignContext& context;
  const job::Job& job;
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

  std::vector<TaskResult> since_snapshot;  // results not in the cube being written (mutex)

  // The writer thread's state. `shadow` is the plan as of the last snapshot, without tasks in
  // flight: only the thread that rewrites touches it (the writer, or the main thread once the
  // writer has ended).
  Plan shadow;
  std::mutex writer_mutex;  // guards the fields below
  std::condition_variable writer_wake;
  bool sync_wanted = false, rewrite_wanted = false, rewrite_running = false, writer_quit = false;
  Clock::time_point last_rewrite_start;
  double last_rewrite_s = 0;      // duration of the last rewrite (unit: s)
  long rewrites = 0, syncs = 0;
  double longest_stall_s = 0;     // the longest time a rewrite held the mutex (unit: s)

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

  // The checkpoint proper: the journal's records to disk (fsync outside the mutex).
  void sync_journal() {
    int fd = -1;
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (!journal_ok) return;
      try {
        fd = journal->flush_and_duplicate();
      } catch (const std::exception& e) {
        journal_failed(e);
        return;
      }
    }
    try {
      journal->sync(fd);  // only reads the journal's path
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      journal_failed(e);
    }
    std::lock_guard<std::mutex> lock(writer_mutex);
    ++syncs;
  }

  // The compaction: writes the cube of every result up to a snapshot, then restarts the journal
  // with what arrived after it. False after a failure (recorded in `failure`); nothing is written
  // once one has happened. Runs on the writer thread, or on the main thread once that has ended.
  bool rewrite() {
    const auto t0 = Clock::now();
    std::vector<TaskResult> snapshot;
    double stall = 0;  // time the mutex is held, from when it is acquired
    {
      std::lock_guard<std::mutex> lock(mutex);
      const auto t = Clock::now();
      flush_journal();
      if (!failure.empty()) return false;
      snapshot.swap(since_snapshot);  // the whole snapshot: O(1) under the mutex
      stall += seconds_since(t);
    }
    for (const TaskResult& r : snapshot) shadow.complete(r);
    snapshot = {};
    try {
      // to OUT.tmp, renamed over OUT: the previous cube stays on failure
      io::write_cube(output, make_cube(context, shadow));
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      fail(output + ": checkpoint failed: " + reason_of(e, output) + " (results kept in the journal; run again to resume)");
      return false;
    }
    // the cube now holds everything but what arrived after the snapshot: journal only that,
    // written beside the journal without the mutex, then completed and renamed under it. The
    // results are moved out of since_snapshot (O(1) under the mutex) and put back before it.
    std::vector<TaskResult> kept;
    {
      std::lock_guard<std::mutex> lock(mutex);
      const auto t = Clock::now();
      if (!journal_ok) return false;  // the old journal, a superset, is still in place
      kept.swap(since_snapshot);
      stall += seconds_since(t);
    }
    bool moved_out = true;
    const auto put_back = [&] {  // caller holds the mutex: since_snapshot = kept + what came since
      if (!moved_out) return;
      kept.insert(kept.end(), since_snapshot.begin(), since_snapshot.end());
      kept.swap(since_snapshot);
      moved_out = false;
    };
    try {
      Journal::File fresh = journal->start_reset(kept);
      // what arrived meanwhile, in rounds, each moved out under the mutex and written without it,
      // until little is left (at most a few rounds: each is shorter than the one before)
      for (int round = 0; round < 4; ++round) {
        std::vector<TaskResult> more;
        {
          std::lock_guard<std::mutex> lock(mutex);
          if (since_snapshot.size() < 1024) break;
          more.swap(since_snapshot);
        }
        kept.insert(kept.end(), more.begin(), more.end());  // first: put back on failure
        journal->extend(fresh, more.data(), more.size());
      }
      // room for the rest, so that putting it back under the mutex copies only that
      kept.reserve(kept.size() + kept.size() / 4 + 4096);
      Journal::File replaced(nullptr, std::fclose);  // closed after the mutex is released
      std::lock_guard<std::mutex> lock(mutex);
      const auto t = Clock::now();
      try {
        replaced = journal->finish_reset(std::move(fresh), since_snapshot.data(), since_snapshot.size());
      } catch (...) {
        put_back();
        throw;
      }
      put_back();
      stall += seconds_since(t);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      put_back();
      journal_failed(e);  // the old journal, a superset, is still in place
      return false;
    }
    std::lock_guard<std::mutex> lock(writer_mutex);
    last_rewrite_start = t0;
    last_rewrite_s = seconds_since(t0);
    ++rewrites;
    longest_stall_s = std::max(longest_stall_s, stall);
    return true;
  }

  // The writer thread: journal syncs and rewrites, as asked by the main thread, one at a time.
  void writer() {
    std::unique_lock<std::mutex> lock(writer_mutex);
    for (;;) {
      writer_wake.wait(lock, [this] { return sync_wanted || rewrite_wanted || writer_quit; });
      if (writer_quit) return;  // what is pending is left to the final rewrite
      if (sync_wanted) {
        sync_wanted = false;
        lock.unlock();
        sync_journal();
        lock.lock();
      } else {
        rewrite_wanted = false;
        rewrite_running = true;
        lock.unlock();
        rewrite();
        lock.lock();
        rewrite_running = false;
      }
    }
  }
  void ask_writer(bool sync, bool rewrite) {
    {
      std::lock_guard<std::mutex> lock(writer_mutex);
      sync_wanted = sync_wanted || sync;
      rewrite_wanted = rewrite_wanted || rewrite;
    }
    writer_wake.notify_one();
  }
  // Whether a periodic rewrite is due: none asked or running, and the amortization rule (time
  // since the last one started >= max(interval, K x its duration)) or the journal's size.
  bool rewrite_due(double interval, std::uint64_t journal_bytes) {
    std::lock_guard<std::mutex> lock(writer_mutex);
    if (rewrite_wanted || rewrite_running) return false;
    if (journal_bytes >= std::max<std::uint64_t>(kJournalFloorBytes, std::uint64_t(plan->size()) * Journal::record_bytes())) return true;
    return seconds_since(last_rewrite_start) >= std::max(interval, kRewriteFactor * last_rewrite_s);
  }
  // Ends the writer thread (after what it is doing) so that the main thread may rewrite.
  void stop_writer(std::thread& w) {
    if (!w.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(writer_mutex);
      writer_quit = true;
    }
    writer_wake.notify_one();
    w.join();
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

  // A stop signal: no new tasks, and a checkpoint at once (the journal fsynced first, then a
  // rewrite, both on the writer thread, so results of tasks in flight are still received).
  // mpirun and batch systems follow a SIGTERM with a SIGKILL within seconds, often before the
  // in-flight tasks could finish; what they finish in the grace period goes into the final
  // checkpoint.
  void notice_stop_signal() {
    if (!stop_signal() || stopping) return;
    {
      std::lock_guard<std::mutex> lock(mutex);
      stopping = true;
      stop_since = Clock::now();
      std::fprintf(stderr, "\n");  // after a progress bar
      log_status("signal {}: no new tasks; checkpoint now, then up to {:g} s for {} in flight", stop_signal(), grace,
                 plan->in_flight());
    }
    ask_writer(true, true);
  }

  // caller holds the mutex
  void report_progress(bool final) {
    if (!options.on_progress) return;
    if (!final && seconds_since(last_progress) < options.progress_interval) return;
    last_progress = Clock::now();
    ProgressReport p;
    p.done = plan->done();
    p.remaining = plan->remaining();
    // a fixed denominator: every cell is settled at the end, inferred ones as the rule infers them
    p.settled = plan->size() - p.remaining - plan->in_flight();
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
  [[noreturn]] void abandon(std::thread& w) {
    stopping = true;
    stop_writer(w);
    const bool written = rewrite();
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
    if (rewrite()) {
      log_status("{} tasks, {} already done, {} ranks, output {}", plan->size(), plan->done(), ranks, output);
    }
    std::thread local([this] { local_worker(); });
    std::thread writing([this] { writer(); });
    std::vector<int> waiting;  // worker ranks whose request is unanswered
    auto last_checkpoint = Clock::now();
    const double checkpoint_interval = options.checkpoint_interval > 0 ? options.checkpoint_interval : job.checkpoint_interval;
    for (;;) {
      const bool busy = receive_results(waiting);
      notice_stop_signal();
      answer_requests(waiting);
      std::uint64_t journal_bytes = 0;
      {
        std::lock_guard<std::mutex> lock(mutex);
        flush_journal();
        report_progress(false);
        if (journal_ok) journal_bytes = journal->bytes();
      }
      const bool sync = seconds_since(last_checkpoint) >= checkpoint_interval;
      if (sync) last_checkpoint = Clock::now();
      const bool rewrite = !stopping && rewrite_due(checkpoint_interval, journal_bytes);
      if (sync || rewrite) ask_writer(sync, rewrite);
      if (everyone_done()) break;
      if (stopping && !stop_since) stop_since = Clock::now();  // stopped by a failed write
      if (stopping && seconds_since(*stop_since) > grace) abandon(writing);
      if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    local.join();
    stop_writer(writing);
    return finish();
  }

  // After the loop: the last checkpoint, and the status.
  MasterResult finish() {
    rewrite();
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
    if (ranks > 1 && options.verbose) {  // dispatch internals: for whoever tunes the dispatch
      log_status("{} tasks sent to {} worker ranks in {} messages ({:.0f} tasks/s over {:.2f} s)", remote_tasks, ranks - 1,
                 remote_messages, double(remote_tasks) / seconds_since(started), seconds_since(started));
      std::lock_guard<std::mutex> lock(writer_mutex);
      log_status("checkpoints: {} journal syncs, {} cube rewrites (the last {:.2f} s), dispatch held at most {:.2f} ms by one",
                 syncs, rewrites, last_rewrite_s, 1e3 * longest_stall_s);
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
