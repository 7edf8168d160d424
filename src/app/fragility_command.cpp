// `rigid fragility CUBE ...` and `rigid hazard CUBE --curve ... --age ...`: fitted fragilities
// (per PGV/PGA bin and the vector fit, bootstrap intervals over records), their CSV and OpenQuake
// NRML exports, and the toppling rate and survival probability of a rock under a PGA hazard curve.
// The statistics live in src/python/rigid_fragility.py (scipy, statsmodels, h5py: Debian packages of
// /usr/bin/python3); as with `rigid plot`, this command finds the script and replaces itself with
// `PYTHON SCRIPT fragility|hazard ARGS...`, so output, signals and exit status (0 done, 2 bad
// input, 1 internal error) are rigid's own. Every argument after the command name, --help
// included, goes to the script unchanged.
#include <string>
#include <vector>

#include "commands.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"

namespace rigid::app {

namespace {

constexpr const char* kScript = "rigid_fragility.py";

void register_fragility_script_command(CLI::App& app, const std::string& name, const std::string& description) {
  CLI::App* cmd = app.add_subcommand(name, description);
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->callback([cmd, name] {
    const std::string script = find_plot_helper(kScript);
    if (script.empty())
      throw InputError("", 0, std::string("cannot find ") + kScript + " (src/python beside the build)");
    std::vector<std::string> args{name};
    for (const std::string& a : cmd->remaining()) args.push_back(a);
    exec_python(script, args,
                "`rigid " + name +
                    "` needs Debian's python3 with python3-numpy, python3-h5py, python3-scipy, "
                    "python3-statsmodels and python3-matplotlib (setup.sh installs them)");
  });
}

}  // namespace

void register_fragility_commands(CLI::App& app) {
  register_fragility_script_command(
      app, "fragility",
      "Fit each object's fragility from a campaign cube by maximum likelihood on its simulated cells: a "
      "lognormal (theta, beta) per PGV/PGA bin and the vector fit at a chosen PGV/PGA, 90 % intervals "
      "by bootstrap over records; a table, --json, --csv FILE, --nrml FILE (OpenQuake NRML 0.5; "
      "--nrml-at-pgv-pga S: the vector fit at a site's PGV/PGA), --vector-csv FILE (its coefficients), and the "
      "fits stored in the cube's /fragility group. `rigid fragility --help` for the options");
  register_fragility_script_command(
      app, "hazard",
      "Annual toppling rate of a rock under a PGA hazard curve (CSV: two columns, OpenQuake or nshmp-haz "
      "layouts), its survival probability over an exposure age with the fit's interval, and how far the "
      "curve must rise before the rock's survival rules it out: `rigid hazard CUBE --curve CSV --age "
      "YEARS`; `rigid hazard reweight OQ_DIR --rock CUBE:OBJECT --age YEARS` reweights the branches of an "
      "OpenQuake logic tree by the rock's survival; `rigid hazard [reweight] --help` for the options");
}

}  // namespace rigid::app
