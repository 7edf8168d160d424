// What a checkpoint costs the campaign master (src/campaign/checkpointer.cpp), against the cube's size:
//   (a) the checkpoint proper: appending the results of one checkpoint interval to the journal
//       and fsyncing it (what the master does every 30 s; the journal does not depend on the cube),
//   (b) the whole-cube rewrite (io::write_cube, now a background compaction) and the period the
//       amortization rule gives it: max(30 s, 20 x its duration),
//   (c) the dispatch stall per rewrite: the time the master's mutex is held (the snapshot, a swap
//       of the results since the last one; the swap of those that arrived during the write; the
//       new journal's tail, rename and the putting back of those results), against copying the
//       plan's arrays under the mutex (the alternative) and the old scheme (the whole rewrite on
//       the dispatch thread, at least the write itself: make_cube comes on top).
// Assumed load: a 500-rank job whose tasks take 0.25 s on average (real tasks take 0.05 to 1 s),
// so 2,000 results/s, 60,000 per 30-s interval (17.5 MB of journal).
//
//   cmake --build build --target checkpoint_bench && build/tests/checkpoint_bench [DIR]
//
// DIR (default: the temporary directory) is where the cube and journal are written: use the file
// system the campaign writes to. Medians of 3. A benchmark, not a test.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/plan.hpp"
#include "study_cube.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using rigid::campaign::Journal;
using rigid::campaign::Plan;
using rigid::campaign::TaskResult;

constexpr double kResultsPerSecond = 2000;  // 500 ranks, 0.25-s tasks
constexpr double kInterval = 30;            // s
constexpr double kRewriteFactor = 20;       // checkpointer.cpp's K

double seconds(const std::function<void()>& f) {
  const auto t0 = Clock::now();
  f();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median3(const std::function<double()>& f) {
  std::vector<double> t{f(), f(), f()};
  std::sort(t.begin(), t.end());
  return t[1];
}

std::vector<TaskResult> results(long n, long first, long cells) {
  std::vector<TaskResult> out(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    TaskResult& r = out[static_cast<std::size_t>(i)];
    r.task = (first + i) % cells;
    r.outcome = 1 + int(i % 2);
    r.failure_time_s = 3.5;
    r.max_tilt_deg = 12.5;
    r.max_slip_m = 0.01;
    r.wall_s = 0.25;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path dir = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path();
  const std::string cube_path = (dir / "rigid_checkpoint_bench.h5").string();
  const std::string journal_path = cube_path + ".journal";
  const long batch = long(kResultsPerSecond * kInterval);
  std::printf("load: %.0f results/s, %ld per %.0f-s checkpoint (%.1f MB of journal); files in %s\n", kResultsPerSecond,
              batch, kInterval, double(batch * Journal::record_bytes()) / 1e6, dir.c_str());
  std::printf("%10s | %14s %9s | %12s %9s %11s | %12s %14s %14s\n", "cells", "(a) checkpoint", "fsync", "(b) rewrite",
              "file MB", "period s", "(c) stall ms", "copy plan ms", "old stall >= s");
  for (const long want : {10'000L, 100'000L, 1'000'000L, 5'000'000L}) {
    const rigid::io::Cube cube = rigid_bench::study_layout_cube(want);
    const long cells = long(cube.objects.size()) * rigid_bench::kCellsPerObject;

    // (a) one interval's results appended (as they arrive), flushed, fsynced
    Journal journal(journal_path, std::string(64, 'k'));
    const std::vector<TaskResult> interval = results(batch, 0, cells);
    double fsync_s = 0;
    const double checkpoint = median3([&] {
      int fd = -1;
      const double append = seconds([&] {
        for (const TaskResult& r : interval) journal.append(r);
        fd = journal.flush_and_duplicate();
      });
      const double sync = seconds([&] { journal.sync(fd); });
      fsync_s = sync;  // (of the last run)
      return append + sync;
    });

    // (b) the whole-cube rewrite
    const double rewrite = median3([&] { return seconds([&] { rigid::io::write_cube(cube_path, cube); }); });
    const double period = std::max(kInterval, kRewriteFactor * rewrite);
    const double file_mb = double(fs::file_size(cube_path)) / 1e6;

    // (c) what the master holds its mutex for around one rewrite (as in Master::rewrite)
    const long during = std::max(1L, long(kResultsPerSecond * rewrite));  // arrive while it writes
    const double stall = median3([&] {
      std::vector<TaskResult> since_snapshot = results(batch, 0, cells), snapshot;
      double held = seconds([&] { snapshot.swap(since_snapshot); });
      since_snapshot = results(during, batch, cells);
      std::vector<TaskResult> kept;
      held += seconds([&] { kept.swap(since_snapshot); });
      Journal::File fresh = journal.start_reset(kept);  // without the mutex
      kept.reserve(kept.size() + kept.size() / 4 + 4096);
      since_snapshot = results(std::max(1L, during / 20), batch + during, cells);  // arrived meanwhile
      Journal::File replaced(nullptr, std::fclose);  // closed after the mutex, as in the master
      held += seconds([&] {
        replaced = journal.finish_reset(std::move(fresh), since_snapshot.data(), since_snapshot.size());
        kept.insert(kept.end(), since_snapshot.begin(), since_snapshot.end());
        kept.swap(since_snapshot);
      });
      return held;
    });
    // the alternative snapshot: the plan's arrays copied under the mutex
    Plan plan(int(cube.objects.size()), rigid_bench::kRecords, rigid_bench::kScales, rigid_bench::kRotations, 0, {});
    for (const TaskResult& r : results(cells, 0, cells)) {
      plan.next();
      plan.complete(r);
    }
    const double copy = median3([&] {
      double t = 0;
      {
        std::vector<Plan> copies;
        copies.reserve(1);
        t = seconds([&] { copies.push_back(plan); });
      }
      return t;
    });
    std::printf("%10ld | %11.1f ms %6.1f ms | %10.3f s %9.1f %11.0f | %12.3f %14.1f %14.2f\n", cells, 1e3 * checkpoint,
                1e3 * fsync_s, rewrite, file_mb, period, 1e3 * stall, 1e3 * copy, rewrite);
    fs::remove(cube_path);
  }
  fs::remove(journal_path);
  return 0;
}
