// `rigid shaketable calibrate`: fits a scanned rock's uncertain physics (its heading on the table,
// the model of its rough base, the contact law and its compliance, restitution, friction) to
// observed shake-table outcomes by maximum likelihood, over campaigns it designs in two stages:
// (1) every base model and contact law at a coarse ring of headings, (2) the best of those, crossed
// with restitution and friction, at a finer ring around their best headings. The campaigns are
// ordinary campaigns (MPI, checkpoints, resume). docs/validation-shaketable.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "campaign_report.hpp"
#include "commands.hpp"
#include "import_report.hpp"
#include "number_checks.hpp"
#include "rigid/campaign/driver.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/scenario/scene.hpp"
#include "shaketable.hpp"
#include "shaketable_report.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;
using shaketable::Physics;

struct CalibrateOptions {
  std::string scan, tests, out, lab_format;
  double scale = 1.0;
  std::string up = "z";
  std::vector<double> flatten_mm{5.0};
  std::vector<std::string> contact_models{"rigid", "5e5", "1e6", "2e6"};
  std::vector<double> restitution{0.0, 0.5};
  std::vector<double> damping{2.0, 1.0, 4.0};
  std::vector<double> friction{0.6, 0.9};
  int headings = 12;
  int keep = 1;
  double refine_step_deg = 10;
  double tilt_deg = 30;
  int max_vertices = 64;
  double pedestal_margin = 0.5;
  std::string progress = "auto";
};

// What rank 0 carries from one stage to the next.
struct Calibration {
  io::LabTestList tests;
  std::vector<int> observed, group;
  std::vector<io::DesignJob::Record> windows;
  shaketable::LabInput lab;
  fs::path work;
  std::vector<Physics> stage1, stage2;
  std::vector<double> headings1, headings2;
  std::optional<calibration::OutcomeGrid> grid1, grid2;
  int stage = 0;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
};

void check(const CalibrateOptions& o) {
  if (o.flatten_mm.empty() || o.contact_models.empty() || o.restitution.empty() || o.damping.empty() ||
      o.friction.empty())
    throw InputError(
        "", 0, "--flatten-mm, --contact-models, --restitution, --damping and --friction need at least one value each");
  for (double d : o.damping) {
    if (!(d >= 0 && d <= 100)) throw InputError("", 0, "--damping: values must be in [0, 100] s/m");
  }
  for (double f : o.flatten_mm) {
    if (!(f >= 0 && f < 100)) throw InputError("", 0, "--flatten-mm: depths must be in [0, 100) mm");
  }
  for (const std::string& c : o.contact_models) {
    if (c == "rigid") continue;
    const std::optional<double> k = whole_number(c);
    if (!k || !(*k >= 1e5 && *k <= 1e13))
      throw InputError(
          "", 0, "--contact-models: '" + c + "' is neither rigid nor a penalty stiffness K_N in [1e5, 1e13] N/m^1.5");
  }
  for (double e : o.restitution) {
    if (!(e >= 0 && e <= 1)) throw InputError("", 0, "--restitution: values must be in [0, 1]");
  }
  for (double mu : o.friction) {
    if (!(mu > 0 && mu <= 10)) throw InputError("", 0, "--friction: values must be in (0, 10]");
  }
  if (o.headings < 4 || o.headings > 72) throw InputError("", 0, "--headings must be 4 to 72");
  if (o.keep < 1 || o.keep > 10) throw InputError("", 0, "--keep must be 1 to 10");
  if (!(o.refine_step_deg > 0 && o.refine_step_deg < 360.0 / o.headings))
    throw InputError("", 0, "--refine-step must be positive and below the coarse heading step");
  if (!(o.tilt_deg > 0 && o.tilt_deg < 90)) throw InputError("", 0, "--tilt-deg must be in (0, 90)");
  if (fs::path(o.out).filename().empty()) throw InputError("", 0, "--out needs DIR/NAME");
}

std::string base_name(double mm) {
  char text[32];
  std::snprintf(text, sizeof text, "flat_%gmm", mm);
  return text;
}

// Imports the scan once per base model into the work folder.
std::map<double, std::string> import_bases(const CalibrateOptions& o, const fs::path& work) {
  std::map<double, std::string> scenes;
  for (double mm : o.flatten_mm) {
    const std::string name = base_name(mm);
    scan::ImportOptions in;
    in.scan = o.scan;
    in.out = (work / name / name).string();
    in.scale = o.scale;
    in.up = o.up;
    in.max_vertices = o.max_vertices;
    in.pedestal_margin = o.pedestal_margin;
    in.flatten_base = mm * 1e-3;
    in.tilt_deg = o.tilt_deg;
    std::printf("shaketable: base model %s (--flatten-base %g m)\n", name.c_str(), in.flatten_base);
    import_and_report(in);
    scenes[mm] = fs::absolute(work / name / (name + ".toml")).lexically_normal().string();
  }
  return scenes;
}

// The base model's scene with the contact model's law, settled with it: a soft contact sinks and
// leans the rock, and a run that started from the rigid pose would begin with that motion.
std::string settled_scene(const std::string& scan, const std::string& base_scene, const Physics& p,
                          const fs::path& work) {
  char name[96];
  if (p.contact == "penalty")
    std::snprintf(name, sizeof name, "%s_k%.3g", p.base.c_str(), p.normal_stiffness);
  else
    std::snprintf(name, sizeof name, "%s_rigid", p.base.c_str());
  fs::create_directories(work / name);
  const std::string scene = fs::absolute(work / name / (std::string(name) + ".toml")).lexically_normal().string();
  io::SceneChanges changes;
  changes.physics = p.contact_law_table();
  changes.comment =
      std::string(name) + ": " + base_scene + " with the " + p.contact + " contact model, settled with it";
  io::write_derived_scene(base_scene, scene, changes);
  const scenario::Scene placed = io::load_scene(scene);
  const scenario::Scene settled = scenario::equilibrate(placed, dynamics::StepSettings{});
  for (std::size_t i = 0; i < placed.bodies.size(); ++i) {
    const double turned = scenario::tilt(placed.bodies[i].orientation, settled.bodies[i].orientation) * 180 / kPi;
    if (!placed.bodies[i].fixed && turned > 5.0) {
      char text[200];
      std::snprintf(text, sizeof text, "does not stand on its base: settling with %s contact tilted it %.1f deg",
                    p.contact.c_str(), turned);
      throw InputError(scan, 0, text);
    }
  }
  io::save_state(scene.substr(0, scene.size() - 5) + ".state.toml", settled);
  return scene;
}

std::vector<double> ring(int count) {
  std::vector<double> h;
  for (int k = 0; k < count; ++k) h.push_back(360.0 * k / count);
  return h;
}

double wrap360(double deg) {
  double h = std::fmod(deg, 360.0);
  if (h < 0) h += 360.0;
  return std::round(h * 1e6) / 1e6;
}

campaign::CampaignOptions stage_options(const Calibration& c, const CalibrateOptions& o, int stage,
                                        const std::vector<Physics>& physics, const std::vector<double>& headings) {
  io::DesignJob job;
  job.comment = "stage " + std::to_string(stage) + " of rigid shaketable calibrate " + o.scan + " --tests " + o.tests +
                "\n(written by the command; run again to resume)";
  job.object_name = "rock";
  job.scene = physics.front().base_scene;
  for (const Physics& p : physics) job.variants.push_back(p.variant_table());
  job.records = c.windows;
  job.lab_format_file = c.lab.format_file.empty() ? "" : fs::absolute(c.lab.format_file).string();
  job.rotation_angles_deg = headings;
  const std::string path = (c.work / ("stage" + std::to_string(stage) + ".toml")).string();
  io::write_design_job(path, job);
  campaign::CampaignOptions options;
  options.job = path;
  options.output = (c.work / ("stage" + std::to_string(stage) + ".h5")).string();
  attach_progress(options, o.progress, 10);
  std::printf("shaketable: stage %d: %zu physics variants x %zu headings x %zu tests = %zu runs (%s)\n", stage,
              physics.size(), headings.size(), c.windows.size(), physics.size() * headings.size() * c.windows.size(),
              path.c_str());
  std::fflush(stdout);
  return options;
}

// Rank 0, before any campaign: tests, bases, windows, the first stage.
campaign::CampaignOptions prepare(Calibration& c, const CalibrateOptions& o) {
  check(o);
  c.tests = io::read_lab_tests(o.tests);
  if (!c.tests.has_outcomes)
    throw InputError(o.tests, 1, "has no 'overturned' column: calibration fits the observed outcomes");
  std::map<std::string, int> groups;
  for (const io::LabTest& t : c.tests.tests) {
    c.observed.push_back(*t.overturned);
    c.group.push_back(groups.emplace(t.record, int(groups.size())).first->second);
  }
  const long overturned = std::count(c.observed.begin(), c.observed.end(), 1);
  if (overturned == 0 || overturned == long(c.observed.size())) {
    throw InputError(o.tests, 0,
                     std::string("all ") + std::to_string(c.observed.size()) + " tests " +
                         (overturned ? "overturned" : "stood") +
                         ": outcomes that are all equal cannot identify the rock's parameters");
  }
  c.lab = shaketable::lab_input(o.lab_format);
  c.work = fs::path(o.out + ".calibration");
  std::error_code ec;
  fs::create_directories(c.work, ec);
  if (ec) throw InputError(c.work.string(), 0, "cannot create the calibration's folder: " + ec.message());
  const std::map<double, std::string> bases = import_bases(o, c.work);
  // the window's level (window_level_g): the design's contact laws decide, not the bases' scenes
  const bool rigid_only =
      std::all_of(o.contact_models.begin(), o.contact_models.end(), [](const std::string& m) { return m == "rigid"; });
  double weakest = 1e300;
  for (const auto& [_, scene] : bases) weakest = std::min(weakest, shaketable::static_toppling_g(scene));
  const double level_g = shaketable::window_level_g(rigid_only, weakest);
  c.windows = shaketable::strong_motion_windows(c.tests, c.lab, level_g);
  double kept = 0;
  for (const auto& w : c.windows) kept += w.end - w.start;
  std::printf(
      "shaketable: %zu tests of %zu recorded motions (%ld overturned); strong-motion windows (|a| > %.3f g, "
      "%s of the weakest base's static toppling acceleration%s) keep %.0f s of motion\n",
      c.tests.tests.size(), groups.size(), overturned, level_g, rigid_only ? "half" : "a tenth",
      rigid_only ? "" : ": penalty contact rocks the rock below it", kept);
  for (const auto& [mm, scene] : bases) {
    for (const std::string& model : o.contact_models) {
      Physics p;
      p.base = base_name(mm);
      p.flatten_m = mm * 1e-3;
      p.contact = model == "rigid" ? "rigid" : "penalty";
      if (model != "rigid") p.normal_stiffness = *whole_number(model);  // check() refused any other text
      p.restitution = o.restitution.front();
      p.damping = o.damping.front();
      p.friction = o.friction.front();
      p.base_scene = settled_scene(o.scan, scene, p, c.work);
      c.stage1.push_back(p);
    }
  }
  c.headings1 = ring(o.headings);
  c.stage = 1;
  return stage_options(c, o, 1, c.stage1, c.headings1);
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

campaign::CampaignOptions second_stage(Calibration& c, const CalibrateOptions& o) {
  const std::vector<calibration::Candidate> best = best_per_variant(*c.grid1, c.observed);
  std::set<double> headings;
  for (int k = 0; k < std::min<int>(o.keep, int(best.size())); ++k) {
    const Physics& p = c.stage1[std::size_t(best[std::size_t(k)].variant)];
    const double h = c.grid1->heading_deg(best[std::size_t(k)].heading);
    for (int j = -2; j <= 2; ++j) headings.insert(wrap360(h + j * o.refine_step_deg));
    // the impact law: restitution for rigid contact, damping for the penalty springs
    for (double law : p.contact == "rigid" ? o.restitution : o.damping) {
      for (double mu : o.friction) {
        Physics q = p;
        (p.contact == "rigid" ? q.restitution : q.damping) = law;
        q.friction = mu;
        c.stage2.push_back(q);
      }
    }
    std::printf("shaketable: stage 1 keeps %s at heading %g deg (log-likelihood %.2f)\n", p.label().c_str(), h,
                best[std::size_t(k)].log_likelihood);
  }
  c.headings2.assign(headings.begin(), headings.end());
  c.stage = 2;
  return stage_options(c, o, 2, c.stage2, c.headings2);
}

void finish(const Calibration& c, const CalibrateOptions& o) {
  shaketable::CalibrationReport report;
  report.scan = o.scan;
  report.tests_csv = o.tests;
  report.out = o.out;
  report.tests = &c.tests;
  report.observed = c.observed;
  report.group = c.group;
  report.stages = {{&*c.grid1, c.stage1}, {&*c.grid2, c.stage2}};
  report.windows = c.windows;
  report.lab_format_file = c.lab.format_file;
  report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - c.start).count();
  shaketable::write_calibration(report);
}

}  // namespace

void add_shaketable_calibrate(CLI::App& parent) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "calibrate",
      "Fit a scanned rock's heading on the table, base model, contact law and its compliance, restitution and "
      "friction to observed shake-table outcomes by maximum likelihood (run under mpirun like a campaign; run again to "
      "resume). Writes OUT.toml (the calibrated scene), OUT.calibration.json and the work folder OUT.calibration/");
  cmd->add_option("scan", o->scan, "The rock's scan (OBJ, PLY, STL), as for rigid model import")->required();
  cmd->add_option("--tests", o->tests,
                  "Test list CSV: test_no,record,pgv_over_pga_s,pga_g,file,overturned (file relative to the CSV)")
      ->required();
  cmd->add_option("--out", o->out, "Output DIR/NAME")->required();
  cmd->add_option("--scale", o->scale, "Scan units to metres, as for rigid model import")->capture_default_str();
  cmd->add_option("--up", o->up, "The scan's up axis, as for rigid model import")->capture_default_str();
  cmd->add_option("--flatten-mm", o->flatten_mm,
                  "Base models to compare: the rough base cut flat this far above its lowest point (mm)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--contact-models", o->contact_models,
                  "Contact laws to compare: rigid, or a penalty stiffness K_N (N/m^1.5, e.g. 1e7)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--restitution", o->restitution,
                  "Restitution values of the rigid contact (the first in stage 1, all in stage 2)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--damping", o->damping,
                  "Damping D of the penalty contact (s/m; the first in stage 1, all in stage 2)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--friction", o->friction, "Friction coefficients (the first in stage 1, all in stage 2)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--headings", o->headings, "Stage 1: headings on a full ring")->capture_default_str();
  cmd->add_option("--keep", o->keep, "Stage 2: the best stage-1 variants refined")->capture_default_str();
  cmd->add_option("--refine-step", o->refine_step_deg,
                  "Stage 2: heading step around each kept variant's best heading (deg)")
      ->capture_default_str();
  cmd->add_option("--tilt-deg", o->tilt_deg, "Overturned = tilted beyond this angle (deg)")->capture_default_str();
  cmd->add_option("--max-vertices", o->max_vertices, "Vertex budget of the rock's hull")->capture_default_str();
  cmd->add_option("--pedestal-margin", o->pedestal_margin, "The table: overhang of the box under the rock (m)")
      ->capture_default_str();
  shaketable::add_recording_options(*cmd, o->lab_format, o->progress);
  cmd->callback([o] {
    Calibration c;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult* previous) -> std::optional<campaign::CampaignOptions> {
          if (c.stage == 0) return prepare(c, *o);
          if (c.stage == 1) {
            c.grid1 = shaketable::outcome_grid(*previous->cube, c.headings1);
            return second_stage(c, *o);
          }
          c.grid2 = shaketable::outcome_grid(*previous->cube, c.headings2);
          c.stage = 3;
          return std::nullopt;
        },
        [&](const campaign::CampaignResult&) { finish(c, *o); });
  });
}

}  // namespace rigid::app
