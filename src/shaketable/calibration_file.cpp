#include "calibration_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "rigid/core/error.hpp"
#include "rigid/io/csv.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/shaketable/calibration_document.hpp"

namespace rigid::shaketable {
namespace {

namespace fs = std::filesystem;
using calibration::Candidate;
using calibration::Member;
using calibration::OutcomeGrid;
using calibration::Scores;

io::Json scores_json(const Scores& s) {
  io::Json j;
  j["tests"] = s.tests;
  j["accuracy"] = s.accuracy;
  j["balanced_accuracy"] = s.balanced_accuracy;
  j["precision"] = s.precision;
  j["recall"] = s.recall;
  j["brier"] = s.brier;
  j["log_loss"] = s.log_loss;
  j["confusion"] = {{"true_positive", s.true_positive},
                    {"false_negative", s.false_negative},
                    {"false_positive", s.false_positive},
                    {"true_negative", s.true_negative}};
  return j;
}

// Predicted P in ten bins against the observed share: how far the probabilities can be taken at
// their word.
io::Json reliability_json(const std::vector<double>& p, const std::vector<int>& y) {
  io::Json rows = io::Json::array();
  for (const calibration::ReliabilityBin& b : calibration::reliability(p, y)) {
    io::Json row;
    row["p_low"] = b.lower;
    row["p_high"] = b.upper;
    row["tests"] = b.tests;
    row["overturned"] = b.overturned;
    if (b.tests > 0) {
      row["mean_p"] = b.mean_probability;
      row["frequency"] = b.frequency;
      row["frequency_interval"] = {b.interval_low, b.interval_high};
    } else {
      row["mean_p"] = nullptr;
      row["frequency"] = nullptr;
      row["frequency_interval"] = nullptr;
    }
    rows.push_back(row);
  }
  return rows;
}

// Scores of probabilities with their reliability table.
io::Json probability_quality_json(const std::vector<double>& p, const std::vector<int>& y) {
  io::Json j = scores_json(calibration::score(p, y));
  j["reliability"] = reliability_json(p, y);
  return j;
}

// The held-out scores of each recorded motion's own tests (its probabilities from a fit that did
// not see it).
io::Json scores_by_motion_json(const std::vector<double>& p, const std::vector<int>& y, const std::vector<int>& group,
                               const std::vector<std::string>& records) {
  std::vector<std::string> name_of;
  for (std::size_t t = 0; t < group.size(); ++t) {
    if (std::size_t(group[t]) >= name_of.size()) name_of.resize(std::size_t(group[t]) + 1);
    name_of[std::size_t(group[t])] = t < records.size() ? records[t] : std::to_string(group[t]);
  }
  io::Json rows = io::Json::array();
  const std::vector<Scores> by = calibration::scores_by_group(p, y, group);
  for (std::size_t g = 0; g < by.size(); ++g) {
    if (by[g].tests == 0) continue;
    double mean_p = 0;
    for (std::size_t t = 0; t < group.size(); ++t)
      if (std::size_t(group[t]) == g) mean_p += p[t];
    rows.push_back({{"record", name_of[g]},
                    {"tests", by[g].tests},
                    {"overturned", by[g].true_positive + by[g].false_negative},
                    {"mean_p", mean_p / by[g].tests},
                    {"accuracy", by[g].accuracy},
                    {"brier", by[g].brier},
                    {"log_loss", by[g].log_loss}});
  }
  return rows;
}

// The profile log-likelihood of each stage's variants over its headings (the best spread and lapse
// at each heading centre): what the calibration figure draws, one row per (stage, variant, heading).
void write_likelihood_table(const std::string& path, const CalibrationReport& r) {
  const std::vector<bool> all(r.observed.size(), true);
  io::write_output_file(path, [&](std::ostream& out) {
    io::CsvWriter csv(out);
    csv.row({"stage", "variant", "label", "heading_deg", "log_likelihood", "heading_spread_deg", "lapse"});
    for (std::size_t stage = 0; stage < r.stages.size(); ++stage) {
      const OutcomeGrid& grid = *r.stages[stage].first;
      std::map<std::pair<int, int>, Candidate> best;  // (variant, heading): ranked best first
      for (const Candidate& c : calibration::rank_candidates(grid, r.observed, all, r.search))
        best.emplace(std::make_pair(c.variant, c.heading), c);
      for (const auto& [key, c] : best) {
        csv.field(int(stage + 1)).field(key.first).field(r.stages[stage].second[std::size_t(key.first)].label());
        csv.field(grid.heading_deg(key.second)).field(c.log_likelihood).field(c.spread_deg).field(c.lapse).end_row();
      }
    }
  });
}

// Signed difference b - a on the circle, in (-180, 180] (unit: deg).
double turn_between(double a, double b) {
  double d = std::remainder(b - a, 360.0);
  return d == -180.0 ? 180.0 : d;
}

// Each variant of a stage on its own: its best heading, spread and lapse, scored in and out of
// sample (the heading refitted without the held-out record).
io::Json variants_table(const OutcomeGrid& grid, const std::vector<Physics>& physics, const std::vector<int>& y,
                        const calibration::SearchSettings& search, const std::vector<int>& group) {
  io::Json rows = io::Json::array();
  const std::vector<bool> all(y.size(), true);
  for (int v = 0; v < grid.variants(); ++v) {
    const OutcomeGrid one = calibration::select_variants(grid, {v});
    const std::vector<Candidate> ranked = calibration::rank_candidates(one, y, all, search);
    const Candidate& best = ranked.front();
    std::vector<double> p_in(y.size());
    for (std::size_t t = 0; t < y.size(); ++t) p_in[t] = calibration::overturn_probability(one, best, int(t));
    const Scores in = calibration::score(p_in, y);
    const bool cv_possible = calibration::cross_validation_possible(group);
    const Scores cv =
        cv_possible ? calibration::score(calibration::cross_validated_probability(one, y, group, search), y) : Scores{};
    io::Json row = physics_json(physics[std::size_t(v)]);
    row["label"] = physics[std::size_t(v)].label();
    row["heading_deg"] = grid.heading_deg(best.heading);
    row["heading_spread_deg"] = best.spread_deg;
    row["lapse"] = best.lapse;
    row["log_likelihood"] = best.log_likelihood;
    row["in_sample"] = {{"accuracy", in.accuracy}, {"balanced_accuracy", in.balanced_accuracy}};
    if (cv_possible) {
      row["cross_validated"] = {{"accuracy", cv.accuracy}, {"balanced_accuracy", cv.balanced_accuracy}};
    } else {
      row["cross_validated"] = nullptr;
    }
    rows.push_back(row);
  }
  return rows;
}

// Each numeric parameter's place in the design (design_extension.hpp): the values tried along
// the best's line, its physical limits and whether the best is interior.
void add_design_status(io::Json& params, const CalibrationReport& r) {
  const std::map<std::string, std::pair<std::string, Range>> keys{
      {"K_N", {"normal_stiffness_n_m1_5", r.limits.normal_stiffness}},
      {"D", {"damping_s_m", r.limits.damping}},
      {"e", {"restitution", r.limits.restitution}},
      {"mu", {"friction", r.limits.friction}},
      {"lapse", {"lapse", r.limits.lapse}}};
  for (const ParameterReport& p : r.parameters) {
    const auto& [key, range] = keys.at(p.name);
    params[key]["status"] = status_text(p.status);
    params[key]["values_tried"] = p.tried;
    params[key]["physical_limits"] = {range.low, range.high};
  }
}

// Every stage's campaign: its number, purpose, headings and each parameter set on its own.
io::Json stages_json(const CalibrationReport& r) {
  io::Json stages = io::Json::array();
  for (std::size_t k = 0; k < r.stages.size(); ++k) {
    const auto& [g, phys] = r.stages[k];
    io::Json s;
    s["stage"] = long(k + 1);
    s["purpose"] = r.stage_purposes[k];
    io::Json headings = io::Json::array();
    for (int h = 0; h < g->headings(); ++h) headings.push_back(g->heading_deg(h));
    s["headings_deg"] = headings;
    s["parameter_sets"] = variants_table(*g, phys, r.observed, r.search, r.group);
    stages.push_back(s);
  }
  return stages;
}

}  // namespace

CalibrationSummary write_calibration(const CalibrationReport& r) {
  const OutcomeGrid& grid = *r.fitted;
  const std::vector<Physics>& physics = r.fitted_physics;
  const std::vector<int>& y = r.observed;
  const std::vector<bool> all(y.size(), true);
  const std::vector<Candidate> ranked = calibration::rank_candidates(grid, y, all, r.search);
  const std::vector<Member> region = calibration::confidence_set(ranked);
  const std::vector<Member> members = calibration::leading_members(region);
  const Candidate& best = ranked.front();
  const Physics& chosen = physics[std::size_t(best.variant)];
  const double heading = grid.heading_deg(best.heading);
  const std::vector<double> p_in = calibration::ensemble_probability(grid, members);
  const Scores in = calibration::score(p_in, y);
  std::optional<Scores> cv;
  std::vector<double> p_cv;
  if (calibration::cross_validation_possible(r.group)) {
    p_cv = calibration::cross_validated_probability(grid, y, r.group, r.search);
    cv = calibration::score(p_cv, y);
  }

  // the calibrated scene: the chosen base model and contact law, the rock turned so that the
  // table's axis is the scene's x axis
  const fs::path out(r.out);
  const std::string name = out.filename().string();
  const std::string scene = r.out + ".toml";
  io::SceneChanges changes;
  changes.physics = chosen.physics_table();
  changes.turn_free_blocks_deg = -heading;
  changes.comment = name + ": " + r.scan + " calibrated on " + r.tests_csv + " by rigid shaketable calibrate (" +
                    chosen.label() + ", the table's axis along x: heading " + std::to_string(heading) +
                    " deg in the scan's frame). Its uncertainty: " + name + ".calibration.json";
  io::write_derived_scene(chosen.base_scene, scene, changes);

  // the ensemble predictions average over: each member's scene turned alike
  io::Json ensemble = io::Json::array();
  std::map<int, std::string> member_scene;
  for (const Member& m : members) {
    const Physics& p = physics[std::size_t(m.candidate.variant)];
    if (!member_scene.count(m.candidate.variant)) {
      if (m.candidate.variant == best.variant) {
        member_scene[m.candidate.variant] = fs::path(scene).filename().string();
      } else {
        const std::string file = name + ".calibration/member_v" + std::to_string(m.candidate.variant) + ".toml";
        io::SceneChanges c = changes;
        c.physics = p.physics_table();
        c.comment = p.label() + ", turned as " + name + ".toml";
        io::write_derived_scene(p.base_scene, (out.parent_path() / file).string(), c);
        member_scene[m.candidate.variant] = file;
      }
    }
    io::Json j = physics_json(p);
    j["scene"] = member_scene[m.candidate.variant];
    j["weight"] = m.weight;
    j["lapse"] = m.candidate.lapse;
    j["heading_deg"] = grid.heading_deg(m.candidate.heading);
    j["heading_spread_deg"] = m.candidate.spread_deg;
    io::Json turns = io::Json::array();
    for (int h : grid.window(m.candidate.heading, m.candidate.spread_deg))
      turns.push_back(turn_between(heading, grid.heading_deg(h)));
    j["rotations_deg"] = turns;  // of the motion, relative to the calibrated scene
    ensemble.push_back(j);
  }

  // intervals: the values within the 95 % likelihood-ratio region
  double turn_lo = 0, turn_hi = 0, spread_hi = 0, lapse_lo = 1, lapse_hi = 0;
  std::set<std::string> bases, contacts;
  std::set<double> stiffness, damping, restitution, friction;
  for (const Member& m : region) {
    const Physics& p = physics[std::size_t(m.candidate.variant)];
    const double d = turn_between(heading, grid.heading_deg(m.candidate.heading));
    turn_lo = std::min(turn_lo, d);
    turn_hi = std::max(turn_hi, d);
    spread_hi = std::max(spread_hi, m.candidate.spread_deg);
    lapse_lo = std::min(lapse_lo, m.candidate.lapse);
    lapse_hi = std::max(lapse_hi, m.candidate.lapse);
    bases.insert(p.base);
    contacts.insert(contact::contact_method_name(p.law.method));
    if (p.penalty()) {
      stiffness.insert(p.law.normal_stiffness);
      damping.insert(p.law.damping);
    } else {
      restitution.insert(p.law.restitution);
    }
    friction.insert(p.law.friction);
  }
  io::Json j;
  j["scan"] = r.scan;
  j["tests"] = r.tests_csv;
  j["scene"] = fs::path(scene).filename().string();
  j["physics"] = chosen.label();  // in words, for titles and logs
  j["lab_format"] = r.lab_format_file.empty() ? "default" : r.lab_format_file;
  j["tests_count"] = long(y.size());
  j["overturned_count"] = long(std::count(y.begin(), y.end(), 1));
  j["method"] =
      "maximum likelihood over the final stage's design: P(overturn) = lapse/2 + (1 - lapse) x the share of "
      "the headings within the spread that overturn the simulated rock; 95 % region = log-likelihood within "
      "1.92 of the best; cross-validation leaves out one recorded motion at a time";
  io::Json params;
  params["heading_deg"] = {{"value", heading}, {"interval", {heading + turn_lo, heading + turn_hi}}};
  params["heading_spread_deg"] = {{"value", best.spread_deg}, {"interval", {0.0, spread_hi}}};
  params["lapse"] = {{"value", best.lapse}, {"interval", {lapse_lo, lapse_hi}}};
  params["base"] = {{"value", chosen.base},
                    {"in_region", bases},
                    {"status", "not extended (each depth is another model of the scanned base: --flatten-base)"}};
  params["contact"] = {{"value", contact::contact_method_name(chosen.law.method)}, {"in_region", contacts}};
  if (chosen.penalty()) {
    params["normal_stiffness_n_m1_5"] = {{"value", chosen.law.normal_stiffness}, {"in_region", stiffness}};
    params["damping_s_m"] = {{"value", chosen.law.damping}, {"in_region", damping}};
  } else {
    params["restitution"] = {{"value", chosen.law.restitution}, {"in_region", restitution}};
  }
  params["friction"] = {{"value", chosen.law.friction}, {"in_region", friction}};
  add_design_status(params, r);
  j["parameters"] = params;
  j["log_likelihood"] = best.log_likelihood;
  j["region_size"] = long(region.size());
  j["in_sample"] = probability_quality_json(p_in, y);
  if (cv) {
    j["cross_validated"] = probability_quality_json(p_cv, y);
    j["cross_validated"]["by_motion"] = scores_by_motion_json(p_cv, y, r.group, r.records);
  } else {
    j["cross_validated"] = {{"available", false},
                            {"reason", "fewer than " + std::to_string(calibration::kMinCrossValidationGroups) +
                                           " recorded motions: leaving one out leaves too little to fit"}};
  }
  j["ensemble"] = ensemble;
  j["stages"] = stages_json(r);
  j["wall_s"] = r.wall_s;
  const std::string json_path = r.out + ".calibration.json";
  write_calibration_document(json_path, j, r.command_line);
  const std::string likelihood_path = r.out + ".calibration/likelihood.csv";
  write_likelihood_table(likelihood_path, r);

  CalibrationSummary summary;
  summary.label = chosen.label();
  summary.heading_deg = heading;
  summary.heading_low_deg = heading + turn_lo;
  summary.heading_high_deg = heading + turn_hi;
  summary.spread_deg = best.spread_deg;
  summary.lapse = best.lapse;
  summary.in_sample = in;
  summary.cross_validated = cv;
  summary.scene = scene;
  summary.json = json_path;
  summary.likelihood_table = likelihood_path;
  summary.wall_s = r.wall_s;
  summary.parameters = r.parameters;
  return summary;
}

}  // namespace rigid::shaketable
