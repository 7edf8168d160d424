#include "rigid/calibration/outcome_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace rigid::calibration {

OutcomeGrid::OutcomeGrid(int variants, int tests, std::vector<double> headings_deg)
    : variants_(variants), tests_(tests), headings_(int(headings_deg.size())), headings_deg_(std::move(headings_deg)) {
  if (variants <= 0 || tests <= 0 || headings_ <= 0)
    throw std::invalid_argument("an outcome grid needs at least one variant, test and heading");
  for (int a = 0; a < headings_; ++a) {
    for (int b = a + 1; b < headings_; ++b) {
      if (std::abs(std::remainder(headings_deg_[std::size_t(a)] - headings_deg_[std::size_t(b)], 360.0)) < 1e-9)
        throw std::invalid_argument("heading listed twice in an outcome grid");
    }
  }
  cells_.assign(std::size_t(variants) * std::size_t(tests) * std::size_t(headings_), 0);
}

std::vector<int> OutcomeGrid::window(int centre, double spread_deg) const {
  std::vector<int> out;
  const double c = headings_deg_[std::size_t(centre)];
  for (int h = 0; h < headings_; ++h) {
    // a hair of tolerance: grids are written as decimals
    if (std::abs(std::remainder(headings_deg_[std::size_t(h)] - c, 360.0)) <= spread_deg + 1e-9) out.push_back(h);
  }
  return out;
}

double member_probability(double overturned_share, double lapse) {
  return 0.5 * lapse + (1.0 - lapse) * overturned_share;
}

namespace {

double window_mean(const OutcomeGrid& grid, int variant, int test, const std::vector<int>& window) {
  int n = 0;
  for (int h : window) n += grid.overturned(variant, test, h) ? 1 : 0;
  return double(n) / double(window.size());
}

bool better(const Candidate& a, const Candidate& b) {
  if (a.log_likelihood != b.log_likelihood) return a.log_likelihood > b.log_likelihood;
  if (a.spread_deg != b.spread_deg) return a.spread_deg < b.spread_deg;
  if (a.variant != b.variant) return a.variant < b.variant;
  if (a.heading != b.heading) return a.heading < b.heading;
  return a.lapse < b.lapse;
}

}  // namespace

double overturn_probability(const OutcomeGrid& grid, const Candidate& c, int test) {
  return member_probability(window_mean(grid, c.variant, test, grid.window(c.heading, c.spread_deg)), c.lapse);
}

double log_likelihood(const OutcomeGrid& grid, const Candidate& c, const std::vector<int>& observed,
                      const std::vector<bool>& use) {
  const std::vector<int> window = grid.window(c.heading, c.spread_deg);
  double sum = 0;
  for (int t = 0; t < grid.tests(); ++t) {
    if (!use[std::size_t(t)]) continue;
    const double p = member_probability(window_mean(grid, c.variant, t, window), c.lapse);
    sum += observed[std::size_t(t)] ? std::log(p) : std::log1p(-p);
  }
  return sum;
}

std::vector<Candidate> rank_candidates(const OutcomeGrid& grid, const std::vector<int>& observed,
                                       const std::vector<bool>& use, const SearchSettings& settings) {
  std::vector<Candidate> out;
  for (int v = 0; v < grid.variants(); ++v) {
    for (int h = 0; h < grid.headings(); ++h) {
      for (double spread : settings.spreads_deg) {
        const std::vector<int> window = grid.window(h, spread);
        // a wider spread that takes in no further heading is the same candidate: keep the narrowest
        if (spread > 0 && window == grid.window(h, 0) && spread != settings.spreads_deg.front()) continue;
        for (double lapse : settings.lapses) {
          Candidate c{v, h, spread, lapse, 0};
          c.log_likelihood = log_likelihood(grid, c, observed, use);
          out.push_back(c);
        }
      }
    }
  }
  std::sort(out.begin(), out.end(), better);
  return out;
}

std::vector<Member> confidence_set(const std::vector<Candidate>& ranked, double log_likelihood_drop) {
  std::vector<Member> out;
  if (ranked.empty()) return out;
  const double best = ranked.front().log_likelihood;
  double total = 0;
  for (const Candidate& c : ranked) {
    if (c.log_likelihood < best - log_likelihood_drop) break;
    const double w = std::exp(c.log_likelihood - best);
    out.push_back({c, w});
    total += w;
  }
  for (Member& m : out) m.weight /= total;
  return out;
}

OutcomeGrid select_variants(const OutcomeGrid& grid, const std::vector<int>& variants) {
  std::vector<double> headings;
  for (int h = 0; h < grid.headings(); ++h) headings.push_back(grid.heading_deg(h));
  OutcomeGrid out(int(variants.size()), grid.tests(), headings);
  for (std::size_t k = 0; k < variants.size(); ++k) {
    for (int t = 0; t < grid.tests(); ++t) {
      for (int h = 0; h < grid.headings(); ++h) out.set(int(k), t, h, grid.overturned(variants[k], t, h));
    }
  }
  return out;
}

OutcomeGrid join_variants(const OutcomeGrid& a, const OutcomeGrid& b) {
  std::vector<double> headings;
  for (int h = 0; h < a.headings(); ++h) headings.push_back(a.heading_deg(h));
  bool same_headings = a.headings() == b.headings();
  for (int h = 0; same_headings && h < a.headings(); ++h) same_headings = a.heading_deg(h) == b.heading_deg(h);
  if (a.tests() != b.tests() || !same_headings)
    throw std::invalid_argument("outcome grids of other tests or headings cannot be joined");
  OutcomeGrid out(a.variants() + b.variants(), a.tests(), headings);
  for (int t = 0; t < a.tests(); ++t) {
    for (int h = 0; h < a.headings(); ++h) {
      for (int v = 0; v < a.variants(); ++v) out.set(v, t, h, a.overturned(v, t, h));
      for (int v = 0; v < b.variants(); ++v) out.set(a.variants() + v, t, h, b.overturned(v, t, h));
    }
  }
  return out;
}

std::vector<Member> leading_members(std::vector<Member> members, double weight, int max_variants) {
  std::sort(members.begin(), members.end(), [](const Member& a, const Member& b) {
    if (a.weight != b.weight) return a.weight > b.weight;
    return better(a.candidate, b.candidate);
  });
  std::vector<Member> out;
  std::vector<int> variants;
  double covered = 0;
  for (const Member& m : members) {
    if (covered >= weight) break;
    const bool known = std::find(variants.begin(), variants.end(), m.candidate.variant) != variants.end();
    if (!known && int(variants.size()) >= max_variants) continue;
    if (!known) variants.push_back(m.candidate.variant);
    out.push_back(m);
    covered += m.weight;
  }
  for (Member& m : out) m.weight /= covered;
  return out;
}

std::vector<double> ensemble_probability(const OutcomeGrid& grid, const std::vector<Member>& members) {
  std::vector<double> p(std::size_t(grid.tests()), 0.0);
  for (const Member& m : members) {
    for (int t = 0; t < grid.tests(); ++t) p[std::size_t(t)] += m.weight * overturn_probability(grid, m.candidate, t);
  }
  return p;
}

std::vector<double> cross_validated_probability(const OutcomeGrid& grid, const std::vector<int>& observed,
                                                const std::vector<int>& group, const SearchSettings& settings) {
  std::vector<double> p(std::size_t(grid.tests()), 0.5);
  std::map<int, int> groups;
  for (int g : group) ++groups[g];
  for (const auto& [g, _] : groups) {
    std::vector<bool> train(std::size_t(grid.tests()));
    for (int t = 0; t < grid.tests(); ++t) train[std::size_t(t)] = group[std::size_t(t)] != g;
    const std::vector<Candidate> ranked = rank_candidates(grid, observed, train, settings);
    const std::vector<Member> members = confidence_set(ranked);
    const std::vector<double> q = ensemble_probability(grid, members);
    for (int t = 0; t < grid.tests(); ++t) {
      if (!train[std::size_t(t)]) p[std::size_t(t)] = q[std::size_t(t)];
    }
  }
  return p;
}

bool cross_validation_possible(const std::vector<int>& group) {
  std::vector<int> distinct = group;
  std::sort(distinct.begin(), distinct.end());
  return std::unique(distinct.begin(), distinct.end()) - distinct.begin() >= kMinCrossValidationGroups;
}

Scores score(const std::vector<double>& probability, const std::vector<int>& observed) {
  Scores s;
  s.tests = int(probability.size());
  double brier = 0, log_loss = 0;
  for (std::size_t t = 0; t < probability.size(); ++t) {
    const bool predicted = probability[t] >= 0.5;
    const bool y = observed[t] != 0;
    if (predicted && y) ++s.true_positive;
    if (predicted && !y) ++s.false_positive;
    if (!predicted && !y) ++s.true_negative;
    if (!predicted && y) ++s.false_negative;
    brier += (probability[t] - (y ? 1.0 : 0.0)) * (probability[t] - (y ? 1.0 : 0.0));
    const double clipped = std::clamp(probability[t], kLogLossClip, 1 - kLogLossClip);
    log_loss -= std::log(y ? clipped : 1 - clipped);
  }
  if (s.tests == 0) return s;
  s.accuracy = double(s.true_positive + s.true_negative) / s.tests;
  const int positives = s.true_positive + s.false_negative, negatives = s.true_negative + s.false_positive;
  s.recall = positives ? double(s.true_positive) / positives : 0.0;
  const double specificity = negatives ? double(s.true_negative) / negatives : 0.0;
  s.balanced_accuracy = 0.5 * (s.recall + specificity);
  s.precision =
      s.true_positive + s.false_positive ? double(s.true_positive) / (s.true_positive + s.false_positive) : 0.0;
  s.brier = brier / s.tests;
  s.log_loss = log_loss / s.tests;
  return s;
}

std::vector<Scores> scores_by_group(const std::vector<double>& probability, const std::vector<int>& observed,
                                    const std::vector<int>& group) {
  const int groups = group.empty() ? 0 : *std::max_element(group.begin(), group.end()) + 1;
  std::vector<std::vector<double>> p(static_cast<std::size_t>(groups));
  std::vector<std::vector<int>> y(static_cast<std::size_t>(groups));
  for (std::size_t t = 0; t < group.size(); ++t) {
    p[std::size_t(group[t])].push_back(probability[t]);
    y[std::size_t(group[t])].push_back(observed[t]);
  }
  std::vector<Scores> out;
  for (int g = 0; g < groups; ++g) out.push_back(score(p[std::size_t(g)], y[std::size_t(g)]));
  return out;
}

std::pair<double, double> wilson_interval(int k, int n, double z) {
  if (n <= 0) return {0.0, 1.0};
  const double share = double(k) / n, z2 = z * z;
  const double centre = (share + z2 / (2.0 * n)) / (1 + z2 / n);
  const double half = z / (1 + z2 / n) * std::sqrt(share * (1 - share) / n + z2 / (4.0 * n * n));
  // the ends at 0 and n successes are exactly 0 and 1 (centre -/+ half there, but for round-off)
  return {k <= 0 ? 0.0 : std::max(0.0, centre - half), k >= n ? 1.0 : std::min(1.0, centre + half)};
}

std::vector<ReliabilityBin> reliability(const std::vector<double>& probability, const std::vector<int>& observed,
                                        int bins) {
  std::vector<ReliabilityBin> out(std::size_t(std::max(bins, 1)));
  std::vector<double> sum(out.size(), 0.0);
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b].lower = double(b) / double(out.size());
    out[b].upper = double(b + 1) / double(out.size());
  }
  for (std::size_t t = 0; t < probability.size(); ++t) {
    const double p = std::clamp(probability[t], 0.0, 1.0);
    const std::size_t b = std::min(out.size() - 1, std::size_t(p * double(out.size())));
    ++out[b].tests;
    out[b].overturned += observed[t] != 0 ? 1 : 0;
    sum[b] += p;
  }
  for (std::size_t b = 0; b < out.size(); ++b) {
    ReliabilityBin& bin = out[b];
    if (bin.tests == 0) continue;
    bin.mean_probability = sum[b] / bin.tests;
    bin.frequency = double(bin.overturned) / bin.tests;
    std::tie(bin.interval_low, bin.interval_high) = wilson_interval(bin.overturned, bin.tests);
  }
  return out;
}

}  // namespace rigid::calibration
