// The study's accuracy test (physics.md §11): a faceted near-sphere dropped on a plane with no
// friction and no damping bounces on and on; a symmetric impact has no torque, so any rotation
// is numerical. The original code rotated after nine bounces, 3DEC after three.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/library/builders.hpp"

namespace rigid {
namespace {

TEST(Geode, BouncesAtLeastNineTimesBeforeMarkedRotation) {
  contact::ContactLaw law;
  law.method = contact::ContactMethod::penalty;  // the study's test of its own (penalty) model
  law.friction = 0;
  law.damping = 0;
  auto geode = library::body_from_soup("geode", library::geodesic_sphere(0.15, 2), 2600, false);
  // put one vertex straight below the centroid, 0.5 m above the plane
  const Vec3 lowest_body = geode.shape.vertices[0];
  const Quat down = Quat::FromTwoVectors(lowest_body, -Vec3::UnitZ());
  geode.orientation = down;
  geode.position = Vec3(0, 0, 0.5 + lowest_body.norm());
  auto plane = library::box_body("plane", Vec3(-1, -1, -0.2), Vec3(1, 1, 0), 2600, true);
  dynamics::StepSettings settings;
  settings.dt = 0.000314;  // the study's step
  dynamics::World world({plane, geode}, law, settings);
  int bounces = 0;
  bool touching = false;
  int bounces_before_rotation = -1;
  const double e0 = world.kinetic_energy() + world.potential_energy();
  for (double t = 0; t < 50.0; t += settings.dt) {
    world.step(settings.dt, Vec3::Zero(), Vec3::Zero());
    const bool now = world.pairs()[0].overlap > 0;
    if (touching && !now) ++bounces;
    touching = now;
    // marked rotation: the body turned by more than one degree
    const double turn = down.angularDistance(world.states()[1].orientation);
    if (turn > kPi / 180 && bounces_before_rotation < 0) bounces_before_rotation = bounces;
  }
  if (bounces_before_rotation < 0) bounces_before_rotation = bounces;
  std::printf("geode: %d bounces in 50 s, %d before marked rotation\n", bounces, bounces_before_rotation);
  EXPECT_GE(bounces_before_rotation, 9);
  // no damping, no friction: energy is conserved (contact springs are elastic)
  const double e1 = world.kinetic_energy() + world.potential_energy() + world.elastic_energy();
  EXPECT_NEAR(e1 / e0, 1.0, 0.01);
}

}  // namespace
}  // namespace rigid
