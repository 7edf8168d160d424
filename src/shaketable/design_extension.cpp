#include "rigid/shaketable/design_extension.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "rigid/core/types.hpp"

namespace rigid::shaketable {
namespace {

using calibration::Candidate;
using calibration::OutcomeGrid;

// Values that differ by less than this share are one value (decimals of the JSON, clamped steps).
bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); }

double& parameter_slot(Physics& p, LawParameter q) {
  switch (q) {
    case LawParameter::normal_stiffness:
      return p.law.normal_stiffness;
    case LawParameter::damping:
      return p.law.damping;
    case LawParameter::restitution:
      return p.law.restitution;
    case LawParameter::friction:
      break;
  }
  return p.law.friction;
}

// Whether a and b lie on one line along q: the same base and model, every other parameter equal.
bool on_line(const Physics& a, const Physics& b, LawParameter q) {
  if (a.base != b.base || a.law.method != b.law.method) return false;
  for (LawParameter other : law_parameters(a)) {
    if (other != q && !same(parameter_value(a, other), parameter_value(b, other))) return false;
  }
  return true;
}

// The step beyond an edge: K_N geometric (the design's ratio at that edge, else 2), the others
// arithmetic (the design's step at that edge, else a default of the parameter's scale).
double step_beyond(const std::vector<double>& values, double edge, bool up, LawParameter q) {
  const bool geometric = q == LawParameter::normal_stiffness;
  const double fallback = geometric                        ? 2.0
                          : q == LawParameter::damping     ? 1.0
                          : q == LawParameter::restitution ? 0.25
                                                           : 0.1;
  double step = fallback;
  if (values.size() >= 2) {
    const double inner = up ? values[values.size() - 2] : values[1];
    step = geometric ? std::max(edge, inner) / std::min(edge, inner) : std::abs(edge - inner);
  }
  if (geometric) return up ? edge * step : edge / step;
  return up ? edge + step : edge - step;
}

// Each variant's best log-likelihood over heading, spread and lapse.
std::vector<double> variant_likelihoods(const std::vector<Candidate>& ranked, int variants) {
  std::vector<double> best(std::size_t(variants), -INFINITY);
  for (const Candidate& c : ranked)
    best[std::size_t(c.variant)] = std::max(best[std::size_t(c.variant)], c.log_likelihood);
  return best;
}

std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

}  // namespace

const char* parameter_symbol(LawParameter p) {
  switch (p) {
    case LawParameter::normal_stiffness:
      return "K_N";
    case LawParameter::damping:
      return "D";
    case LawParameter::restitution:
      return "e";
    case LawParameter::friction:
      break;
  }
  return "mu";
}

std::vector<LawParameter> law_parameters(const Physics& p) {
  if (p.penalty()) return {LawParameter::normal_stiffness, LawParameter::damping, LawParameter::friction};
  return {LawParameter::restitution, LawParameter::friction};
}

double parameter_value(const Physics& p, LawParameter q) { return parameter_slot(const_cast<Physics&>(p), q); }

Range PhysicalLimits::of(LawParameter q) const {
  switch (q) {
    case LawParameter::normal_stiffness:
      return normal_stiffness;
    case LawParameter::damping:
      return damping;
    case LawParameter::restitution:
      return restitution;
    case LawParameter::friction:
      break;
  }
  return friction;
}

const char* status_text(EdgeStatus s) {
  switch (s) {
    case EdgeStatus::interior:
      return "interior";
    case EdgeStatus::at_edge_budget:
      return "at edge (budget)";
    case EdgeStatus::at_physical_limit:
      return "at a physical limit";
    case EdgeStatus::not_identified:
      return "not identified (another value within the 95 % region)";
    case EdgeStatus::fixed:
      break;
  }
  return "fixed (one value given)";
}

Range stiffness_limits(const std::vector<dynamics::BodyDef>& bodies, double base_half_width_m) {
  double weight = 0;
  for (const auto& b : bodies) {
    if (!b.fixed) weight = std::max(weight, b.shape.mass * kGravity);
  }
  // Hertz: the whole weight on one contact sinks it (m g / K_N)^(2/3)
  const double sinkage_low = weight / std::pow(kMaxSinkageFraction * base_half_width_m, 1.5);
  const double high = weight / std::pow(kRigidSinkage_m, 1.5);
  return {std::max(sinkage_low, 1e5), std::min(high, 1e13)};
}

ExtensionStage extension_stage(const OutcomeGrid& fitted, const std::vector<int>& observed,
                               const std::vector<Physics>& fitted_physics, const std::vector<Physics>& earlier,
                               const calibration::SearchSettings& search, const PhysicalLimits& limits,
                               bool budget_left) {
  const std::vector<bool> all(observed.size(), true);
  const std::vector<Candidate> ranked = calibration::rank_candidates(fitted, observed, all, search);
  const std::vector<double> fit = variant_likelihoods(ranked, fitted.variants());
  ExtensionStage out;
  out.best_variant = ranked.front().variant;
  const Physics& best = fitted_physics[std::size_t(out.best_variant)];
  for (LawParameter q : law_parameters(best)) {
    const double value = parameter_value(best, q);
    const Range range = limits.of(q);
    // every value of q tried with this model, for the steps; those on the best's line, for the edges
    std::set<double> anywhere_set;
    for (const auto* list : {&fitted_physics, &earlier}) {
      for (const Physics& p : *list) {
        if (p.law.method == best.law.method) anywhere_set.insert(parameter_value(p, q));
      }
    }
    const std::vector<double> anywhere(anywhere_set.begin(), anywhere_set.end());
    ParameterReport report{parameter_symbol(q), value, {}, EdgeStatus::interior};
    bool below = false, above = false, flat = false;
    for (std::size_t v = 0; v < fitted_physics.size(); ++v) {
      const Physics& p = fitted_physics[v];
      if (!on_line(p, best, q)) continue;
      const double x = parameter_value(p, q);
      report.tried.push_back(x);
      below = below || (x < value && !same(x, value));
      above = above || (x > value && !same(x, value));
      if (!same(x, value) && fit[v] >= fit[std::size_t(out.best_variant)] - calibration::kRegionLogLikelihoodDrop)
        flat = true;
    }
    std::sort(report.tried.begin(), report.tried.end());
    report.tried.erase(std::unique(report.tried.begin(), report.tried.end(), same), report.tried.end());
    // a value on the best's line inside the 95 % likelihood-ratio region: the outcomes cannot tell
    // it from the best, so the edge points nowhere and extending would only chase noise
    if (flat) report.status = EdgeStatus::not_identified;
    // a parameter the user gave one value is not a dimension of the design
    const bool fixed = anywhere.size() < 2;
    if (fixed) report.status = EdgeStatus::fixed;
    if (fixed || flat || (below && above)) {
      out.parameters.push_back(report);
      continue;
    }
    bool limited = false, budget = false;
    const std::size_t proposed_before = out.physics.size();
    for (bool up : {false, true}) {
      if (up ? above : below) continue;
      // the nearest value tried elsewhere on this side, else a step beyond the design's edge
      double next = NAN;
      for (double x : anywhere) {
        if (!same(x, value) && (up ? x > value : x < value) &&
            (std::isnan(next) || std::abs(x - value) < std::abs(next - value)))
          next = x;
      }
      if (std::isnan(next)) next = step_beyond(anywhere, value, up, q);
      const double bound = up ? range.high : range.low;
      if ((up ? next > bound : next < bound) || same(next, bound)) next = bound;
      if (same(next, value) || (up ? value > bound : value < bound)) {
        limited = true;
        continue;
      }
      if (!budget_left) {
        budget = true;
        continue;
      }
      Physics p = best;
      parameter_slot(p, q) = next;
      if (q == LawParameter::normal_stiffness) p.base_scene.clear();  // settled anew with its stiffness
      out.physics.push_back(p);
      out.moves.push_back(std::string(parameter_symbol(q)) + (up ? " up to " : " down to ") + short_number(next));
    }
    // an open side (extended now, or left by the budget) outranks a side at its limit
    const bool open = budget || out.physics.size() > proposed_before;
    report.status = open || !limited ? EdgeStatus::at_edge_budget : EdgeStatus::at_physical_limit;
    out.parameters.push_back(report);
  }
  return out;
}

LapseExtension extend_lapses(const OutcomeGrid& fitted, const std::vector<int>& observed,
                             calibration::SearchSettings search, const Range& limits) {
  const std::vector<bool> all(observed.size(), true);
  LapseExtension out;
  for (;;) {
    std::vector<double>& lapses = search.lapses;
    std::sort(lapses.begin(), lapses.end());
    const double best = calibration::rank_candidates(fitted, observed, all, search).front().lapse;
    out.report = {"lapse", best, lapses, EdgeStatus::interior};
    const bool low = same(best, lapses.front()), high = same(best, lapses.back());
    if (!low && !high) break;
    const double step =
        lapses.size() >= 2 ? (high ? lapses.back() - lapses[lapses.size() - 2] : lapses[1] - lapses[0]) : 0.05;
    double next = high ? std::min(best + step, limits.high) : std::max(best - step, limits.low);
    for (double bound : {limits.low, limits.high}) {
      if (same(next, bound)) next = bound;  // steps of decimals: 0.3 + 0.1 + 0.1 is the limit 0.5
    }
    if (same(next, best) ||
        std::find_if(lapses.begin(), lapses.end(), [&](double x) { return same(x, next); }) != lapses.end()) {
      out.report.status = EdgeStatus::at_physical_limit;
      break;
    }
    lapses.push_back(next);
  }
  out.search = search;
  return out;
}

std::string stage_purpose(int stage, const std::vector<std::string>& moves) {
  std::string text = "stage " + std::to_string(stage) + " (extend ";
  for (std::size_t k = 0; k < moves.size(); ++k) text += (k ? ", " : "") + moves[k];
  return text + ")";
}

}  // namespace rigid::shaketable
