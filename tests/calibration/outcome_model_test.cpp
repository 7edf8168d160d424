// The calibration's outcome model against hand computation and planted truths: likelihoods of a
// grid small enough to sum by hand, the heading window on the circle, the scores of a known
// confusion matrix, and recovery of a planted (variant, heading) from outcomes drawn from it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rigid/calibration/outcome_model.hpp"

namespace rigid::calibration {
namespace {

TEST(OutcomeModel, WindowWrapsAroundTheCircle) {
  OutcomeGrid grid(1, 1, {0, 30, 60, 300, 330});
  EXPECT_EQ(grid.window(0, 0), (std::vector<int>{0}));
  EXPECT_EQ(grid.window(0, 30), (std::vector<int>{0, 1, 4}));
  EXPECT_EQ(grid.window(4, 40), (std::vector<int>{0, 3, 4}));
  EXPECT_THROW(OutcomeGrid(1, 1, {0, 360}), std::invalid_argument);
}

TEST(OutcomeModel, LikelihoodIsTheHandSum) {
  // one variant, three tests, two headings 0 and 90; test 0 overturns at both, test 1 at 0 only,
  // test 2 at neither
  OutcomeGrid grid(1, 3, {0, 90});
  grid.set(0, 0, 0, true);
  grid.set(0, 0, 1, true);
  grid.set(0, 1, 0, true);
  const std::vector<int> y{1, 0, 0};
  const std::vector<bool> all(3, true);
  // centre 0, spread 90: p = 1, 1/2, 0 before the lapse; lapse 0.2 maps p to 0.1 + 0.8 p
  const Candidate c{0, 0, 90, 0.2, 0};
  const double expected = std::log(0.9) + std::log(1 - 0.5) + std::log(1 - 0.1);
  EXPECT_NEAR(log_likelihood(grid, c, y, all), expected, 1e-12);
  EXPECT_NEAR(overturn_probability(grid, c, 1), 0.5, 1e-12);
  // only test 2 used
  EXPECT_NEAR(log_likelihood(grid, c, y, {false, false, true}), std::log(0.9), 1e-12);
}

TEST(OutcomeModel, JoinedGridsKeepEachCellAndRefuseOtherHeadings) {
  OutcomeGrid a(1, 2, {0, 10}), b(2, 2, {0, 10});
  a.set(0, 1, 0, true);
  b.set(1, 0, 1, true);
  const OutcomeGrid joined = join_variants(a, b);
  ASSERT_EQ(joined.variants(), 3);
  int overturned = 0;
  for (int v = 0; v < 3; ++v) {
    for (int t = 0; t < 2; ++t) {
      for (int h = 0; h < 2; ++h) overturned += joined.overturned(v, t, h) ? 1 : 0;
    }
  }
  EXPECT_EQ(overturned, 2);
  EXPECT_TRUE(joined.overturned(0, 1, 0));  // a's variant 0
  EXPECT_TRUE(joined.overturned(2, 0, 1));  // b's variant 1, after a's one
  EXPECT_THROW(join_variants(a, OutcomeGrid(1, 2, {0, 20})), std::invalid_argument);
  EXPECT_THROW(join_variants(a, OutcomeGrid(1, 3, {0, 10})), std::invalid_argument);
}

TEST(OutcomeModel, ScoresOfAKnownConfusionMatrix) {
  // tp 2, fn 1, fp 1, tn 4
  const std::vector<double> p{0.9, 0.6, 0.2, 0.7, 0.1, 0.0, 0.4, 0.3};
  const std::vector<int> y{1, 1, 1, 0, 0, 0, 0, 0};
  const Scores s = score(p, y);
  EXPECT_EQ(s.true_positive, 2);
  EXPECT_EQ(s.false_negative, 1);
  EXPECT_EQ(s.false_positive, 1);
  EXPECT_EQ(s.true_negative, 4);
  EXPECT_NEAR(s.accuracy, 6.0 / 8, 1e-12);
  EXPECT_NEAR(s.recall, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.precision, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.balanced_accuracy, 0.5 * (2.0 / 3 + 4.0 / 5), 1e-12);
  const double brier = (0.01 + 0.16 + 0.64 + 0.49 + 0.01 + 0 + 0.16 + 0.09) / 8;
  EXPECT_NEAR(s.brier, brier, 1e-12);
  // -ln of the probability given to what happened; the 0.0 of a test that stood is clipped to 0.001
  const double log_loss = -(std::log(0.9) + std::log(0.6) + std::log(0.2) + std::log(0.3) + std::log(0.9) +
                            std::log(0.999) + std::log(0.6) + std::log(0.7)) /
                          8;
  EXPECT_NEAR(s.log_loss, log_loss, 1e-12);
  EXPECT_NEAR(s.log_loss, 0.5504323, 1e-6);  // the sum by hand: 4.4034583 / 8
}

TEST(OutcomeModel, LogLossClipsCertaintyThatWasWrong) {
  // P = 0 for a test that overturned costs ln(1000), not infinity; P = 1 for one that did is free
  // up to the clip
  const Scores wrong = score({0.0}, {1});
  EXPECT_NEAR(wrong.log_loss, std::log(1000.0), 1e-9);
  const Scores right = score({1.0}, {1});
  EXPECT_NEAR(right.log_loss, -std::log(0.999), 1e-12);
  // a coin toss costs ln 2 whatever happens
  EXPECT_NEAR(score({0.5, 0.5}, {0, 1}).log_loss, std::log(2.0), 1e-12);
}

TEST(OutcomeModel, ScoresByGroupAreEachGroupsOwn) {
  const std::vector<double> p{0.9, 0.2, 0.4, 0.7};
  const std::vector<int> y{1, 0, 1, 1};
  const std::vector<Scores> by = scores_by_group(p, y, {0, 2, 0, 2});
  ASSERT_EQ(by.size(), 3u);
  EXPECT_EQ(by[0].tests, 2);
  EXPECT_NEAR(by[0].accuracy, 0.5, 1e-12);  // 0.9 right, 0.4 wrong
  EXPECT_NEAR(by[0].brier, (0.01 + 0.36) / 2, 1e-12);
  EXPECT_EQ(by[1].tests, 0);
  EXPECT_NEAR(by[2].accuracy, 1.0, 1e-12);
  EXPECT_NEAR(by[2].log_loss, -(std::log(0.8) + std::log(0.7)) / 2, 1e-12);
}

TEST(OutcomeModel, WilsonIntervalMatchesPublishedExamples) {
  // Newcombe (1998), Statistics in Medicine 17:857, Table I, method 3 (Wilson score)
  const auto near = [](std::pair<double, double> got, double lo, double hi) {
    EXPECT_NEAR(got.first, lo, 5e-5);
    EXPECT_NEAR(got.second, hi, 5e-5);
  };
  near(wilson_interval(81, 263), 0.2553, 0.3662);
  near(wilson_interval(15, 148), 0.0624, 0.1605);
  near(wilson_interval(0, 20), 0.0, 0.1611);
  near(wilson_interval(1, 29), 0.0061, 0.1718);
  // n successes of n: the lower end is n / (n + z^2)
  near(wilson_interval(2, 2), 2 / (2 + 1.959964 * 1.959964), 1.0);
  near(wilson_interval(0, 0), 0.0, 1.0);
  // exactly, not by round-off: a share of 0 or 1 lies inside its interval
  EXPECT_EQ(wilson_interval(0, 9).first, 0.0);
  EXPECT_EQ(wilson_interval(9, 9).second, 1.0);
}

TEST(OutcomeModel, ReliabilityTableByHand) {
  const std::vector<double> p{0.05, 0.12, 0.15, 0.95, 1.0, 0.5, 0.55, 0.58, 0.52};
  const std::vector<int> y{0, 0, 1, 1, 1, 0, 1, 1, 0};
  const std::vector<ReliabilityBin> bins = reliability(p, y, 10);
  ASSERT_EQ(bins.size(), 10u);
  int total = 0;
  for (const ReliabilityBin& b : bins) total += b.tests;
  EXPECT_EQ(total, 9);
  EXPECT_NEAR(bins[1].lower, 0.1, 1e-12);
  EXPECT_NEAR(bins[1].upper, 0.2, 1e-12);
  EXPECT_EQ(bins[0].tests, 1);
  EXPECT_EQ(bins[0].overturned, 0);
  EXPECT_NEAR(bins[0].interval_high, 0.7935, 5e-5);  // z^2 / (1 + z^2)
  EXPECT_EQ(bins[1].tests, 2);
  EXPECT_NEAR(bins[1].mean_probability, 0.135, 1e-12);
  EXPECT_NEAR(bins[1].frequency, 0.5, 1e-12);
  EXPECT_EQ(bins[5].tests, 4);  // 0.5 opens its bin
  EXPECT_EQ(bins[5].overturned, 2);
  EXPECT_NEAR(bins[5].mean_probability, 0.5375, 1e-12);
  EXPECT_EQ(bins[9].tests, 2);  // 1.0 falls in the last bin
  EXPECT_NEAR(bins[9].frequency, 1.0, 1e-12);
  EXPECT_EQ(bins[3].tests, 0);
  EXPECT_NEAR(bins[3].interval_low, 0.0, 0);
  EXPECT_NEAR(bins[3].interval_high, 1.0, 0);
}

// A toy simulator: test t shakes with amplitude a_t along its own direction phi_t (records differ in
// what they excite); variant v has a capacity c_v; the rock feels the shaking's component along
// the table heading h (the axis pushes both ways). Overturn when a_t |cos(h - phi_t)| > c_v.
OutcomeGrid toy_grid(const std::vector<double>& amplitude, const std::vector<double>& direction,
                     const std::vector<double>& capacity, const std::vector<double>& headings) {
  OutcomeGrid grid(int(capacity.size()), int(amplitude.size()), headings);
  for (std::size_t v = 0; v < capacity.size(); ++v) {
    for (std::size_t t = 0; t < amplitude.size(); ++t) {
      for (std::size_t h = 0; h < headings.size(); ++h) {
        const double felt = amplitude[t] * std::abs(std::cos((headings[h] - direction[t]) * M_PI / 180.0));
        grid.set(int(v), int(t), int(h), felt > capacity[v]);
      }
    }
  }
  return grid;
}

TEST(OutcomeModel, RecoversAPlantedVariantAndHeading) {
  std::vector<double> headings;
  for (int k = 0; k < 18; ++k) headings.push_back(20.0 * k);
  const std::vector<double> capacity{0.6, 0.8, 1.0, 1.2, 1.4};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.2, 2.4);
  std::uniform_real_distribution<double> angle(0.0, 180.0);
  std::vector<double> amplitude, direction;
  std::vector<int> group;
  for (int t = 0; t < 160; ++t) {
    amplitude.push_back(u(rng));
    if (t % 8 == 0)
      direction.push_back(angle(rng));
    else
      direction.push_back(direction.back());
    group.push_back(t / 8);  // 20 "records" of 8 tests, one direction each
  }
  const OutcomeGrid grid = toy_grid(amplitude, direction, capacity, headings);
  // the planted truth: variant 2, heading 40 deg (index 2), lapse 0.05
  const Candidate truth{2, 2, 0, 0.05, 0};
  std::vector<int> y;
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int t = 0; t < grid.tests(); ++t) y.push_back(u01(rng) < overturn_probability(grid, truth, t) ? 1 : 0);
  const std::vector<bool> all(std::size_t(grid.tests()), true);
  const std::vector<Candidate> ranked = rank_candidates(grid, y, all, {});
  ASSERT_FALSE(ranked.empty());
  EXPECT_EQ(ranked.front().variant, 2);
  // heading 40 and 40 + 180 = 220 shake the rock alike: either is the truth
  const double h = grid.heading_deg(ranked.front().heading);
  EXPECT_NEAR(std::abs(std::remainder(h - 40.0, 180.0)), 0.0, 20.0 + 1e-9) << h;
  // the 95 % set holds the truth's variant and its weights sum to 1
  const std::vector<Member> members = confidence_set(ranked);
  double total = 0;
  bool has_truth_variant = false;
  for (const Member& m : members) {
    total += m.weight;
    has_truth_variant = has_truth_variant || m.candidate.variant == 2;
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_TRUE(has_truth_variant);
  // cross-validated predictions of the planted model are good out of sample
  const Scores cv = score(cross_validated_probability(grid, y, group, {}), y);
  EXPECT_GT(cv.accuracy, 0.85);
}

}  // namespace
}  // namespace rigid::calibration
