// The penalty model's automatic step across the stiffness range (physics.md §10): for three
// blocks and K_N = K_S from 1e4 to 1e10 N/m^1.5 at the study's damping D = 2, the step the default
// accuracy preset takes, which limit sets it (the damped critical step or the rocking cap), whether
// the run bounds accept the scene, and what one second of free rocking from a 0.1 rad tilt costs
// (steps, wall time on this machine, one core) and whether it gained energy.
//
//   cmake --build build --target penalty_step_bench && build/tests/penalty_step_bench
//
// A benchmark, not a test: it prints a table.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/dynamics/world.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/scenario/run_bounds.hpp"

namespace {

using rigid::Quat;
using rigid::Vec3;

struct Block {
  std::string name;
  double b, h, depth;  // half-width, half-height, depth (m)
};

rigid::scenario::Scene tilted(const Block& k, const rigid::contact::ContactLaw& law) {
  rigid::scenario::Scene scene;
  scene.law = law;
  scene.source = k.name;
  scene.bodies.push_back(rigid::library::box_body("base", Vec3(-3 * k.b - 0.1, -k.depth, -0.5),
                                                  Vec3(3 * k.b + 0.1, k.depth, 0), 2600, true));
  auto block =
      rigid::library::box_body("block", Vec3(-k.b, -0.5 * k.depth, 0), Vec3(k.b, 0.5 * k.depth, 2 * k.h), 2600, false);
  const Vec3 pivot(k.b, 0, 0);
  const Quat turn(Eigen::AngleAxisd(0.1, Vec3::UnitY()));
  block.position = pivot + turn * (block.position - pivot);
  block.orientation = turn * block.orientation;
  scene.bodies.push_back(block);
  return scene;
}

}  // namespace

int main() {
  using namespace rigid;
  const std::vector<Block> blocks = {{"4x4x16 cm, 0.67 kg", 0.02, 0.08, 0.04},
                                     {"peer 0.2x0.5x1 m, 264 kg", 0.5 * std::tan(0.2), 0.5, 0.5},
                                     {"0.6x0.8x1.2 m, 1.5 t", 0.3, 0.6, 0.8}};
  const double safety = scenario::find_accuracy_preset(scenario::kDefaultAccuracy)->safety;
  std::printf("automatic step at safety %.2g (the default preset), D = 2 s/m, 1 s of free rocking\n", safety);
  std::printf("%-26s %8s %11s %-9s %10s %9s %9s %11s\n", "block", "K_N", "step (s)", "set by", "steps/s", "wall (s)",
              "accepted", "energy gain");
  for (const Block& block : blocks) {
    for (double k = 1e4; k <= 1.01e10; k *= std::sqrt(10.0)) {
      contact::ContactLaw law;
      law.method = contact::ContactMethod::penalty;
      law.normal_stiffness = law.shear_stiffness = k;
      const scenario::Scene scene = tilted(block, law);
      dynamics::StepSettings step;
      step.safety = safety;
      const double critical = dynamics::critical_time_step(scene.bodies, law);
      const double rocking = dynamics::rigid_time_step(scene.bodies, 1.0);
      std::string accepted = "yes";
      try {
        scenario::check_run_bounds(scene, step, 1.0);
      } catch (const InputError&) {
        accepted = "no (sinks)";
      }
      double wall = 0, gain = 0;
      long steps = 0;
      if (accepted == "yes") {
        const auto start = std::chrono::steady_clock::now();
        dynamics::World world(scene.bodies, law, step);
        const double e0 = world.kinetic_energy() + world.potential_energy() + world.elastic_energy();
        steps = std::lround(1.0 / world.dt());
        for (long i = 0; i < steps; ++i) {
          world.step(world.dt(), Vec3::Zero(), Vec3::Zero());
          gain = std::max(gain, world.kinetic_energy() + world.potential_energy() + world.elastic_energy() - e0);
        }
        wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
      std::printf("%-26s %8.1e %11.3e %-9s %10ld %9.3f %9s %11.2e\n", block.name.c_str(), k,
                  dynamics::time_step(scene.bodies, law, step), critical < rocking ? "critical" : "rocking", steps,
                  wall, accepted.c_str(), gain);
    }
  }
  return 0;
}
