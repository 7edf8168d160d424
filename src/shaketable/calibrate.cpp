#include "rigid/shaketable/calibrate.hpp"
#include "text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "calibration_file.hpp"
#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/scenario/scene.hpp"
#include "rigid/shaketable/ensemble.hpp"
#include "rigid/shaketable/settle.hpp"

namespace rigid::shaketable {
namespace {

namespace fs = std::filesystem;

double wrap360(double deg) {
  double h = std::fmod(deg, 360.0);
  if (h < 0) h += 360.0;
  return std::round(h * 1e6) / 1e6;
}

// The best candidate of each variant, best variants first.
std::vector<calibration::Candidate> best_per_variant(const calibration::OutcomeGrid& grid, const std::vector<int>& y) {
  const std::vector<bool> all(y.size(), true);
  std::vector<calibration::Candidate> out;
  std::set<int> seen;
  for (const auto& cand : calibration::rank_candidates(grid, y, all, {})) {
    if (seen.insert(cand.variant).second) out.push_back(cand);
  }
  return out;
}

}  // namespace

std::optional<ContactChoice> parse_contact_choice(const std::string& text) {
  if (text == "rigid") return ContactChoice{contact::ContactMethod::rigid, 0};
  // a strict number: all of the text, finite
  char* end = nullptr;
  const double k = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !(k >= 1e5 && k <= 1e13)) return std::nullopt;
  return ContactChoice{contact::ContactMethod::penalty, k};
}

void check_settings(const CalibrationSettings& o) {
  if (o.flatten_base_m.empty() || o.contact_models.empty() || o.restitution.empty() || o.damping.empty() ||
      o.friction.empty())
    throw InputError("", 0,
                     "--flatten-base, --contact-models, --restitution, --damping and --friction need at least one "
                     "value each");
  for (double d : o.damping) {
    if (!(d >= 0 && d <= 100)) throw InputError("", 0, "--damping: values must be in [0, 100] s/m");
  }
  for (double f : o.flatten_base_m) {
    if (!(f >= 0 && f < 0.1)) throw InputError("", 0, "--flatten-base: depths must be in [0, 0.1) m");
  }
  for (double e : o.restitution) {
    if (!(e >= 0 && e <= 1)) throw InputError("", 0, "--restitution: values must be in [0, 1]");
  }
  for (double mu : o.friction) {
    if (!(mu > 0 && mu <= 10)) throw InputError("", 0, "--friction: values must be in (0, 10]");
  }
  if (o.extend_stages < 0 || o.extend_stages > 20) throw InputError("", 0, "--extend-stages must be 0 to 20");
  if (o.headings < 4 || o.headings > 72) throw InputError("", 0, "--headings must be 4 to 72");
  if (o.keep < 1 || o.keep > 10) throw InputError("", 0, "--keep must be 1 to 10");
  if (!(o.refine_step_deg > 0 && o.refine_step_deg < 360.0 / o.headings))
    throw InputError("", 0, "--refine-step must be positive and below the coarse heading step");
  if (!(o.tilt_deg > 0 && o.tilt_deg < 90)) throw InputError("", 0, "--tilt-rule must be in (0, 90) deg");
  if (fs::path(o.out).filename().empty()) throw InputError("", 0, "--out needs DIR/NAME");
  if (o.figure_format != "png" && o.figure_format != "pdf" && o.figure_format != "svg")
    throw InputError("", 0, "--figure-format must be png, pdf or svg");
}

std::string calibration_manifest(const CalibrationSettings& s, const io::LabTestList& tests) {
  std::ostringstream m;
  m.precision(17);
  const auto list = [&](const char* name, const std::vector<double>& values) {
    m << name << ":";
    for (double v : values) m << " " << v;
    m << "\n";
  };
  m << "scan: " << io::file_sha256(s.scan) << "\n";
  m << "lab format: " << (s.lab_format.empty() ? std::string("default") : io::file_sha256(s.lab_format)) << "\n";
  m << "scale: " << s.scale << "\nup: " << s.up << "\n";
  list("flatten base (m)", s.flatten_base_m);
  m << "contact models:";
  for (const ContactChoice& c : s.contact_models)
    m << " "
      << (c.method == contact::ContactMethod::rigid ? std::string("rigid") : format("%.17g", c.normal_stiffness));
  m << "\n";
  list("restitution", s.restitution);
  list("damping (s/m)", s.damping);
  list("friction", s.friction);
  m << "headings: " << s.headings << "\nkeep: " << s.keep << "\nrefine step (deg): " << s.refine_step_deg
    << "\ntilt rule (deg): " << s.tilt_deg << "\nmax vertices: " << s.max_vertices
    << "\npedestal margin (m): " << s.pedestal_margin << "\nextend stages: " << s.extend_stages << "\n";
  // the tests by what the campaigns run (number, motion, recording's contents), their outcomes apart
  std::string listed, outcomes;
  for (const io::LabTest& t : tests.tests) {
    listed += std::to_string(t.test_no) + "," + t.record + "," + io::file_sha256(t.file) + "\n";
    outcomes += t.overturned ? char('0' + *t.overturned) : '?';
  }
  m << "tests: " << io::sha256_hex(listed) << "\noutcomes: " << io::sha256_hex(outcomes) << "\n";
  return m.str();
}

scan::ImportOptions base_model_import(const CalibrationSettings& s, const std::string& scan, double flatten_m,
                                      const std::string& out) {
  scan::ImportOptions in;
  in.scan = scan;
  in.out = out;
  in.scale = s.scale;
  in.up = s.up;
  in.max_vertices = s.max_vertices;
  in.pedestal_margin = s.pedestal_margin;
  in.flatten_base = flatten_m;
  in.tilt_deg = s.tilt_deg;
  return in;
}

std::string base_name(double flatten_m) { return format("flat_%gmm", flatten_m * 1e3); }

std::vector<double> heading_ring(int count) {
  std::vector<double> h;
  for (int k = 0; k < count; ++k) h.push_back(360.0 * k / count);
  return h;
}

std::vector<Physics> first_stage_physics(const std::map<double, std::string>& base_scenes,
                                         const CalibrationSettings& s) {
  std::vector<Physics> out;
  for (const auto& [flatten_m, scene] : base_scenes) {
    for (const ContactChoice& c : s.contact_models) {
      Physics p;
      p.base = base_name(flatten_m);
      p.flatten_m = flatten_m;
      p.base_scene = scene;
      p.law.method = c.method;
      if (c.method == contact::ContactMethod::penalty) p.law.normal_stiffness = c.normal_stiffness;
      p.law.restitution = s.restitution.front();
      p.law.damping = s.damping.front();
      p.law.friction = s.friction.front();
      out.push_back(p);
    }
  }
  return out;
}

SecondStage second_stage_design(const calibration::OutcomeGrid& grid, const std::vector<int>& observed,
                                const std::vector<Physics>& stage1, const CalibrationSettings& s) {
  const std::vector<calibration::Candidate> best = best_per_variant(grid, observed);
  SecondStage out;
  std::set<double> headings;
  for (int k = 0; k < std::min<int>(s.keep, int(best.size())); ++k) {
    const Physics& p = stage1[std::size_t(best[std::size_t(k)].variant)];
    const double h = grid.heading_deg(best[std::size_t(k)].heading);
    for (int j = -2; j <= 2; ++j) headings.insert(wrap360(h + j * s.refine_step_deg));
    // the impact law: restitution for rigid contact, damping for the penalty springs
    for (double law : p.penalty() ? s.damping : s.restitution) {
      for (double mu : s.friction) {
        Physics q = p;
        (p.penalty() ? q.law.damping : q.law.restitution) = law;
        q.law.friction = mu;
        out.physics.push_back(q);
      }
    }
    out.kept.push_back(format("stage 1 keeps %s at heading %g deg (log-likelihood %.2f)", p.label().c_str(), h,
                              best[std::size_t(k)].log_likelihood));
  }
  out.headings_deg.assign(headings.begin(), headings.end());
  return out;
}

Calibrator::Calibrator(CalibrationSettings settings, Callbacks callbacks)
    : settings_(std::move(settings)), callbacks_(std::move(callbacks)) {
  if (!callbacks_.import_scan) callbacks_.import_scan = [](const scan::ImportOptions& o) { scan::import_scan(o); };
}

std::string first_stage_purpose(const CalibrationSettings& s) {
  return "stage 1 (every base model x contact law on a ring of " + std::to_string(s.headings) + " headings)";
}

std::string second_stage_purpose() { return "stage 2 (the best of stage 1 x impact law x friction, finer headings)"; }

PhysicalLimits design_limits(const std::vector<std::string>& base_scenes) {
  PhysicalLimits limits;
  for (const std::string& path : base_scenes) {
    const scenario::Scene scene = io::load_scene(path);
    const auto rocking = analysis::rocking_parameters(scene);
    if (!rocking)
      throw InputError(path, 0, "has no single free block standing on its pedestal (no rocking parameters)");
    const Range k = stiffness_limits(scene.bodies, rocking->radius * std::sin(rocking->alpha));
    limits.normal_stiffness.low = std::max(limits.normal_stiffness.low, k.low);
    limits.normal_stiffness.high = std::min(limits.normal_stiffness.high, k.high);
  }
  return limits;
}

campaign::CampaignOptions Calibrator::stage_options(int stage, const std::vector<Physics>& physics,
                                                    const std::vector<double>& headings,
                                                    const std::string& purpose) const {
  const CalibrationSettings& o = settings_;
  io::JobFile job = designed_job(physics.front().base_scene, lab_);
  job.variants = physics_variants(physics);
  job.records = windows_;
  job.rotation_angles_deg = headings;
  const std::string path = (fs::path(work_) / ("stage" + std::to_string(stage) + ".toml")).string();
  io::write_job_file(path, job,
                     purpose + " of rigid shaketable calibrate " + o.scan + " --tests " + o.tests +
                         "\n(written by the command; run again to resume)");
  campaign::CampaignOptions options;
  options.job = path;
  options.output = (fs::path(work_) / ("stage" + std::to_string(stage) + ".h5")).string();
  if (callbacks_.on_campaign) callbacks_.on_campaign(options, "shaketable: " + purpose);
  callbacks_.tell(format("shaketable: %s: %zu physics variants x %zu headings x %zu tests = %zu runs (%s)",
                         purpose.c_str(), physics.size(), headings.size(), windows_.size(),
                         physics.size() * headings.size() * windows_.size(), path.c_str()));
  return options;
}

campaign::CampaignOptions Calibrator::prepare() {
  const CalibrationSettings& o = settings_;
  check_settings(o);
  tests_ = io::read_lab_tests(o.tests);
  io::require_outcomes(tests_, "calibration fits the observed outcomes");
  std::map<std::string, int> groups;
  for (const io::LabTest& t : tests_.tests) {
    observed_.push_back(*t.overturned);
    group_.push_back(groups.emplace(t.record, int(groups.size())).first->second);
  }
  const long overturned = std::count(observed_.begin(), observed_.end(), 1);
  if (overturned == 0 || overturned == long(observed_.size())) {
    throw InputError(o.tests, 0,
                     std::string("all ") + std::to_string(observed_.size()) + " tests " +
                         (overturned ? "overturned" : "stood") +
                         ": outcomes that are all equal cannot identify the rock's parameters");
  }
  lab_ = lab_input(o.lab_format);
  work_ = o.out + ".calibration";
  {  // every output checked against every input before the first write
    const io::InputFiles inputs = command_inputs(o.tests, tests_, lab_, {}, {o.scan});
    for (const std::string& ending :
         std::vector<std::string>{".toml", ".state.toml", ".calibration.json", ".calibration." + o.figure_format})
      inputs.refuse_as_output(o.out + ending);
    inputs.refuse_folder(work_);
  }
  claim_work_folder(calibration_manifest(o, tests_));
  // the scan once per base model
  std::map<double, std::string> bases;
  for (double flatten_m : o.flatten_base_m) {
    const std::string name = base_name(flatten_m);
    const scan::ImportOptions in = base_model_import(o, o.scan, flatten_m, (fs::path(work_) / name / name).string());
    callbacks_.tell(format("shaketable: base model %s (--flatten-base %g m)", name.c_str(), in.flatten_base));
    callbacks_.import_scan(in);
    bases_[flatten_m] = bases[flatten_m] =
        fs::absolute(fs::path(work_) / name / (name + ".toml")).lexically_normal().string();
  }
  // the window's level (window_level_g): the design's contact laws decide, not the bases' scenes
  const bool rigid_only = std::all_of(o.contact_models.begin(), o.contact_models.end(),
                                      [](const ContactChoice& c) { return c.method == contact::ContactMethod::rigid; });
  double weakest = 1e300;
  for (const auto& [_, scene] : bases) weakest = std::min(weakest, static_toppling_g(scene));
  const double level_g = window_level_g(rigid_only, weakest);
  windows_ = strong_motion_records(tests_, lab_, level_g);
  double kept = 0;
  for (const auto& w : windows_) kept += w.end - w.start;
  callbacks_.tell(
      format("shaketable: %zu tests of %zu recorded motions (%ld overturned); strong-motion windows (|a| > %.3f g, "
             "%s of the weakest base's static toppling acceleration%s) keep %.0f s of motion",
             tests_.tests.size(), groups.size(), overturned, level_g, rigid_only ? "half" : "a tenth",
             rigid_only ? "" : ": penalty contact rocks the rock below it", kept));
  std::vector<std::string> base_scenes;
  for (const auto& [_, scene] : bases) base_scenes.push_back(scene);
  limits_ = design_limits(base_scenes);
  callbacks_.tell(
      format("shaketable: edge extension (--extend-stages %d): K_N within [%.3g, %.3g] N/m^1.5, D [%g, %g] "
             "s/m, e [%g, %g], mu [%g, %g], lapse [%g, %g] (docs/physics.md)",
             o.extend_stages, limits_.normal_stiffness.low, limits_.normal_stiffness.high, limits_.damping.low,
             limits_.damping.high, limits_.restitution.low, limits_.restitution.high, limits_.friction.low,
             limits_.friction.high, limits_.lapse.low, limits_.lapse.high));
  Stage first{first_stage_purpose(o), first_stage_physics(bases, o), heading_ring(o.headings), {}};
  for (Physics& p : first.physics) p.base_scene = settled_scene(o.scan, p.base_scene, p, work_);
  stages_.push_back(std::move(first));
  const Stage& s = stages_.back();
  return stage_options(1, s.physics, s.headings, s.purpose);
}

void Calibrator::claim_work_folder(const std::string& manifest) {
  const fs::path work(work_), manifest_file = fs::path(work_) / "calibration.manifest";
  std::error_code ec;
  fs::create_directories(fs::absolute(settings_.out).parent_path(), ec);
  lock_ = std::make_unique<campaign::OutputLock>(settings_.out, "--out");
  if (settings_.restart) fs::remove_all(work, ec);
  if (fs::exists(manifest_file)) {
    std::ifstream in(manifest_file);
    std::stringstream then;
    then << in.rdbuf();
    if (then.str() != manifest) {
      std::istringstream a(then.str()), b(manifest);
      std::string was, now;
      while (std::getline(a, was) && std::getline(b, now) && was == now) {
      }
      const bool outcomes_only = now.rfind("outcomes:", 0) == 0;
      throw InputError(work_, 0,
                       outcomes_only
                           ? "was started on other outcomes of " + settings_.tests +
                                 " (the second stage is designed on them): run again with --restart to start over"
                           : "holds a calibration of other inputs or settings (then '" + was + "', now '" + now +
                                 "'): choose another --out, or --restart to start over");
    }
    return;  // the same calibration: its campaigns resume
  }
  if (fs::exists(work) && !fs::is_empty(work, ec))
    throw InputError(work_, 0,
                     "exists and is not a calibration's work folder (no calibration.manifest): choose another "
                     "--out, or --restart to start over");
  fs::create_directories(work, ec);
  if (ec) throw InputError(work_, 0, "cannot create the calibration's folder: " + ec.message());
  io::write_output_file(manifest_file.string(), [&](std::ostream& out) { out << manifest; });
}

std::optional<campaign::CampaignOptions> Calibrator::next(const campaign::CampaignResult* previous) {
  if (done_) return std::nullopt;
  if (stages_.empty()) return prepare();
  Stage& last = stages_.back();
  last.grid = outcome_grid(*previous->cube, last.headings);
  if (stages_.size() == 1) {
    SecondStage second = second_stage_design(*last.grid, observed_, last.physics, settings_);
    for (const std::string& line : second.kept) callbacks_.tell("shaketable: " + line);
    stages_.push_back({second_stage_purpose(), std::move(second.physics), std::move(second.headings_deg), {}});
    const Stage& s = stages_.back();
    return stage_options(2, s.physics, s.headings, s.purpose);
  }
  return extend(*previous);
}

std::optional<campaign::CampaignOptions> Calibrator::extend(const campaign::CampaignResult&) {
  const Stage& last = stages_.back();
  fitted_ = fitted_ ? calibration::join_variants(*fitted_, *last.grid) : *last.grid;
  fitted_physics_.insert(fitted_physics_.end(), last.physics.begin(), last.physics.end());
  const LapseExtension lapse = extend_lapses(*fitted_, observed_, {}, limits_.lapse);
  search_ = lapse.search;
  const int extended = int(stages_.size()) - 2;
  const ExtensionStage ext = extension_stage(*fitted_, observed_, fitted_physics_, stages_.front().physics, search_,
                                             limits_, extended < settings_.extend_stages);
  parameters_ = ext.parameters;
  parameters_.push_back(lapse.report);
  if (ext.physics.empty()) {
    for (const ParameterReport& r : parameters_) {
      std::string tried;
      for (double v : r.tried) tried += format("%s%.3g", tried.empty() ? "" : ", ", v);
      callbacks_.tell(
          format("shaketable: %s = %.3g of [%s]: %s", r.name.c_str(), r.value, tried.c_str(), status_text(r.status)));
    }
    done_ = true;
    return std::nullopt;
  }
  Stage next{stage_purpose(int(stages_.size()) + 1, ext.moves), ext.physics, last.headings, {}};
  for (Physics& p : next.physics) {
    if (p.base_scene.empty()) p.base_scene = settled_scene(settings_.scan, bases_.at(p.flatten_m), p, work_);
  }
  stages_.push_back(std::move(next));
  const Stage& s = stages_.back();
  return stage_options(int(stages_.size()), s.physics, s.headings, s.purpose);
}

CalibrationSummary Calibrator::finish() const {
  CalibrationReport report;
  report.scan = settings_.scan;
  report.tests_csv = settings_.tests;
  report.out = settings_.out;
  report.command_line = settings_.command_line;
  report.observed = observed_;
  report.group = group_;
  for (const Stage& s : stages_) {
    report.stages.emplace_back(&*s.grid, s.physics);
    report.stage_purposes.push_back(s.purpose);
  }
  report.fitted = &*fitted_;
  report.fitted_physics = fitted_physics_;
  report.search = search_;
  report.parameters = parameters_;
  report.limits = limits_;
  for (const io::LabTest& t : tests_.tests) report.records.push_back(t.record);
  report.lab_format_file = lab_.format_file;
  report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return write_calibration(report);
}

}  // namespace rigid::shaketable
