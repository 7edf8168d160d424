#pragma once
/// Maximum-likelihood calibration of a rock's uncertain physics on observed shake-table outcomes
/// (docs/validation-shaketable.md). No I/O, no MPI: the simulated outcomes come in as a grid.
///
/// The simulator is deterministic: a test either overturns the simulated rock or not. What makes a
/// real test uncertain is modelled in two parts. (1) The rock's heading on the table is not known
/// exactly and varies a little each time it is set up again: a candidate averages the simulated
/// outcomes over a window of headings, which gives graded probabilities. (2) Whatever the model
/// misses (placement of the rock on its asperities, table repeatability) is a lapse rate: with
/// probability `lapse` the outcome is a coin toss. A candidate is thus (physics variant, heading,
/// heading spread, lapse), and its likelihood is the Bernoulli likelihood of the observed outcomes.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rigid::calibration {

/// Simulated outcomes over a design: every physics variant, every test, every heading of a list
/// (the direction of the table's axis in the rock's frame, unit: deg, distinct modulo 360).
class OutcomeGrid {
 public:
  /// Throws std::invalid_argument for no variant, test or heading, or a repeated heading.
  OutcomeGrid(int variants, int tests, std::vector<double> headings_deg);
  int variants() const { return variants_; }
  int tests() const { return tests_; }
  int headings() const { return headings_; }
  double heading_deg(int h) const { return headings_deg_[std::size_t(h)]; }
  /// The headings within `spread` of heading `centre` on the circle (unit: deg), centre included.
  std::vector<int> window(int centre, double spread_deg) const;
  bool overturned(int variant, int test, int heading) const { return cells_[index(variant, test, heading)] != 0; }
  void set(int variant, int test, int heading, bool overturned) {
    cells_[index(variant, test, heading)] = overturned ? 1 : 0;
  }

 private:
  std::size_t index(int v, int t, int h) const {
    return (std::size_t(v) * std::size_t(tests_) + std::size_t(t)) * std::size_t(headings_) + std::size_t(h);
  }
  int variants_, tests_, headings_;
  std::vector<double> headings_deg_;
  std::vector<std::int8_t> cells_;
};

/// The grid of a subset of its variants (in the order given).
OutcomeGrid select_variants(const OutcomeGrid& grid, const std::vector<int>& variants);

/// The variants of `a` followed by those of `b`, on the same tests and headings (a design extended
/// by a stage on the same heading list). Throws std::invalid_argument when they differ.
OutcomeGrid join_variants(const OutcomeGrid& a, const OutcomeGrid& b);

/// One candidate model of the real tests.
struct Candidate {
  int variant = 0;            ///< physics variant (index in the design)
  int heading = 0;            ///< heading centre (index on the grid)
  double spread_deg = 0;      ///< heading window half-width: every grid heading within it counts equally
  double lapse = 0;           ///< probability that an outcome is a coin toss (unit: 1)
  double log_likelihood = 0;  ///< of the outcomes it was fitted to (natural log)
};

/// Which candidates are tried.
struct SearchSettings {
  std::vector<double> spreads_deg{0, 10, 20, 30};         ///< unit: deg
  std::vector<double> lapses{0.02, 0.05, 0.1, 0.2, 0.3};  ///< unit: 1
};

/// The one rule of a member's P(overturn): with probability `lapse` the outcome is a coin toss,
/// else it is the share of the member's headings that overturned the simulated rock:
/// lapse/2 + (1 - lapse) x share. Ensembles average it over members by weight.
double member_probability(double overturned_share, double lapse);

/// P(overturn) of test `test` under candidate c.
double overturn_probability(const OutcomeGrid& grid, const Candidate& c, int test);

/// Log-likelihood of the outcomes `observed` (0/1 per test) over the tests with use[test] true.
double log_likelihood(const OutcomeGrid& grid, const Candidate& c, const std::vector<int>& observed,
                      const std::vector<bool>& use);

/// Every candidate of the search, scored on the used tests, best first. Ties (equal likelihood)
/// prefer the narrower spread, then the lower variant, heading and lapse, so the order does not
/// depend on anything but the inputs.
std::vector<Candidate> rank_candidates(const OutcomeGrid& grid, const std::vector<int>& observed,
                                       const std::vector<bool>& use, const SearchSettings& settings);

/// The candidates within the likelihood-ratio confidence region of the best one
/// (log-likelihood >= best - half the chi-square quantile, 1.92 for 95 % and one parameter of
/// interest), with weights proportional to their likelihood (a flat prior over the design):
/// what predictions average over.
struct Member {
  Candidate candidate;
  double weight = 0;
};
/// Half the chi-square 95 % quantile of one degree of freedom: the likelihood-ratio region's depth.
inline constexpr double kRegionLogLikelihoodDrop = 1.92;
std::vector<Member> confidence_set(const std::vector<Candidate>& ranked,
                                   double log_likelihood_drop = kRegionLogLikelihoodDrop);

/// The members that carry most of the weight, for predictions that must simulate each member's
/// variant: the heaviest first until `weight` is covered or another variant would exceed
/// `max_variants`; weights renormalised.
std::vector<Member> leading_members(std::vector<Member> members, double weight = 0.9, int max_variants = 3);

/// P(overturn) of every test averaged over an ensemble.
std::vector<double> ensemble_probability(const OutcomeGrid& grid, const std::vector<Member>& members);

/// Leave-groups-out cross-validation: for each group (a recorded motion), the best candidate
/// fitted to the tests of the other groups gives the probabilities of the group's tests. A
/// group whose complement has outcomes all equal is fitted anyway (its best candidate is then
/// uninformed, and the score says so).
std::vector<double> cross_validated_probability(const OutcomeGrid& grid, const std::vector<int>& observed,
                                                const std::vector<int>& group, const SearchSettings& settings);

/// The fewest groups (recorded motions) a leave-one-group-out score means something with: with
/// one, no fold has a training test; with two, each fold is fitted on one motion alone.
inline constexpr int kMinCrossValidationGroups = 3;
/// Whether `group` has at least kMinCrossValidationGroups distinct groups.
bool cross_validation_possible(const std::vector<int>& group);

/// Log loss clips each probability to [kLogLossClip, 1 - kLogLossClip]: a prediction of exactly 0
/// or 1 that is wrong would otherwise cost an infinite loss, and one such test would decide the
/// whole score. The clip caps a test's loss at ln(1000) = 6.91. Calibrated ensembles reach it only
/// with a lapse of 0 (their lapse keeps every P in [lapse/2, 1 - lapse/2]), which edge extension
/// chooses only where the model explains every test it was fitted to.
inline constexpr double kLogLossClip = 1e-3;

/// Scores of probabilities against outcomes; predicted = p >= 0.5. Brier and log loss are proper
/// scores (Brier 1950; Gneiting & Raftery 2007): expected best when the probabilities are the true
/// ones, so they judge the probabilities themselves, not only the side of 0.5 they fall on.
struct Scores {
  int tests = 0, true_positive = 0, false_positive = 0, true_negative = 0, false_negative = 0;
  double accuracy = 0;           ///< (tp + tn) / tests
  double balanced_accuracy = 0;  ///< mean of recall and specificity
  double precision = 0;          ///< tp / (tp + fp); 0 when nothing is predicted to overturn
  double recall = 0;             ///< tp / (tp + fn)
  double brier = 0;              ///< mean of (p - y)^2
  double log_loss = 0;           ///< mean of -ln p (overturned) or -ln(1 - p) (stood), p clipped (kLogLossClip)
};
Scores score(const std::vector<double>& probability, const std::vector<int>& observed);

/// The scores of the tests of each group (a recorded motion) on their own, by group index
/// (0..max group); a group without tests has tests = 0.
std::vector<Scores> scores_by_group(const std::vector<double>& probability, const std::vector<int>& observed,
                                    const std::vector<int>& group);

/// One bin of a reliability table: the tests whose predicted P(overturn) fell in [lower, upper)
/// (the last bin includes 1), against the share of them that overturned.
struct ReliabilityBin {
  double lower = 0, upper = 0;
  int tests = 0, overturned = 0;
  double mean_probability = 0;  ///< mean predicted P of the bin's tests (0 when empty)
  double frequency = 0;         ///< overturned / tests (0 when empty)
  /// Wilson's 95 % score interval of the frequency (Wilson 1927): a binomial interval that stays
  /// inside [0, 1] and is not empty at 0 or n successes, unlike the normal one. [0, 1] when empty.
  double interval_low = 0, interval_high = 1;
};

/// Wilson's score interval of k successes in n trials at the normal quantile z (95 %: 1.959964).
/// [0, 1] for n = 0.
std::pair<double, double> wilson_interval(int k, int n, double z = 1.959963984540054);

/// The reliability table of probabilities against outcomes: `bins` equal bins of [0, 1], all of
/// them, empty ones included. A calibrated model's bins lie on the diagonal (frequency = mean P)
/// within their intervals.
std::vector<ReliabilityBin> reliability(const std::vector<double>& probability, const std::vector<int>& observed,
                                        int bins = 10);

}  // namespace rigid::calibration
