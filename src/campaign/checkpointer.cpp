// Checkpoints cost what changed. The journal is the durability layer: every result is appended
// and flushed to the kernel as it arrives (a kill loses nothing) and the journal is fsynced every
// checkpoint interval (a node crash loses at most one interval); that is the checkpoint, and its
// cost is the results since the last one, whatever the cube's size. The whole-cube rewrite
// (io::write_cube: OUT.tmp, fsync, rename) is only a compaction that lets the journal start over:
// it is built from a shadow plan (the results up to a snapshot, taken by swapping one vector
// under the lock, so dispatch never waits for the cube), and runs only when the time since the
// last one started is at least max(checkpoint interval, K x its duration), K = 20 (rewrites then
// take at most 1/K = 5 % of the wall time, of the disk's bandwidth and of the core the writer
// thread shares with a simulating rank), when the journal holds more records than the plan has
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
#include "rigid/campaign/checkpointer.hpp"

#include <algorithm>
#include <cstdio>

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

}  // namespace

Checkpointer::Checkpointer(std::string output, std::string key, const Plan& restored, CubeOf cube_of,
                           const std::vector<TaskResult>& carried, std::atomic<bool>& stop)
    : output_(std::move(output)), cube_of_(std::move(cube_of)), stop_(stop), shadow_(restored) {
  journal_limit_bytes_ =
      std::max<std::uint64_t>(kJournalFloorBytes, std::uint64_t(restored.size()) * Journal::record_bytes());
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    journal_ = std::make_unique<Journal>(output_ + ".journal", std::move(key), carried);
    journal_ok_ = true;
  } catch (const std::exception& e) {
    journal_failed(e);
  }
}

void Checkpointer::fail(const std::string& message) {
  if (failure_.empty()) failure_ = message;
  stop_ = true;
}

void Checkpointer::journal_failed(const std::exception& e) {
  journal_ok_ = false;
  fail(std::string(e.what()) + " (the cube and the journal keep what was written; run again to resume)");
}

void Checkpointer::flush_locked() {
  if (!journal_ok_) return;
  try {
    journal_->flush();
  } catch (const std::exception& e) {
    journal_failed(e);
  }
}

void Checkpointer::record(std::span<const TaskResult> results) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const TaskResult& r : results) {
    since_snapshot_.push_back(r);
    if (!journal_ok_) continue;
    try {
      journal_->append(r);
    } catch (const std::exception& e) {
      journal_failed(e);
    }
  }
}

void Checkpointer::flush() {
  std::lock_guard<std::mutex> lock(mutex_);
  flush_locked();
}

void Checkpointer::sync() {
  int fd = -1;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!journal_ok_) return;
    try {
      fd = journal_->flush_and_duplicate();
    } catch (const std::exception& e) {
      journal_failed(e);
      return;
    }
  }
  try {
    journal_->sync(fd);  // only reads the journal's path
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    journal_failed(e);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  ++stats_.syncs;
}

bool Checkpointer::rewrite() {
  std::lock_guard<std::mutex> rewriting(rewrite_mutex_);
  const auto t0 = Clock::now();
  double stall_s = 0;  // time mutex_ is held, from when it is acquired
  if (!take_snapshot(stall_s) || !write_shadow_cube() || !restart_journal(stall_s)) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  stats_.last_rewrite_start = t0;
  stats_.last_rewrite_s = seconds_since(t0);
  ++stats_.rewrites;
  stats_.longest_stall_s = std::max(stats_.longest_stall_s, stall_s);
  return true;
}

// Moves every result since the last snapshot into the shadow plan (the swap is O(1) under the
// lock; the shadow is only ever touched under rewrite_mutex_).
bool Checkpointer::take_snapshot(double& stall_s) {
  std::vector<TaskResult> snapshot;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto t = Clock::now();
    flush_locked();
    if (!failure_.empty()) return false;
    snapshot.swap(since_snapshot_);
    stall_s += seconds_since(t);
  }
  for (const TaskResult& r : snapshot) shadow_.complete(r);
  return true;
}

bool Checkpointer::write_shadow_cube() {
  try {
    // to OUT.tmp, renamed over OUT: the previous cube stays on failure
    io::write_cube(output_, cube_of_(shadow_));
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    fail(output_ + ": checkpoint failed: " + reason_of(e, output_) +
         " (results kept in the journal; run again to resume)");
    return false;
  }
  return true;
}

// The cube now holds everything but what arrived after the snapshot: journal only that, written
// beside the journal without the lock, then completed and renamed under it. The results are
// moved out of since_snapshot_ (O(1) under the lock) and put back before it is released.
bool Checkpointer::restart_journal(double& stall_s) {
  std::vector<TaskResult> kept;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto t = Clock::now();
    if (!journal_ok_) return false;  // the old journal, a superset, is still in place
    kept.swap(since_snapshot_);
    stall_s += seconds_since(t);
  }
  bool moved_out = true;
  const auto put_back = [&] {  // caller holds mutex_: since_snapshot_ = kept + what came since
    if (!moved_out) return;
    kept.insert(kept.end(), since_snapshot_.begin(), since_snapshot_.end());
    kept.swap(since_snapshot_);
    moved_out = false;
  };
  try {
    // start_reset and extend only read the journal's path and key: no lock needed
    Journal::File fresh = journal_->start_reset(kept);
    // what arrived meanwhile, in rounds, each moved out under the lock and written without it,
    // until little is left (at most a few rounds: each is shorter than the one before)
    for (int round = 0; round < 4; ++round) {
      std::vector<TaskResult> more;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (since_snapshot_.size() < 1024) break;
        more.swap(since_snapshot_);
      }
      kept.insert(kept.end(), more.begin(), more.end());  // first: put back on failure
      journal_->extend(fresh, more.data(), more.size());
    }
    // room for the rest, so that putting it back under the lock copies only that
    kept.reserve(kept.size() + kept.size() / 4 + 4096);
    Journal::File replaced(nullptr, std::fclose);  // closed after the lock is released
    std::lock_guard<std::mutex> lock(mutex_);
    const auto t = Clock::now();
    try {
      replaced = journal_->finish_reset(std::move(fresh), since_snapshot_.data(), since_snapshot_.size());
    } catch (...) {
      put_back();
      throw;
    }
    put_back();
    stall_s += seconds_since(t);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    put_back();
    journal_failed(e);  // the old journal, a superset, is still in place
    return false;
  }
  return true;
}

bool Checkpointer::rewrite_due(double interval_s) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (journal_ok_ && journal_->bytes() >= journal_limit_bytes_) return true;
  return seconds_since(stats_.last_rewrite_start) >= std::max(interval_s, kRewriteFactor * stats_.last_rewrite_s);
}

std::string Checkpointer::failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

CheckpointStats Checkpointer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace rigid::campaign
