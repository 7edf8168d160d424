// The task plan: the stop rule's inferred cells depend on outcomes alone (any dispatch order,
// any interleaving of completions, any restart), and rotation angles depend on the cell alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "rigid/campaign/plan.hpp"

namespace rigid::campaign {
namespace {

using scenario::CellOutcome;

// A fixed "physics": the block overturns at scale >= threshold[record], except a few holes.
CellOutcome truth(const Cell& c) {
  static const int threshold[3] = {3, 1, 100};
  if (c.record == 0 && c.scale == 5 && c.rotation == 1) return CellOutcome::survived;  // non-monotone
  return c.scale >= threshold[c.record] ? CellOutcome::overturned : CellOutcome::survived;
}

TaskResult result_of(const Plan& p, long t) {
  TaskResult r;
  r.task = t;
  r.outcome = static_cast<std::int32_t>(truth(p.cell(t)));
  r.max_tilt_deg = double(t);
  return r;
}

// Runs the plan with `workers` tasks in flight at once, completing them in a shuffled order,
// optionally "killed" (in-flight work dropped) and restored from its results every `restart`
// completions.
std::vector<std::int8_t> run_plan(unsigned seed, int workers, int restart) {
  const int O = 2, R = 3, S = 12, A = 2, N = 3;
  std::mt19937 rng(seed);
  Plan plan(O, R, S, A, N, {5.0, 1.0, 3.0});
  std::vector<TaskResult> saved;
  std::vector<long> flight;
  int completed = 0;
  for (int guard = 0; guard < 100000; ++guard) {
    while (int(flight.size()) < workers) {
      const auto t = plan.next();
      if (!t) break;
      flight.push_back(*t);
    }
    if (flight.empty()) {
      if (plan.finished()) break;
      ADD_FAILURE() << "nothing in flight but the plan is not finished";
      break;
    }
    std::uniform_int_distribution<std::size_t> pick(0, flight.size() - 1);
    const std::size_t i = pick(rng);
    const TaskResult r = result_of(plan, flight[i]);
    flight.erase(flight.begin() + long(i));
    plan.complete(r);
    saved.push_back(r);
    if (restart > 0 && ++completed % restart == 0) {
      // a kill: in-flight work is lost, the results on disk are restored into a new plan
      Plan fresh(O, R, S, A, N, {5.0, 1.0, 3.0});
      for (const auto& s : saved) fresh.restore(s);
      plan = fresh;
      flight.clear();
    }
  }
  EXPECT_TRUE(plan.finished());
  return plan.final_outcomes();
}

TEST(Plan, InferredCellsDependOnOutcomesAloneNotOnOrderOrRestarts) {
  const auto reference = run_plan(1, 1, 0);
  for (unsigned seed : {2u, 3u, 4u}) {
    for (int workers : {1, 2, 3, 8, 64}) {
      EXPECT_EQ(run_plan(seed, workers, 0), reference) << "seed " << seed << ", " << workers << " in flight";
      EXPECT_EQ(run_plan(seed, workers, 7), reference) << "with restarts, seed " << seed;
    }
  }
}

TEST(Plan, StopRuleInfersAboveNConsecutiveFullyOverturnedScales) {
  const auto out = run_plan(1, 1, 0);
  const int R = 3, S = 12, A = 2;
  auto at = [&](int o, int r, int s, int k) { return static_cast<CellOutcome>(out[((o * R + r) * S + s) * A + k]); };
  for (int o = 0; o < 2; ++o) {
    // record 0 overturns from scale 3 but survives once at scale 5: runs are 3-4, then 6-8,
    // so scales 9.. are inferred (N = 3)
    for (int s = 0; s < 9; ++s) EXPECT_NE(at(o, 0, s, 0), CellOutcome::inferred) << s;
    for (int s = 9; s < S; ++s) EXPECT_EQ(at(o, 0, s, 1), CellOutcome::inferred) << s;
    EXPECT_EQ(at(o, 0, 5, 1), CellOutcome::survived);
    // record 1 overturns from scale 1: scales 1-3 simulated, 4.. inferred
    EXPECT_EQ(at(o, 1, 3, 0), CellOutcome::overturned);
    EXPECT_EQ(at(o, 1, 4, 0), CellOutcome::inferred);
    // record 2 never overturns: everything simulated
    for (int s = 0; s < S; ++s) EXPECT_EQ(at(o, 2, s, 0), CellOutcome::survived);
  }
}

TEST(Plan, NoStopRuleSimulatesEveryCell) {
  Plan plan(1, 2, 4, 2, 0, {});
  long n = 0;
  while (auto t = plan.next()) {
    TaskResult r;
    r.task = *t;
    r.outcome = static_cast<std::int32_t>(CellOutcome::overturned);
    plan.complete(r);
    ++n;
  }
  EXPECT_EQ(n, plan.size());
  EXPECT_TRUE(plan.finished());
}

TEST(Plan, LowScalesFirstAndLongestRecordFirstWithinAScale) {
  Plan plan(1, 3, 2, 1, 0, {1.0, 9.0, 4.0});
  std::vector<Cell> order;
  while (auto t = plan.next()) order.push_back(plan.cell(*t));
  ASSERT_EQ(order.size(), 6u);
  EXPECT_EQ(order[0].scale, 0);
  EXPECT_EQ(order[0].record, 1);
  EXPECT_EQ(order[1].record, 2);
  EXPECT_EQ(order[2].record, 0);
  EXPECT_EQ(order[3].scale, 1);
}

TEST(RotationAngle, DependsOnlyOnSeedAndCellAndFillsTheCircle) {
  const double a = rotation_angle_deg(42, {0, 1, 2, 3});
  EXPECT_EQ(a, rotation_angle_deg(42, {0, 1, 2, 3}));
  EXPECT_NE(a, rotation_angle_deg(43, {0, 1, 2, 3}));
  EXPECT_NE(a, rotation_angle_deg(42, {0, 1, 2, 4}));
  // uniform on [0, 360): 10 bins of 5000 draws each within 5 sigma
  std::vector<int> bins(10, 0);
  for (int r = 0; r < 100; ++r) {
    for (int s = 0; s < 250; ++s) {
      for (int k = 0; k < 2; ++k) {
        const double d = rotation_angle_deg(7, {0, r, s, k});
        ASSERT_GE(d, 0.0);
        ASSERT_LT(d, 360.0);
        ++bins[int(d / 36.0)];
      }
    }
  }
  for (int b : bins) EXPECT_NEAR(b, 5000, 5 * std::sqrt(5000.0 * 0.9));
}

}  // namespace
}  // namespace rigid::campaign
