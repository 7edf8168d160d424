// The rigid model's contact solver on configurations whose impulses statics and Coulomb's law give
// by hand: a cube on a plane (one step of weight carried), on two symmetric supports, on an
// incline below and above its friction angle; and a solve cut off by its sweep cap, which must
// say so (in the solver's result and in the World's count of such steps).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rigid/dynamics/contact_solver.hpp"
#include "rigid/dynamics/world.hpp"
#include "rigid/library/builders.hpp"

namespace rigid {
namespace {

using dynamics::ContactRow;
using dynamics::FrictionPatch;
using dynamics::SolverBody;

constexpr double kMass = 100;  // unit: kg
constexpr double kHalf = 0.5;  // half the cube's side (unit: m)
constexpr double kDt = 1e-3;   // unit: s
constexpr double kG = 9.81;    // unit: m/s^2

// The ground (immovable) and a cube of side 2 kHalf whose centre is kHalf above the ground's
// surface, moving at `velocity`: what gravity gave it over one step when it started at rest.
std::vector<SolverBody> ground_and_cube(const Vec3& velocity) {
  std::vector<SolverBody> bodies(2);
  bodies[1].velocity = velocity;
  bodies[1].inverse_mass = 1 / kMass;
  // a cube's moment of inertia about any centroidal axis: m (2 h)^2 / 6
  const double inertia = kMass * (2 * kHalf) * (2 * kHalf) / 6;
  bodies[1].inverse_inertia = Mat3::Identity() / inertia;
  return bodies;
}

// A contact point on the ground's surface below the cube, at (x, y) from the cube's axis.
ContactRow support(double x, double y) {
  ContactRow row;
  row.a = 0;
  row.b = 1;
  row.ra = Vec3(x, y, 0);
  row.rb = Vec3(x, y, -kHalf);
  row.normal = Vec3(0, 0, 1);
  return row;
}

std::vector<ContactRow> four_corners() {
  return {support(kHalf, kHalf), support(-kHalf, kHalf), support(-kHalf, -kHalf), support(kHalf, -kHalf)};
}

// The friction of the cube's bottom face: centred under the cube, twisting resisted at the
// corners' mean distance from the centre.
FrictionPatch bottom_face(double friction) {
  FrictionPatch patch;
  patch.a = 0;
  patch.b = 1;
  patch.first_row = 0;
  patch.row_count = 4;
  patch.ra = Vec3::Zero();
  patch.rb = Vec3(0, 0, -kHalf);
  patch.normal = Vec3(0, 0, 1);
  patch.friction = friction;
  patch.radius = kHalf * std::sqrt(2.0);
  dynamics::set_tangents(patch);
  return patch;
}

// Tolerances far below the impulses checked: the solve is then exact to ~1e-9 of them.
dynamics::SolverSettings tight() {
  dynamics::SolverSettings s;
  s.velocity_tolerance = 1e-13;
  s.angular_tolerance = 1e-13;
  s.max_iterations = 100000;
  return s;
}

dynamics::SolverResult solve(std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows,
                             std::vector<FrictionPatch>& patches, const dynamics::SolverSettings& settings) {
  std::vector<SolverBody> scratch;
  dynamics::prepare(bodies, rows, patches);
  dynamics::warm_start(bodies, rows, patches);
  return dynamics::solve_velocities(bodies, rows, patches, settings, scratch);
}

double total_normal(const std::vector<ContactRow>& rows) {
  double sum = 0;
  for (const auto& r : rows) sum += r.normal_impulse;
  return sum;
}

TEST(ContactSolver, CubeOnAPlaneCarriesOneStepOfItsWeight) {
  auto bodies = ground_and_cube(Vec3(0, 0, -kG * kDt));
  auto rows = four_corners();
  // the solver sweeps rows patch by patch: a frictionless patch holds them
  std::vector<FrictionPatch> patches = {bottom_face(0.0)};
  const auto result = solve(bodies, rows, patches, tight());
  ASSERT_TRUE(result.converged);
  // brought to rest: the impulse that cancels one step of gravity, m g dt, in total
  const double weight = kMass * kG * kDt;
  EXPECT_NEAR(total_normal(rows), weight, 1e-9 * weight);
  // statics: the corners' impulses have no moment about the centre (their split among four
  // corners is indeterminate, their first moments are not)
  double moment_x = 0, moment_y = 0;
  for (const auto& r : rows) {
    EXPECT_GE(r.normal_impulse, 0);
    moment_x += r.normal_impulse * r.rb.y();
    moment_y += r.normal_impulse * r.rb.x();
  }
  EXPECT_NEAR(moment_x, 0, 1e-9 * weight * kHalf);
  EXPECT_NEAR(moment_y, 0, 1e-9 * weight * kHalf);
  EXPECT_LT(bodies[1].velocity.norm(), 1e-10);
  EXPECT_LT(bodies[1].angular_velocity.norm(), 1e-10);
}

TEST(ContactSolver, TwoSymmetricSupportsShareTheWeightEqually) {
  // two supports at equal distances either side of the centre of mass: statically determinate,
  // each carries half the weight
  auto bodies = ground_and_cube(Vec3(0, 0, -kG * kDt));
  std::vector<ContactRow> rows = {support(kHalf, 0), support(-kHalf, 0)};
  std::vector<FrictionPatch> patches = {bottom_face(0.0)};
  patches[0].row_count = 2;
  patches[0].radius = kHalf;
  const auto result = solve(bodies, rows, patches, tight());
  ASSERT_TRUE(result.converged);
  const double half_weight = 0.5 * kMass * kG * kDt;
  EXPECT_NEAR(rows[0].normal_impulse, half_weight, 1e-9 * half_weight);
  EXPECT_NEAR(rows[1].normal_impulse, half_weight, 1e-9 * half_weight);
}

// A cube on an incline at angle theta, in the incline's frame: gravity has a component
// g sin(theta) down the slope (+x here) and g cos(theta) into it.
struct Incline {
  double theta, friction;
  std::vector<SolverBody> bodies;
  std::vector<ContactRow> rows = four_corners();
  std::vector<FrictionPatch> patches;
  dynamics::SolverResult result;

  Incline(double theta_deg, double mu) : theta(theta_deg * kPi / 180), friction(mu) {
    bodies = ground_and_cube(kG * kDt * Vec3(std::sin(theta), 0, -std::cos(theta)));
    patches = {bottom_face(mu)};
    result = solve(bodies, rows, patches, tight());
  }
  // the friction impulse on the cube, in the incline's frame
  Vec3 friction_impulse() const {
    const auto& p = patches[0];
    return p.impulse.x() * p.tangent1 + p.impulse.y() * p.tangent2;
  }
};

TEST(ContactSolver, CubeOnAnInclineBelowTheFrictionAngleSticks) {
  const Incline incline(20, 0.6);  // tan 20 deg = 0.36 < 0.6
  ASSERT_TRUE(incline.result.converged);
  const double weight = kMass * kG * kDt;
  // statics: friction holds the whole down-slope pull, m g sin(theta) dt, and the normal
  // impulses the rest, m g cos(theta) dt
  const Vec3 f = incline.friction_impulse();
  EXPECT_NEAR(f.x(), -weight * std::sin(incline.theta), 1e-9 * weight);
  EXPECT_NEAR(f.y(), 0, 1e-9 * weight);
  EXPECT_NEAR(total_normal(incline.rows), weight * std::cos(incline.theta), 1e-9 * weight);
  EXPECT_NEAR(incline.patches[0].impulse.z(), 0, 1e-9 * weight * kHalf);  // nothing twists it
  EXPECT_LT(incline.bodies[1].velocity.norm(), 1e-10);
  EXPECT_LT(incline.bodies[1].angular_velocity.norm(), 1e-10);
}

TEST(ContactSolver, CubeOnAnInclineAboveTheFrictionAngleSlides) {
  const Incline incline(40, 0.5);  // tan 40 deg = 0.84 > 0.5; mu < 1: it slides without tipping
  ASSERT_TRUE(incline.result.converged);
  const double weight = kMass * kG * kDt;
  const double normal = weight * std::cos(incline.theta);
  // Coulomb: sliding friction mu N against the motion, N = m g cos(theta) dt; the cube keeps
  // g (sin(theta) - mu cos(theta)) dt of down-slope velocity and does not turn
  EXPECT_NEAR(total_normal(incline.rows), normal, 1e-9 * weight);
  const Vec3 f = incline.friction_impulse();
  EXPECT_NEAR(f.x(), -incline.friction * normal, 1e-9 * weight);
  EXPECT_NEAR(f.y(), 0, 1e-9 * weight);
  const double slide = kG * kDt * (std::sin(incline.theta) - incline.friction * std::cos(incline.theta));
  EXPECT_NEAR(incline.bodies[1].velocity.x(), slide, 1e-9 * kG * kDt);
  EXPECT_NEAR(incline.bodies[1].velocity.z(), 0, 1e-9 * kG * kDt);
  EXPECT_LT(incline.bodies[1].angular_velocity.norm(), 1e-9);
}

TEST(ContactSolver, ASolveCutOffByItsSweepCapSaysItDidNotConverge) {
  // stopping the falling cube changes its velocity by g dt in the first sweep, far above the
  // tolerance: one sweep cannot also be the sweep that changes nothing
  auto bodies = ground_and_cube(Vec3(0, 0, -kG * kDt));
  auto rows = four_corners();
  std::vector<FrictionPatch> patches = {bottom_face(0.6)};
  dynamics::SolverSettings capped = tight();
  capped.max_iterations = 1;
  const auto result = solve(bodies, rows, patches, capped);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 1);
}

// A 1 m cube standing on a fixed slab, rigid contacts.
dynamics::World cube_on_slab(const dynamics::StepSettings& settings, contact::ContactMethod model) {
  contact::ContactLaw law;
  law.method = model;
  std::vector<dynamics::BodyDef> bodies = {
      library::box_body("slab", Vec3(-2, -2, -1), Vec3(2, 2, 0), 2600, true),
      library::box_body("cube", Vec3(-0.5, -0.5, 0), Vec3(0.5, 0.5, 1), 2600, false)};
  return dynamics::World(std::move(bodies), law, settings);
}

TEST(ContactSolver, TheWorldCountsTheStepsWhoseSolveHitItsCap) {
  dynamics::StepSettings capped;
  capped.solver_max_sweeps = 1;
  dynamics::World world = cube_on_slab(capped, contact::ContactMethod::rigid);
  // the first step starts without a warm start: its one sweep must stop the cube (as above)
  world.step(world.dt(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(world.stats().unconverged_steps, 1);
  EXPECT_EQ(world.stats().max_solver_sweeps, 1);

  // with the default cap, a cube at rest converges every step
  dynamics::World resting = cube_on_slab(dynamics::StepSettings{}, contact::ContactMethod::rigid);
  for (int k = 0; k < 200; ++k) resting.step(resting.dt(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(resting.stats().unconverged_steps, 0);
  EXPECT_GE(resting.stats().max_solver_sweeps, 2);  // the first step's solve needs more than one
  EXPECT_LT(resting.stats().max_solver_sweeps, dynamics::StepSettings{}.solver_max_sweeps);
  EXPECT_NEAR(resting.states()[1].position.z(), 0.5, 1e-6) << "the cube should stand still";

  // penalty contacts have no such solve
  dynamics::World springs = cube_on_slab(dynamics::StepSettings{}, contact::ContactMethod::penalty);
  for (int k = 0; k < 10; ++k) springs.step(springs.dt(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(springs.stats().unconverged_steps, 0);
  EXPECT_EQ(springs.stats().max_solver_sweeps, 0);
}

}  // namespace
}  // namespace rigid
