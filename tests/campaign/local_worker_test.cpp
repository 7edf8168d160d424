// The master's own simulation thread (campaign/local_worker) over the task pool
// (campaign/task_pool), with a stand-in for the simulation: every task the plan needs is run
// exactly once, cells the stop rule infers are never run, and a stopping campaign hands out
// nothing more. Oracles: the plan's grid and the stop rule's definition (plan.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <numeric>
#include <thread>
#include <vector>

#include "rigid/campaign/local_worker.hpp"
#include "rigid/campaign/task_pool.hpp"

namespace rigid::campaign {
namespace {

// Runs a local worker over `plan` until it ends; returns the tasks it ran, in order.
std::vector<std::int64_t> run_alone(Plan& plan, std::atomic<bool>& stopping, std::int32_t outcome) {
  TaskPool pool(plan, stopping);
  std::mutex mutex;
  std::vector<std::int64_t> ran;
  LocalWorker worker(
      pool,
      [outcome](std::int64_t t) {
        TaskResult r;
        r.task = t;
        r.outcome = outcome;
        return r;
      },
      [&](std::span<const TaskResult> results) {
        pool.complete(results);
        std::lock_guard<std::mutex> lock(mutex);
        for (const TaskResult& r : results) ran.push_back(r.task);
      },
      false);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!worker.done() && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(worker.done()) << "the worker did not end";
  stopping = true;  // ends it if it did not
  worker.join();
  EXPECT_TRUE(pool.over());
  return ran;
}

TEST(LocalWorker, RunsEveryTaskOnceWithoutTheStopRule) {
  Plan plan(2, 2, 3, 2, 0, {1.0, 2.0});  // 24 cells
  std::atomic<bool> stopping{false};
  std::vector<std::int64_t> ran =
      run_alone(plan, stopping, static_cast<std::int32_t>(scenario::CellOutcome::overturned));
  std::sort(ran.begin(), ran.end());
  std::vector<std::int64_t> every(24);
  std::iota(every.begin(), every.end(), 0);
  EXPECT_EQ(ran, every);
  EXPECT_EQ(plan.done(), 24);
  EXPECT_EQ(plan.in_flight(), 0);
}

TEST(LocalWorker, NeverRunsCellsTheStopRuleInfers) {
  // stop after 1 fully overturned scale: every cell overturns, so only scale 0 is simulated
  Plan plan(1, 2, 4, 3, 1, {1.0, 1.0});
  std::atomic<bool> stopping{false};
  const std::vector<std::int64_t> ran =
      run_alone(plan, stopping, static_cast<std::int32_t>(scenario::CellOutcome::overturned));
  EXPECT_EQ(ran.size(), 2u * 3u);  // 2 records x 3 rotations at scale 0
  for (std::int64_t t : ran) EXPECT_EQ(plan.cell(t).scale, 0) << "task " << t;
}

TEST(LocalWorker, AStoppingCampaignHandsOutNothing) {
  Plan plan(1, 1, 2, 2, 0, {1.0});
  std::atomic<bool> stopping{true};
  EXPECT_TRUE(run_alone(plan, stopping, static_cast<std::int32_t>(scenario::CellOutcome::survived)).empty());
  EXPECT_EQ(plan.in_flight(), 0);
  TaskPool pool(plan, stopping);
  const Handout h = pool.take_batch(4);
  EXPECT_TRUE(h.tasks.empty());
  EXPECT_TRUE(h.over);
}

}  // namespace
}  // namespace rigid::campaign
