// `rigid model library`: writes the rock library (models/library) from
// rigid::library::rock_library(): per model its STL meshes, an original Rigid model file, a TOML
// scene and the equilibrated state; `--card` measures each model's quasi-static toppling
// acceleration by tilt tests and prints the card table (markdown) for models/library/README.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "output_options.hpp"
#include "rigid/analysis/tilt_test.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/io/stl.hpp"
#include "rigid/library/rock_library.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;

struct LibraryOptions {
  std::string out = "models/library";
  std::vector<std::string> only;
  bool card = false;       // measure and print the card after writing
  bool card_only = false;  // measure the files already in `out`, write nothing
  int azimuths = 8;
};

std::string fixed_text(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

void write_model(const library::LibraryModel& m, const fs::path& root) {
  const fs::path dir = root / m.name;
  fs::create_directories(dir);
  std::vector<io::SceneBlock> blocks;  // the original model format: no comments, study defaults for the physics
  for (const auto& p : m.pieces) {
    io::write_stl_ascii((dir / (p.name + ".stl")).string(), p.soup, p.name);
    blocks.push_back({p.name, p.name + ".stl", p.fixed, {}});
  }
  const std::string model_path = (dir / (m.name + ".model")).string();
  io::write_model_file(model_path, blocks);
  const std::string scene_path = (dir / (m.name + ".toml")).string();
  io::SceneFile scene_file;
  scene_file.comments = {m.description + ".", "Failure rule " + m.failure_note + ".",
                         "Regenerate: rigid model library --out " + root.generic_string() + " --only " + m.name +
                             " (models/library/README.md)"};
  scene_file.model = m.name + ".model";
  scene_file.state = m.name + ".state.toml";
  if (m.failure.kind == scenario::FailureRule::Kind::tilt) {
    // to a tenth of a degree, as the library states its rules
    scene_file.tilt_rule_deg = std::round(m.failure.tilt_angle * 180.0 / kPi * 10.0) / 10.0;
  }
  io::write_scene(scene_path, scene_file);
  // the equilibrium the shaking runs start from, computed from the files just written so that it
  // belongs to exactly these meshes
  scenario::Scene scene = io::load_scene(model_path);
  scene.failure = m.failure;
  const scenario::Scene settled = scenario::equilibrate(scene, dynamics::StepSettings{});
  io::save_state((dir / (m.name + ".state.toml")).string(), settled);
  double moved = 0, turned = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    moved = std::max(moved, (settled.bodies[i].position - scene.bodies[i].position).norm());
    turned = std::max(turned, scenario::tilt(scene.bodies[i].orientation, settled.bodies[i].orientation));
  }
  std::printf("wrote %s: %zu blocks; settling moved them up to %.2f mm and %.3f deg\n", dir.generic_string().c_str(),
              m.pieces.size(), 1e3 * moved, turned * 180.0 / kPi);
  std::fflush(stdout);
}

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? sep : "") + items[i];
  return s;
}

std::string accel_text(double g) { return std::isfinite(g) ? fixed_text(g, 3) : "> 1"; }

void print_card(const std::vector<library::LibraryModel>& models, const fs::path& root, int azimuths) {
  std::vector<std::string> rows, detail;
  for (const auto& m : models) {
    const fs::path scene_path = root / m.name / (m.name + ".toml");
    const scenario::Scene scene = io::load_scene(scene_path.string());
    std::fprintf(stderr, "card: %s ...\n", m.name.c_str());
    const auto survey = analysis::tilt_survey(scene, azimuths);
    std::vector<std::string> heights, masses;
    double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
    int free = 0;
    for (const auto& b : scene.bodies) {
      if (b.fixed) continue;
      ++free;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const auto& v : b.shape.vertices) {
        const double z = (b.orientation * v + b.position).z();
        lo = std::min(lo, z);
        hi = std::max(hi, z);
      }
      heights.push_back(fixed_text(hi - lo, 2));
      masses.push_back(fixed_text(b.shape.mass, 0));
      top = std::max(top, hi);
      bottom = std::min(bottom, lo);
    }
    const auto& worst = *std::min_element(survey.results.begin(), survey.results.end(),
                                          [](const auto& a, const auto& b) { return a.acceleration < b.acceleration; });
    std::string statics = "-";
    if (m.simple_stack) {
      statics = fixed_text(library::static_toppling(m, survey.azimuth_of_minimum), 3) + " (" +
                fixed_text(library::static_toppling(m, -1), 3) + ")";
    }
    const bool tilt = m.failure.kind == scenario::FailureRule::Kind::tilt;
    rows.push_back("| " + m.name + " | " + std::to_string(free) + " + " + std::to_string(scene.bodies.size() - free) +
                   " | " + join(heights, ", ") + " | " + fixed_text(top - bottom, 2) + " | " + join(masses, ", ") +
                   " | **" + accel_text(survey.minimum) + "** | " +
                   fixed_text(survey.azimuth_of_minimum * 180.0 / kPi, 0) + " | " + worst.block + " | " + statics +
                   " | " + (tilt ? "tilt " + fixed_text(m.failure.tilt_angle * 180.0 / kPi, 0) : std::string("below")) +
                   " |");
    std::string d = "| " + m.name + " |";
    for (const auto& r : survey.results) d += " " + accel_text(r.acceleration) + " |";
    detail.push_back(d);
  }
  std::printf(
      "| model | blocks (free + fixed) | free-block heights (m) | free height (m) | free-block masses (kg) | "
      "toppling acceleration (g) | azimuth (deg) | first to go | rigid statics (g) | failure rule |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : rows) std::printf("%s\n", r.c_str());
  std::printf("\nPer azimuth of the ground acceleration (g; \"> 1\": stood 1 g):\n\n| model |");
  for (int j = 0; j < azimuths; ++j) std::printf(" %s deg |", fixed_text(360.0 * j / azimuths, 0).c_str());
  std::printf("\n|---|");
  for (int j = 0; j < azimuths; ++j) std::printf("---|");
  std::printf("\n");
  for (const auto& d : detail) std::printf("%s\n", d.c_str());
}

void run_library(const LibraryOptions& o) {
  if (o.azimuths < 1) throw InputError("", 0, "--azimuths must be at least 1");
  std::vector<library::LibraryModel> models;
  std::vector<std::string> known;
  for (auto& m : library::rock_library()) {
    known.push_back(m.name);
    if (o.only.empty() || std::find(o.only.begin(), o.only.end(), m.name) != o.only.end())
      models.push_back(std::move(m));
  }
  for (const auto& name : o.only) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw InputError("", 0, "--only: no model '" + name + "' (models: " + join(known, ", ") + ")");
    }
  }
  const fs::path root(o.out);
  if (!o.card_only) {
    for (const auto& m : models) write_model(m, root);
  }
  if (o.card || o.card_only) print_card(models, root, o.azimuths);
}

}  // namespace

void add_library_subcommand(CLI::App& model_command) {
  auto o = std::make_shared<LibraryOptions>();
  CLI::App* lib =
      model_command.add_subcommand("library",
                                   "The rock library: rectangular blocks, geode and nine synthetic PBR analogues "
                                   "(STL, model file, TOML scene, equilibrated state per model)");
  add_output_directory(*lib, o->out, "one subdirectory per model")->capture_default_str();
  lib->add_option("--only", o->only, "Only these models (names, comma-separated)")->delimiter(',');
  lib->add_flag("--card", o->card,
                "After writing, measure each model's quasi-static toppling acceleration by tilt tests "
                "(minimum over the azimuths) and print the card table (markdown)");
  lib->add_flag("--card-only", o->card_only, "Print the card of the models already in --out; write nothing");
  lib->add_option("--azimuths", o->azimuths, "Tilt-test directions, evenly spaced from +x")->capture_default_str();
  lib->callback([o] { run_library(*o); });
}

}  // namespace rigid::app
