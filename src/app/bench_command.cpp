// `rigid bench`: speed of the engine on its reference scenes (the geode and the peer scene,
// docs/performance.md), as medians of repeated runs on this machine (one core).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/json.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/rocking/housner.hpp"
#include "rigid/scenario/accuracy.hpp"

namespace rigid::app {
namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The study's geode: a faceted near-sphere (320 facets) dropped 0.5 m on a plane, no friction,
// no damping, dt = 0.000314 s, 50 s simulated.
struct GeodeResult {
  double wall;
  long steps;
};
GeodeResult run_geode() {
  contact::ContactLaw law;
  law.method = contact::ContactMethod::penalty;
  law.friction = 0;
  law.damping = 0;
  auto geode = library::body_from_soup("geode", library::geodesic_sphere(0.15, 2), 2600, false);
  const Vec3 lowest = geode.shape.vertices[0];
  geode.orientation = Quat::FromTwoVectors(lowest, -Vec3::UnitZ());
  geode.position = Vec3(0, 0, 0.5 + lowest.norm());
  auto plane = library::box_body("plane", Vec3(-1, -1, -0.2), Vec3(1, 1, 0), 2600, true);
  dynamics::StepSettings settings;
  settings.dt = 0.000314;
  const auto start = Clock::now();
  dynamics::World world({plane, geode}, law, settings);
  const long steps = std::lround(50.0 / settings.dt);
  for (long k = 0; k < steps; ++k) world.step(settings.dt, Vec3::Zero(), Vec3::Zero());
  return {std::chrono::duration<double>(Clock::now() - start).count(), steps};
}

// The peer scene: a 1 m tall block, alpha = 0.2 rad, 0.5 m deep, on a pedestal, one-sine pulse
// of period 0.5 s, then free rocking until 15 s.
scenario::GroundDrive one_sine(double amplitude, double period) { return library::one_sine_drive(amplitude, period); }

struct Threshold {
  double g;
  double wall_per_run;  ///< median over the search's runs (unit: s)
  int runs;
};

// Overturning amplitude of the one-sine pulse by bisection between 0.2 g and 0.5 g, to 0.5 %.
Threshold pulse_threshold(const scenario::Scene& scene, const scenario::RunSettings& settings) {
  double lo = 0.2, hi = 0.5;  // g
  std::vector<double> walls;
  while (hi - lo > 0.005 * lo) {
    const double mid = 0.5 * (lo + hi);
    const auto start = Clock::now();
    const bool overturned = scenario::run(scene, one_sine(mid * kGravity, 0.5), settings).overturned;
    walls.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    (overturned ? hi : lo) = mid;
  }
  return {0.5 * (lo + hi), median(walls), int(walls.size())};
}

// The same scene in ODE (src/peer/ode_peer.cpp, built beside `rigid` when Debian's libode-dev is
// installed), run in this session so the figures compare: its threshold (same 0.5 % bisection)
// and median wall per run. Empty when the peer is not built.
struct PeerEngine {
  bool found = false;
  double threshold_g = 0, wall_per_run = 0, dt = 0;
  int runs = 0;
  double wall_at[2] = {0, 0};  ///< median wall of a 15 s run at kFixedAmplitudes (unit: s)
  bool overturned_at[2] = {false, false};
};

// Two amplitudes both engines answer alike, one survived and one overturned: the same runs timed
// in each, where the bisection's median run can be a short (overturned) one in one engine and a
// long one in the other.
constexpr double kFixedAmplitudes[2] = {0.29, 0.35};  // g

// A number of the peer's JSON line; NaN when the line or the key is missing.
double json_number(const io::Json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : std::nan("");
}

// Runs the peer with these arguments and returns its one-line JSON (null on failure).
io::Json run_peer(const std::filesystem::path& exe, const std::string& args) {
  std::FILE* pipe = popen((exe.string() + " " + args + " --json").c_str(), "r");
  if (!pipe) return nullptr;
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  if (pclose(pipe) != 0) return nullptr;
  return io::Json::parse(out, nullptr, /*allow_exceptions=*/false);  // discarded (null) if malformed
}

PeerEngine ode_peer(int repeat) {
  PeerEngine p;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path exe = self.parent_path() / "rigid_ode_peer";
  if (ec || !std::filesystem::exists(exe)) return p;
  const std::string n = " --dt 0.001 --repeat " + std::to_string(repeat);
  const io::Json search = run_peer(exe, "--threshold --tolerance 0.0015" + n);
  p.threshold_g = json_number(search, "threshold_g");
  p.wall_per_run = json_number(search, "wall_s_per_run_median");
  p.dt = json_number(search, "dt_s");
  p.runs = int(json_number(search, "runs"));
  for (int k = 0; k < 2; ++k) {
    const io::Json run = run_peer(exe, "--amplitude " + std::to_string(kFixedAmplitudes[k]) + n);
    p.wall_at[k] = json_number(run, "wall_s_median");
    p.overturned_at[k] = run.is_object() && run.value("overturned", false);
  }
  p.found = std::isfinite(p.threshold_g) && std::isfinite(p.wall_per_run) && std::isfinite(p.wall_at[0]) &&
            std::isfinite(p.wall_at[1]);
  return p;
}

// One contact model on the peer scene: a 15 s run at 0.29 g (median wall) and the threshold.
struct PeerFigures {
  std::string name;
  double wall_at[2] = {0, 0};  ///< median wall of a 15 s run at kFixedAmplitudes (unit: s)
  bool overturned_at[2] = {false, false};
  long steps = 0;  ///< of the run at 0.29 g
  double dt = 0;
  double simulated = 0;
  Threshold threshold{};
  double fine_mesh_threshold = 0;  ///< unit: g
};

// The peer scene's block as 12 triangles (subdivisions 1) or finely meshed (12 n^2 triangles).
scenario::Scene peer_scene(const contact::ContactLaw& law, const dynamics::StepSettings& step, int subdivisions = 1) {
  const double alpha = 0.2, h = 0.5, b = h * std::tan(alpha), depth = 0.5;
  scenario::Scene scene = library::block_on_pedestal(b, h, depth, law);
  if (subdivisions > 1) {
    scene.bodies[1] = library::body_from_soup(
        "block", library::subdivided_box_soup(Vec3(-b, -0.5 * depth, 0), Vec3(b, 0.5 * depth, 2 * h), subdivisions),
        2600, false);
  }
  return scenario::equilibrate(scene, step);
}

PeerFigures peer_figures(const std::string& name, const contact::ContactLaw& law, const dynamics::StepSettings& step,
                         int repeat) {
  const scenario::Scene scene = peer_scene(law, step);
  scenario::RunSettings settings;
  settings.step = step;
  settings.duration = 15.0;
  PeerFigures f;
  f.name = name;
  for (int k = 0; k < 2; ++k) {
    std::vector<double> wall;
    for (int i = 0; i < repeat; ++i) {
      const auto start = Clock::now();
      const scenario::RunOutcome r = scenario::run(scene, one_sine(kFixedAmplitudes[k] * kGravity, 0.5), settings);
      wall.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      f.overturned_at[k] = r.overturned;
      if (k == 0) {
        f.steps = r.steps;
        f.dt = r.dt_s;
        f.simulated = r.simulated_s;
      }
    }
    f.wall_at[k] = median(wall);
  }
  f.threshold = pulse_threshold(scene, settings);
  // the same block meshed with 1,200 triangles (vertices inside its faces)
  f.fine_mesh_threshold = pulse_threshold(peer_scene(law, step, 10), settings).g;
  return f;
}

void bench(int repeat, bool json, const std::string& only) {
  if (!only.empty() && only != "rigid" && only != "penalty")
    throw InputError("", 0, "--contact must be rigid or penalty");
  // (a) geode
  std::vector<double> geode_wall;
  long geode_steps = 0;
  for (int i = 0; i < repeat; ++i) {
    const auto r = run_geode();
    geode_wall.push_back(r.wall);
    geode_steps = r.steps;
  }
  const double geode_median = median(geode_wall);

  // (b) the peer scene with each contact model; the penalty model also at near-rigid stiffness
  // (the limit the 2D model assumes) at the largest stable step
  std::vector<PeerFigures> peers;
  const dynamics::StepSettings preset_step = [] {
    scenario::RunSettings s;
    scenario::apply_accuracy(*scenario::find_accuracy_preset(scenario::kDefaultAccuracy), {}, s);
    return s.step;
  }();
  if (only.empty() || only == "rigid") {
    contact::ContactLaw rigid;
    rigid.method = contact::ContactMethod::rigid;
    peers.push_back(peer_figures("rigid", rigid, preset_step, repeat));
  }
  if (only.empty() || only == "penalty") {
    contact::ContactLaw study;
    study.method = contact::ContactMethod::penalty;
    peers.push_back(peer_figures("penalty", study, preset_step, repeat));
    contact::ContactLaw stiff = study;
    stiff.normal_stiffness = stiff.shear_stiffness = 1e10;
    dynamics::StepSettings stiff_step = preset_step;
    stiff_step.safety = 1.0;
    peers.push_back(peer_figures("penalty K=1e10", stiff, stiff_step, repeat));
  }
  const double alpha = 0.2, h = 0.5, b = h * std::tan(alpha);
  const auto block2d = rocking::RockingBlock::rectangular(b, h);
  const double housner = rocking::min_overturning_amplitude(block2d, rocking::PulseShape::one_sine, 0.5) / kGravity;
  const PeerEngine ode = ode_peer(repeat);

  if (json) {
    io::Json j;
    j["repeat"] = long(repeat);
    j["geode_wall_s_median"] = geode_median;
    j["geode_steps"] = geode_steps;
    j["geode_steps_per_s"] = double(geode_steps) / geode_median;
    j["housner_threshold_g"] = housner;
    if (ode.found) {
      j["ode_threshold_g"] = ode.threshold_g;
      j["ode_threshold_ratio"] = ode.threshold_g / housner;
      j["ode_dt_s"] = ode.dt;
      j["ode_wall_s_per_search_run"] = ode.wall_per_run;
      j["ode_wall_s_median"] = ode.wall_at[0];
      j["ode_wall_s_median_at_0p35g"] = ode.wall_at[1];
    }
    for (const auto& f : peers) {
      std::string key = f.name == "penalty K=1e10" ? "stiff" : f.name;
      j[key + "_wall_s_median"] = f.wall_at[0];
      j[key + "_wall_s_median_at_0p35g"] = f.wall_at[1];
      j[key + "_steps"] = f.steps;
      j[key + "_dt_s"] = f.dt;
      j[key + "_simulated_s"] = f.simulated;
      j[key + "_overturned_at_0p29g"] = f.overturned_at[0];
      j[key + "_overturned_at_0p35g"] = f.overturned_at[1];
      j[key + "_threshold_g"] = f.threshold.g;
      j[key + "_threshold_ratio"] = f.threshold.g / housner;
      j[key + "_wall_s_per_search_run"] = f.threshold.wall_per_run;
      j[key + "_fine_mesh_threshold_g"] = f.fine_mesh_threshold;
    }
    std::printf("%s\n", io::json_line(j).c_str());
    return;
  }
  std::printf("rigid bench (medians of %d runs, one core)\n", repeat);
  std::printf("(a) geode (penalty, the study's test), 50 s at dt 0.000314 s: %.3f s wall, %ld steps, %.3g steps/s\n",
              geode_median, geode_steps, double(geode_steps) / geode_median);
  std::printf("(b) peer scene: 1 m block, alpha 0.2, one-sine T 0.5 s, to 15 s; 2D Housner threshold %.4f g\n",
              housner);
  std::printf("    %-15s %11s %8s %9s | %-23s %-23s %13s\n", "contact", "threshold g", "/Housner", "dt s",
              "15 s run at 0.29 g", "15 s run at 0.35 g", "search run");
  auto verdict = [](bool overturned) { return overturned ? "overturned" : "survived"; };
  for (const auto& f : peers) {
    std::printf("    %-15s %11.4f %8.3f %9.3g | %7.4f s %-13s %7.4f s %-13s %9.4f s\n", f.name.c_str(), f.threshold.g,
                f.threshold.g / housner, f.dt, f.wall_at[0], verdict(f.overturned_at[0]), f.wall_at[1],
                verdict(f.overturned_at[1]), f.threshold.wall_per_run);
  }
  if (ode.found) {
    std::printf("    %-15s %11.4f %8.3f %9.3g | %7.4f s %-13s %7.4f s %-13s %9.4f s\n", "ODE (peer)", ode.threshold_g,
                ode.threshold_g / housner, ode.dt, ode.wall_at[0], verdict(ode.overturned_at[0]), ode.wall_at[1],
                verdict(ode.overturned_at[1]), ode.wall_per_run);
  } else {
    std::printf("    ODE (peer): not built (apt-get install libode-dev, then rebuild: build/bin/rigid_ode_peer)\n");
  }
  std::printf(
      "    walls: medians, whole runs (Rigid ends a run once the block has fallen or rests after the\n"
      "    motion; the ODE driver only once it has fallen); search run: the bisection's runs to 0.5 %%\n");
  for (const auto& f : peers) {
    std::printf(
        "    %s: %ld steps in the 0.29 g run (%.2f s simulated); the block as 1,200 triangles: threshold "
        "%.4f g (%+.1f %% against 12 triangles)\n",
        f.name.c_str(), f.steps, f.simulated, f.fine_mesh_threshold,
        100.0 * (f.fine_mesh_threshold / f.threshold.g - 1.0));
  }
}

}  // namespace

void register_bench_command(CLI::App& app) {
  auto repeat = std::make_shared<int>(5);
  auto json = std::make_shared<bool>(false);
  auto contact = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("bench", "Time the engine on the reference scenes (geode drop, peer rocking scene)");
  cmd->add_option("--repeat", *repeat, "Runs per figure; medians are reported")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("--json", *json, "Print one JSON object");
  cmd->add_option("--contact", *contact, "Only this contact model on the peer scene: rigid or penalty (default: both)");
  cmd->callback([repeat, json, contact] { bench(*repeat, *json, *contact); });
}

}  // namespace rigid::app
