// Energy is never created (physics.md §10): a block released tilted on a fixed base, no ground
// motion, rocks freely; its total energy (kinetic + gravitational + the elastic energy of the
// penalty springs) must never exceed its initial value. Rigid contact, and penalty contact at
// K_N = 1e4, 1e6, 1e8 and 1e10 N/m^1.5, each on the automatic step of the default accuracy preset
// (no dt given). Oracle: conservation of energy; the contacts can only dissipate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rigid/dynamics/world.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/scenario/run_bounds.hpp"

namespace rigid {
namespace {

// A 4 x 4 x 16 cm block (0.67 kg, slenderness atan(1/4) = 0.245 rad): light enough that the
// softest springs, 1e4, carry it (it sinks 3 mm on four corners, 15 % of its half-width).
constexpr double kHalfWidth = 0.02, kHalfHeight = 0.08, kDepth = 0.04;
constexpr double kTilt = 0.15;  // rad: below the slenderness, so it rocks back rather than topples

scenario::Scene tilted_block(const contact::ContactLaw& law) {
  scenario::Scene scene;
  scene.law = law;
  scene.source = "tilted block";
  scene.bodies.push_back(library::box_body("base", Vec3(-0.3, -0.1, -0.2), Vec3(0.3, 0.1, 0), 2600, true));
  dynamics::BodyDef block = library::box_body("block", Vec3(-kHalfWidth, -0.5 * kDepth, 0),
                                              Vec3(kHalfWidth, 0.5 * kDepth, 2 * kHalfHeight), 2600, false);
  // turned about its +x bottom edge, which stays on the base (touching, no overlap)
  const Vec3 pivot(kHalfWidth, 0, 0);
  const Quat turn(Eigen::AngleAxisd(kTilt, Vec3::UnitY()));
  block.position = pivot + turn * (block.position - pivot);
  block.orientation = turn * block.orientation;
  scene.bodies.push_back(block);
  return scene;
}

struct EnergyRecord {
  double dt = 0;
  double released = 0;    ///< initial energy above the block standing upright (unit: J)
  double worst_gain = 0;  ///< largest E(t) - E(0) (unit: J)
  double final_left = 0;  ///< E(end) above upright, as a share of `released`
};

EnergyRecord rock_freely(const scenario::Scene& scene, double duration) {
  dynamics::StepSettings step;
  step.safety = scenario::find_accuracy_preset(scenario::kDefaultAccuracy)->safety;
  dynamics::World world(scene.bodies, scene.law, step);
  const auto energy = [&] { return world.kinetic_energy() + world.potential_energy() + world.elastic_energy(); };
  EnergyRecord r;
  r.dt = world.dt();
  const double upright = world.bodies()[1].shape.mass * kGravity * kHalfHeight;
  const double e0 = energy();
  r.released = e0 - upright;
  const long steps = std::lround(duration / r.dt);
  for (long i = 0; i < steps; ++i) {
    world.step(r.dt, Vec3::Zero(), Vec3::Zero());
    r.worst_gain = std::max(r.worst_gain, energy() - e0);
  }
  r.final_left = (energy() - upright) / r.released;
  return r;
}

// Rigid contact, Housner's plastic impacts: energy is lost at each impact and conserved between
// them up to the Moreau-Jean step's O((p h)^2) error ((p h)^2 = 5e-5 here, p the block's frequency
// parameter), except for where the model holds a resting contact: anywhere within its slop, 1e-5
// of the block's bounding radius r, of touching (physics.md §12), so the block may rest up to that
// much higher than it started. The bound: m g (2e-5 r), the potential energy of twice the slop
// (measured: half of it).
TEST(FreeRockingEnergy, RigidContactNeverGainsEnergy) {
  contact::ContactLaw law;
  law.method = contact::ContactMethod::rigid;
  law.friction = 0.8;
  const scenario::Scene scene = tilted_block(law);
  const EnergyRecord r = rock_freely(scene, 2.0);
  const auto& block = scene.bodies[1].shape;
  const double slop_energy = block.mass * kGravity * 1e-5 * block.bounding_radius;
  std::printf(
      "rigid: dt %.3g s, released %.4g J, worst gain %.3g of it (%.3g of the slop's energy), %.3g left after 2 s\n",
      r.dt, r.released, r.worst_gain / r.released, r.worst_gain / slop_energy, r.final_left);
  EXPECT_LE(r.worst_gain, 2 * slop_energy);
  EXPECT_LT(r.final_left, 0.5);  // the impacts dissipate (r^2 = 0.83 per impact at this slenderness)
}

struct PenaltyCase {
  double stiffness;  // K_N = K_S
  double damping;    // D (s/m)
};

class FreeRockingPenalty : public ::testing::TestWithParam<PenaltyCase> {};

// The automatic step is accepted by the run bounds (no --dt needed) and creates no energy.
// D = 2 (the study's): the hysteretic damping removes energy at every compression, so the total
// never rises (measured: < 1e-12 of the released energy); 1e-6 leaves room for rounding only.
// D = 0 (lossless springs, the hardest case): velocity Verlet is symplectic, so its energy error
// is bounded, O((omega h)^2) of the energy in the springs, and does not accumulate (measured: at
// most 2.2e-4 of the released energy, at K_N = 1e4). 1e-3 allows four times that; five times the
// automatic step already gains 3e-3 to 7e-3 (K_N = 1e6, 1e4), and an unstable step without bound.
TEST_P(FreeRockingPenalty, AutomaticStepNeverGainsEnergy) {
  const PenaltyCase c = GetParam();
  contact::ContactLaw law;
  law.method = contact::ContactMethod::penalty;
  law.normal_stiffness = law.shear_stiffness = c.stiffness;
  law.damping = c.damping;
  law.friction = 0.8;
  const scenario::Scene scene = tilted_block(law);
  dynamics::StepSettings step;
  step.safety = scenario::find_accuracy_preset(scenario::kDefaultAccuracy)->safety;
  EXPECT_NO_THROW(scenario::check_run_bounds(scene, step, 1.0));
  const EnergyRecord r = rock_freely(scene, 1.0);
  std::printf("K_N %.0e, D %g: dt %.3g s, released %.4g J, worst gain %.3g of it, %.3g left after 1 s\n", c.stiffness,
              c.damping, r.dt, r.released, r.worst_gain / r.released, r.final_left);
  EXPECT_LE(r.worst_gain, (c.damping > 0 ? 1e-6 : 1e-3) * r.released);
  EXPECT_LE(r.final_left, 1.0 + (c.damping > 0 ? 1e-6 : 1e-3));
}

INSTANTIATE_TEST_SUITE_P(Stiffnesses, FreeRockingPenalty,
                         ::testing::Values(PenaltyCase{1e4, 2}, PenaltyCase{1e6, 2}, PenaltyCase{1e8, 2},
                                           PenaltyCase{1e10, 2}, PenaltyCase{1e4, 0}, PenaltyCase{1e6, 0},
                                           PenaltyCase{1e8, 0}, PenaltyCase{1e10, 0}),
                         [](const ::testing::TestParamInfo<PenaltyCase>& info) {
                           return "K1e" + std::to_string(int(std::lround(std::log10(info.param.stiffness)))) + "_D" +
                                  std::to_string(int(info.param.damping));
                         });

}  // namespace
}  // namespace rigid
