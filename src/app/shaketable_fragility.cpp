// `rigid shaketable fragility`: the flags of the fragility workflow (rigid::shaketable::FragilityDesign),
// then the fits, the table of medians and the figure, which are src/python/shaketable_fragility.py's,
// run once the campaign has ended (docs/validation-shaketable.md).
#include <cstdio>
#include <memory>

#include "old_spellings.hpp"
#include "output_options.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"
#include "rigid/shaketable/fragility.hpp"
#include "shaketable.hpp"

namespace rigid::app {
namespace {

struct FragilityFlags {
  rigid::shaketable::FragilitySettings settings;
  std::string progress = "auto";
  int bootstrap = 1000;
  long seed = 1;
};

}  // namespace

void add_shaketable_fragility(CLI::App& parent) {
  auto f = std::make_shared<FragilityFlags>();
  rigid::shaketable::FragilitySettings& o = f->settings;
  CLI::App* cmd = parent.add_subcommand(
      "fragility",
      "The rock's fragility two ways: the lab's (probit fit per PGV/PGA bin on the tests' measured PGA and outcomes) "
      "beside the (calibrated) scene's, from the same recorded motions scaled over a PGA grid; writes "
      "OUT.fragility.csv "
      "(medians with intervals) and the figure OUT.fragility.png");
  cmd->add_option("scene", o.scene, "The scene, e.g. OUT.toml of rigid shaketable calibrate")->required();
  cmd->add_option("--tests", o.tests, "Test list CSV with an overturned column; file relative to the CSV")->required();
  add_output_prefix(*cmd, o.out, "NAME.fragility.csv, NAME.fragility.FORMAT and the work folder NAME.fragility.work/")
      ->required();
  cmd->add_option("--min-pga", o.min_pga_g, "Bottom of the PGA grid (g)")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 5.0));
  cmd->add_option("--max-pga", o.max_pga_g, "Top of the PGA grid (g); default 1.25 x the largest measured PGA")
      ->check(CLI::Range(0.01, 20.0));
  cmd->add_option("--per-decade", o.per_decade, "PGAs per decade of the geometric grid")
      ->capture_default_str()
      ->check(CLI::Range(2, 100));
  cmd->add_option("--bins", o.bins_s,
                  "PGV/PGA bin edges (s), comma-separated, e.g. 0.02,0.06,0.1,0.3; default: three bins holding a "
                  "third of the motions each")
      ->delimiter(',');
  cmd->add_option("--bootstrap", f->bootstrap, "Bootstrap replicates of the 90 % intervals")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--seed", f->seed, "Seed of the bootstrap")->capture_default_str()->check(CLI::Range(0L, 1L << 62));
  CLI::Option* figure_format =
      cmd->add_option("--figure-format", o.figure_format, "The figure OUT.fragility.FORMAT: png, pdf or svg")
          ->capture_default_str()
          ->check(CLI::IsMember({"png", "pdf", "svg"}));
  add_old_spelling(*cmd, *figure_format, {"--format", "", {}});  // calibrate's spelling, one for both
  shaketable::add_recording_options(*cmd, o.lab_format, f->progress);
  cmd->callback([f] {
    const rigid::shaketable::FragilitySettings& o = f->settings;
    std::unique_ptr<rigid::shaketable::FragilityDesign> design;
    std::filesystem::path work;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult* previous) -> std::optional<campaign::CampaignOptions> {
          if (!design)
            design =
                std::make_unique<rigid::shaketable::FragilityDesign>(o, shaketable::command_callbacks(f->progress));
          return design->next(previous);
        },
        [&](const campaign::CampaignResult& result) { work = design->write_fit_inputs(*result.cube); });
    if (work.empty()) return;  // not rank 0
    // after MPI has ended: the fit replaces this process, its exit status is the command's
    const std::string script = find_plot_helper("shaketable_fragility.py");
    if (script.empty()) throw InputError("", 0, "cannot find shaketable_fragility.py (src/python beside the build)");
    std::vector<std::string> args{design->cube_path(),
                                  "--lab",
                                  (work / "lab_tests.csv").string(),
                                  "--motions",
                                  (work / "motions.csv").string(),
                                  "--model",
                                  (work / "model.csv").string(),
                                  "--out",
                                  o.out,
                                  "--bootstrap",
                                  std::to_string(f->bootstrap),
                                  "--seed",
                                  std::to_string(f->seed),
                                  "--format",
                                  o.figure_format,
                                  "--physics",
                                  design->physics_title()};
    if (!o.bins_s.empty()) {
      std::string edges;
      char edge[32];
      for (double e : o.bins_s) {
        std::snprintf(edge, sizeof edge, "%.17g", e);
        edges += (edges.empty() ? "" : ",") + std::string(edge);
      }
      args.push_back("--bins");
      args.push_back(edges);
    }
    exec_python(script, args,
                "`rigid shaketable fragility` needs Debian's python3 with python3-numpy, python3-h5py, python3-scipy "
                "and python3-matplotlib (setup.sh installs them)");
  });
}

}  // namespace rigid::app
