// `rigid bench`: speed of the engine on the reference scenes of the issue tracker, as medians of
// repeated runs on this machine (one core).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "commands.hpp"
#include "json.hpp"
#include "rigid/rocking/housner.hpp"
#include "rigid/scenario/builders.hpp"

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
  law.friction = 0;
  law.damping = 0;
  auto geode = scenario::body_from_soup("geode", scenario::geodesic_sphere(0.15, 2), 2600, false);
  const Vec3 lowest = geode.shape.vertices[0];
  geode.orientation = Quat::FromTwoVectors(lowest, -Vec3::UnitZ());
  geode.position = Vec3(0, 0, 0.5 + lowest.norm());
  auto plane = scenario::box_body("plane", Vec3(-1, -1, -0.2), Vec3(1, 1, 0), 2600, true);
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
scenario::GroundDrive one_sine(double amplitude, double period) {
  scenario::GroundDrive drive;
  drive.dt = 1e-3;
  const long n = std::lround(period / drive.dt);
  for (long i = 0; i <= n; ++i) {
    const double t = double(i) * drive.dt;
    drive.velocity.emplace_back(amplitude * period / (2 * kPi) * (1 - std::cos(2 * kPi * t / period)), 0, 0);
  }
  return drive;
}

struct Threshold {
  double g;
  double wall_per_run;
  int runs;
};

// Overturning amplitude of the one-sine pulse by bisection between 0.2 g and 0.5 g.
Threshold pulse_threshold(const scenario::Scene& scene, const scenario::RunSettings& settings) {
  double lo = 0.2, hi = 0.5;  // g
  int runs = 0;
  const auto start = Clock::now();
  while (hi - lo > 0.0025) {
    const double mid = 0.5 * (lo + hi);
    (scenario::run(scene, one_sine(mid * kGravity, 0.5), settings).overturned ? hi : lo) = mid;
    ++runs;
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  return {0.5 * (lo + hi), wall / runs, runs};
}

void bench(int repeat, bool json) {
  // (a) geode
  std::vector<double> geode_wall;
  long geode_steps = 0;
  for (int i = 0; i < repeat; ++i) {
    const auto r = run_geode();
    geode_wall.push_back(r.wall);
    geode_steps = r.steps;
  }
  const double geode_median = median(geode_wall);

  // (b) peer scene at 0.29 g, and its overturning threshold by bisection
  const double alpha = 0.2, h = 0.5, b = h * std::tan(alpha);
  const scenario::Scene scene =
      scenario::equilibrate(scenario::block_on_pedestal(b, h, 0.5), dynamics::StepSettings{});
  scenario::RunSettings settings;
  settings.duration = 15.0;
  std::vector<double> peer_wall;
  scenario::RunOutcome peer;
  for (int i = 0; i < repeat; ++i) {
    const auto start = Clock::now();
    peer = scenario::run(scene, one_sine(0.29 * kGravity, 0.5), settings);
    peer_wall.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  const Threshold study = pulse_threshold(scene, settings);
  // the same with near-rigid contacts, the limit the 2D model assumes, at the largest stable step
  contact::ContactLaw stiff;
  stiff.normal_stiffness = stiff.shear_stiffness = 1e10;
  dynamics::StepSettings stiff_step;
  stiff_step.safety = 1.0;
  const scenario::Scene stiff_scene =
      scenario::equilibrate(scenario::block_on_pedestal(b, h, 0.5, stiff), stiff_step);
  scenario::RunSettings stiff_settings = settings;
  stiff_settings.step = stiff_step;
  const Threshold rigid_limit = pulse_threshold(stiff_scene, stiff_settings);
  const auto block2d = rocking::RockingBlock::rectangular(b, h);
  const double housner =
      rocking::min_overturning_amplitude(block2d, rocking::PulseShape::one_sine, 0.5) / kGravity;

  if (json) {
    JsonObject j;
    j.add("repeat", long(repeat))
        .add("geode_wall_s_median", geode_median)
        .add("geode_steps", geode_steps)
        .add("geode_steps_per_s", double(geode_steps) / geode_median)
        .add("peer_wall_s_median", median(peer_wall))
        .add("peer_steps", peer.steps)
        .add("peer_dt_s", peer.dt)
        .add("peer_simulated_s", peer.simulated)
        .add("peer_overturned_at_0p29g", peer.overturned)
        .add("peer_threshold_g", study.g)
        .add("peer_wall_s_per_search_run", study.wall_per_run)
        .add("stiff_threshold_g", rigid_limit.g)
        .add("stiff_wall_s_per_search_run", rigid_limit.wall_per_run)
        .add("housner_threshold_g", housner);
    std::printf("%s\n", j.str().c_str());
    return;
  }
  std::printf("rigid bench (medians of %d runs, one core)\n", repeat);
  std::printf("(a) geode, 50 s at dt 0.000314 s: %.3f s wall, %ld steps, %.3g steps/s\n", geode_median,
              geode_steps, double(geode_steps) / geode_median);
  std::printf("(b) peer scene, one-sine 0.29 g, T 0.5 s, to 15 s: %.4f s wall per run, %ld steps of %.3g s "
              "(%.2f s simulated, %s)\n",
              median(peer_wall), peer.steps, peer.dt, peer.simulated,
              peer.overturned ? "overturned" : "survived");
  std::printf("    overturning threshold by bisection: %.4f g (2D Housner model: %.4f g); %d runs, %.4f s per run\n",
              study.g, housner, study.runs, study.wall_per_run);
  std::printf("    with near-rigid contacts (K_N = K_S = 1e10, safety 1.0): %.4f g; %.4f s per run\n",
              rigid_limit.g, rigid_limit.wall_per_run);
}

}  // namespace

void register_bench_command(CLI::App& app) {
  auto repeat = std::make_shared<int>(5);
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("bench", "Time the engine on the reference scenes (geode drop, peer rocking scene)");
  cmd->add_option("--repeat", *repeat, "Runs per figure; medians are reported")->capture_default_str()->check(CLI::Range(1, 1000));
  cmd->add_flag("--json", *json, "Print one JSON object");
  cmd->callback([repeat, json] { bench(*repeat, *json); });
}

}  // namespace rigid::app
