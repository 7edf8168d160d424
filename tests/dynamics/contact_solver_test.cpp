// The rigid model's contact solver on configurations whose impulses statics and Coulomb's law give
// by hand: a cube on a plane (one step of weight carried), on two symmetric supports, on an
// incline below and above its friction angle; a slender block pushed sideways below and above its
// uplift acceleration (a single-pivot rigid-body solve by hand); random face contacts against a
// second method (a plain Gauss-Seidel on the dense problem, run to convergence); and a solve cut
// off by its sweep cap, which must say so (in the solver's result and in the World's count).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>

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
  // the cube's face as two patches of two corners each: the first patch, solved alone, stops the
  // falling cube (a change of g dt), which the second then changes again, far above the
  // tolerance: one sweep cannot also be the sweep that changes nothing
  auto bodies = ground_and_cube(Vec3(0, 0, -kG * kDt));
  auto rows = four_corners();
  std::vector<FrictionPatch> patches = {bottom_face(0.6), bottom_face(0.6)};
  patches[0].row_count = patches[1].row_count = 2;
  patches[1].first_row = 2;
  dynamics::SolverSettings capped = tight();
  capped.max_iterations = 1;
  const auto result = solve(bodies, rows, patches, capped);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 1);
}

// A block of half-width b (x), half-depth d (y) and half-height h on the ground, its four bottom
// corners as rows and its bottom face as the patch, and the free velocity `velocity`.
struct Block {
  double b, d, h, mass = kMass;
  std::vector<SolverBody> bodies;
  std::vector<ContactRow> rows;
  std::vector<FrictionPatch> patches;
  Mat3 inertia;

  Block(double half_width, double half_depth, double half_height, const Vec3& velocity, double friction)
      : b(half_width), d(half_depth), h(half_height) {
    bodies.resize(2);
    bodies[1].velocity = velocity;
    bodies[1].inverse_mass = 1 / mass;
    inertia = Vec3(mass * (d * d + h * h) / 3, mass * (b * b + h * h) / 3, mass * (b * b + d * d) / 3).asDiagonal();
    bodies[1].inverse_inertia = inertia.inverse();
    for (const auto& [x, y] : {std::pair{b, d}, std::pair{-b, d}, std::pair{-b, -d}, std::pair{b, -d}}) {
      ContactRow row;
      row.a = 0;
      row.b = 1;
      row.ra = Vec3(x, y, 0);
      row.rb = Vec3(x, y, -h);
      rows.push_back(row);
    }
    FrictionPatch patch;
    patch.a = 0;
    patch.b = 1;
    patch.row_count = 4;
    patch.rb = Vec3(0, 0, -h);
    patch.friction = friction;
    patch.radius = std::hypot(b, d);
    dynamics::set_tangents(patch);
    patches = {patch};
  }
  dynamics::SolverResult solve(const dynamics::SolverSettings& settings) {
    return rigid::solve(bodies, rows, patches, settings);
  }
  Vec3 friction_impulse() const {
    const auto& p = patches[0];
    return p.impulse.x() * p.tangent1 + p.impulse.y() * p.tangent2;
  }
};

// The default tolerance of a 1 ms step: 1e-7 of the velocity gravity adds in it.
dynamics::SolverSettings default_tolerance() {
  dynamics::SolverSettings s;
  s.velocity_tolerance = 1e-7 * kG * kDt;
  s.angular_tolerance = s.velocity_tolerance / 0.5;
  return s;
}

TEST(ContactSolver, ASlenderBlockOnItsFaceIsSolvedInOneSweep) {
  // alpha = 0.05: Gauss-Seidel over the corners converges at ~1 - 1/(h/b)^2 per sweep here, and
  // the patch's exact solve ends it at once (the second sweep only confirms it)
  const double b = 0.05, h = 1.0;
  Block block(b, 0.25, h, Vec3(0, 0, -kG * kDt), 0.6);
  const auto result = block.solve(default_tolerance());
  ASSERT_TRUE(result.converged);
  EXPECT_LE(result.iterations, 2);
  const double weight = kMass * kG * kDt;
  EXPECT_NEAR(total_normal(block.rows), weight, 1e-9 * weight);
  // centre of pressure under the centroid: no moment of the normal impulses about it
  double moment_x = 0, moment_y = 0;
  for (const auto& r : block.rows) {
    EXPECT_GE(r.normal_impulse, 0);
    moment_x += r.normal_impulse * r.rb.y();
    moment_y += r.normal_impulse * r.rb.x();
  }
  EXPECT_NEAR(moment_x, 0, 1e-9 * weight * b);
  EXPECT_NEAR(moment_y, 0, 1e-9 * weight * b);
  EXPECT_LT(block.bodies[1].velocity.norm(), 1e-9 * kG * kDt);
}

// The block's free velocity when the ground accelerates at `accel_g` along +x for one step: in the
// ground's frame, -accel dt along x and -g dt along z.
Vec3 pushed(double accel_g) { return kG * kDt * Vec3(-accel_g, 0, -1); }

TEST(ContactSolver, ASlenderBlockBelowItsUpliftAccelerationStaysPut) {
  // below a = g b / h the block sticks and stands: friction m a dt, weight m g dt, and the centre
  // of pressure moves toward the leading (-x) edge by h a / g (moments about the centroid)
  const double b = 0.05, h = 1.0, accel_g = 0.8 * b / h;
  Block block(b, 0.25, h, pushed(accel_g), 0.6);
  const auto result = block.solve(default_tolerance());
  ASSERT_TRUE(result.converged);
  EXPECT_LE(result.iterations, 2);
  const double weight = kMass * kG * kDt;
  EXPECT_NEAR(total_normal(block.rows), weight, 1e-9 * weight);
  EXPECT_NEAR(block.friction_impulse().x(), accel_g * weight, 1e-9 * weight);
  double moment = 0;
  for (const auto& r : block.rows) moment += r.normal_impulse * r.rb.x();
  EXPECT_NEAR(moment / weight, -h * accel_g, 1e-9 * b);
  EXPECT_LT(block.bodies[1].velocity.norm(), 1e-9 * kG * kDt);
  EXPECT_LT(block.bodies[1].angular_velocity.norm(), 1e-9 * kG * kDt / h);
}

TEST(ContactSolver, ASlenderBlockAboveItsUpliftAccelerationPivotsOnItsLeadingEdge) {
  // above a = g b / h it lifts off its trailing edge: the whole impulse P at the leading edge
  // r = (-b, 0, -h), which then neither sinks nor slides. By hand: v + P / m + (I^-1 (r x P)) x r = 0,
  // one 3 x 3 solve, with friction inside mu P_z
  const double b = 0.05, h = 1.0, accel_g = 2.0 * b / h;
  Block block(b, 0.25, h, pushed(accel_g), 0.6);
  const Vec3 free = block.bodies[1].velocity;
  const auto result = block.solve(default_tolerance());
  ASSERT_TRUE(result.converged);
  EXPECT_LE(result.iterations, 3);
  const Vec3 r(-b, 0, -h);
  Mat3 cross;
  cross << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;  // [r]x: [r]x P = r x P
  const Mat3 k = Mat3::Identity() / block.mass - cross * block.inertia.inverse() * cross;
  const Vec3 p = k.fullPivLu().solve(-free);
  ASSERT_GT(p.z(), 0);
  ASSERT_LT(std::abs(p.x()), 0.6 * p.z());
  EXPECT_NEAR(total_normal(block.rows), p.z(), 1e-8 * p.z());
  EXPECT_NEAR(block.friction_impulse().x(), p.x(), 1e-8 * p.z());
  for (const auto& row : block.rows) {
    if (row.rb.x() > 0) {
      EXPECT_EQ(row.normal_impulse, 0) << "the trailing edge has lifted";
    }
  }
  const Vec3 spin = block.inertia.inverse() * r.cross(p);
  EXPECT_NEAR(block.bodies[1].angular_velocity.y(), spin.y(), 1e-8 * std::abs(spin.y()));
  EXPECT_LT(spin.y(), 0) << "tipping toward -x";
}

// The second method: the patch as a dense problem (W = J M^-1 J^T over four normal rows and three
// friction rows, built here from the geometry) solved by plain projected Gauss-Seidel, one row at
// a time, for as many sweeps as it takes. Returns the block's final velocity.
struct DenseResult {
  Vec3 velocity, angular_velocity;
  double normal = 0;
  Eigen::Vector3d friction;
};
DenseResult dense_gauss_seidel(const Block& block, const Vec3& free, const Vec3& free_spin) {
  const auto& p = block.patches[0];
  const Mat3 inverse_inertia = block.inertia.inverse();
  // rows' Jacobians on the block (the ground does not move): linear and angular parts
  Eigen::Matrix<double, 7, 6> j = Eigen::Matrix<double, 7, 6>::Zero();
  for (int i = 0; i < 4; ++i) {
    j.block<1, 3>(i, 0) = Vec3::UnitZ().transpose();
    j.block<1, 3>(i, 3) = block.rows[i].rb.cross(Vec3::UnitZ()).transpose();
  }
  j.block<1, 3>(4, 0) = p.tangent1.transpose();
  j.block<1, 3>(4, 3) = p.rb.cross(p.tangent1).transpose();
  j.block<1, 3>(5, 0) = p.tangent2.transpose();
  j.block<1, 3>(5, 3) = p.rb.cross(p.tangent2).transpose();
  j.block<1, 3>(6, 3) = Vec3::UnitZ().transpose();
  Eigen::Matrix<double, 6, 6> minv = Eigen::Matrix<double, 6, 6>::Zero();
  minv.topLeftCorner<3, 3>() = Mat3::Identity() / block.mass;
  minv.bottomRightCorner<3, 3>() = inverse_inertia;
  const Eigen::Matrix<double, 7, 7> w = j * minv * j.transpose();
  Eigen::Matrix<double, 6, 1> v0;
  v0 << free, free_spin;
  const Eigen::Matrix<double, 7, 1> c = j * v0;
  Eigen::Matrix<double, 7, 1> x = Eigen::Matrix<double, 7, 1>::Zero();
  const Eigen::Matrix3d ktt_inverse = w.bottomRightCorner<3, 3>().inverse();
  for (int sweep = 0; sweep < 2000000; ++sweep) {
    const Eigen::Matrix<double, 7, 1> before = x;
    for (int i = 0; i < 4; ++i) x(i) = std::max(0.0, x(i) - (w.row(i) * x + c(i)) / w(i, i));
    Eigen::Vector3d t = x.tail<3>() - ktt_inverse * (w.bottomRows<3>() * x + c.tail<3>());
    const double limit = p.friction * x.head<4>().sum();
    const double size = std::hypot(t.x(), t.y(), t.z() / p.radius);
    if (size > limit) t *= limit / size;
    x.tail<3>() = t;
    if ((x - before).cwiseAbs().maxCoeff() < 1e-16 * block.mass * kG * kDt) break;
  }
  const Eigen::Matrix<double, 6, 1> v = v0 + minv * j.transpose() * x;
  return {v.head<3>(), v.tail<3>(), x.head<4>().sum(), x.tail<3>()};
}

TEST(ContactSolver, RandomFaceContactsAgreeWithPlainGaussSeidelRunToConvergence) {
  std::mt19937 random(20261206);
  std::uniform_real_distribution<double> unit(0, 1), signed_unit(-1, 1);
  int sliding = 0, lifting = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double b = 0.05 + 0.45 * unit(random), d = 0.05 + 0.45 * unit(random), h = 0.2 + 0.8 * unit(random);
    const double friction = 0.1 + 0.8 * unit(random);
    const Vec3 free = kG * kDt * Vec3(3 * signed_unit(random), 3 * signed_unit(random), -1 - unit(random));
    const Vec3 spin = kG * kDt / h * Vec3(signed_unit(random), signed_unit(random), signed_unit(random));
    Block block(b, d, h, free, friction);
    block.bodies[1].angular_velocity = spin;
    dynamics::SolverSettings settings = tight();
    const auto result = block.solve(settings);
    ASSERT_TRUE(result.converged) << "trial " << trial;
    const DenseResult oracle = dense_gauss_seidel(block, free, spin);
    const double scale = kG * kDt;
    EXPECT_NEAR((block.bodies[1].velocity - oracle.velocity).norm(), 0, 1e-7 * scale) << "trial " << trial;
    EXPECT_NEAR((block.bodies[1].angular_velocity - oracle.angular_velocity).norm(), 0, 1e-7 * scale / h)
        << "trial " << trial;
    EXPECT_NEAR(total_normal(block.rows), oracle.normal, 1e-7 * kMass * scale) << "trial " << trial;
    EXPECT_NEAR((block.patches[0].impulse - oracle.friction).norm(), 0, 1e-7 * kMass * scale) << "trial " << trial;
    const double size =
        std::hypot(oracle.friction.x(), oracle.friction.y(), oracle.friction.z() / block.patches[0].radius);
    if (size >= friction * oracle.normal * (1 - 1e-9)) ++sliding;
    for (const auto& r : block.rows) lifting += r.normal_impulse == 0;
  }
  // the sample covers both friction states and corners that lift
  EXPECT_GT(sliding, 5);
  EXPECT_GT(lifting, 5);
}

TEST(ContactSolver, ASlenderBlockRockedByAPulseConvergesEveryStep) {
  // the case that capped 40 % of its contact steps with point-by-point Gauss-Seidel: alpha 0.05
  // (b = 0.05 m, 2 h = 2 m), rigid contact, a one-sine pulse of 0.1 g that rocks it
  const double b = 0.05, h = 1.0;
  scenario::Scene scene = library::block_on_pedestal(b, h, 0.5);
  scenario::RunSettings settings;
  settings.duration = 3.0;
  const scenario::RunOutcome out = scenario::run(scene, library::one_sine_drive(0.1 * kGravity, 0.5), settings);
  EXPECT_GT(out.max_tilt_rad, 1e-3) << "the pulse should rock the block (0.1 g > tan alpha = 0.05 g)";
  EXPECT_GT(out.solver_solves, 100);
  EXPECT_EQ(out.unconverged_steps, 0);
  EXPECT_LE(double(out.solver_sweeps) / double(out.solver_solves), 3.0);
}

// Two 1 m cubes stacked on a fixed slab, rigid contacts: two patches that share the lower cube.
dynamics::World stack_on_slab(const dynamics::StepSettings& settings, contact::ContactMethod model) {
  contact::ContactLaw law;
  law.method = model;
  std::vector<dynamics::BodyDef> bodies = {
      library::box_body("slab", Vec3(-2, -2, -1), Vec3(2, 2, 0), 2600, true),
      library::box_body("lower", Vec3(-0.5, -0.5, 0), Vec3(0.5, 0.5, 1), 2600, false),
      library::box_body("upper", Vec3(-0.5, -0.5, 1), Vec3(0.5, 0.5, 2), 2600, false)};
  return dynamics::World(std::move(bodies), law, settings);
}

TEST(ContactSolver, TheWorldCountsTheStepsWhoseSolveHitItsCap) {
  dynamics::StepSettings capped;
  capped.solver_max_sweeps = 1;
  dynamics::World world = stack_on_slab(capped, contact::ContactMethod::rigid);
  // the first step starts without a warm start: the upper patch's impulse, found after the lower
  // patch was solved without it, changes the lower cube again
  world.step(world.dt(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(world.stats().unconverged_steps, 1);
  EXPECT_EQ(world.stats().max_solver_sweeps, 1);

  // with the default cap, a stack at rest converges every step
  dynamics::World resting = stack_on_slab(dynamics::StepSettings{}, contact::ContactMethod::rigid);
  for (int k = 0; k < 200; ++k) resting.step(resting.dt(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(resting.stats().unconverged_steps, 0);
  EXPECT_GE(resting.stats().max_solver_sweeps, 2);  // the first step's solve needs more than one
  EXPECT_LT(resting.stats().max_solver_sweeps, dynamics::StepSettings{}.solver_max_sweeps);
  EXPECT_NEAR(resting.states()[1].position.z(), 0.5, 1e-6) << "the lower cube should stand still";
  EXPECT_NEAR(resting.states()[2].position.z(), 1.5, 1e-6) << "the upper cube should stand still";

  // penalty contacts have no such solve
  dynamics::World springs = stack_on_slab(dynamics::StepSettings{}, contact::ContactMethod::penalty);
  for (int k = 0; k < 10; ++k) springs.step(springs.dt(), Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(springs.stats().unconverged_steps, 0);
  EXPECT_EQ(springs.stats().max_solver_sweeps, 0);
}

// Two cubes stacked on the ground, one step of gravity on each: the two patches share the lower
// cube, so the solve visits their points by over-relaxed sweeps. Statics is the oracle: the top
// face carries one cube's weight, the bottom face two, and nothing moves; friction, though
// available, has no load to take.
TEST(ContactSolver, AStackOfTwoCubesCarriesEachCubesWeightOnTheFaceBelowIt) {
  auto bodies = ground_and_cube(Vec3(0, 0, -kG * kDt));
  bodies.push_back(bodies[1]);
  auto rows = four_corners();
  for (const ContactRow& lower : four_corners()) {
    ContactRow upper = lower;
    upper.a = 1;
    upper.b = 2;
    upper.ra = lower.ra + Vec3(0, 0, kHalf);
    rows.push_back(upper);
  }
  FrictionPatch top = bottom_face(0.5);
  top.a = 1;
  top.b = 2;
  top.first_row = 4;
  top.ra = Vec3(0, 0, kHalf);
  std::vector<FrictionPatch> patches = {bottom_face(0.5), top};
  const auto result = solve(bodies, rows, patches, tight());
  ASSERT_TRUE(result.converged);
  const double weight = kMass * kG * kDt;
  double bottom = 0, upper = 0;
  for (int k = 0; k < 4; ++k) bottom += rows[std::size_t(k)].normal_impulse;
  for (int k = 4; k < 8; ++k) upper += rows[std::size_t(k)].normal_impulse;
  EXPECT_NEAR(bottom, 2 * weight, 1e-8 * weight);
  EXPECT_NEAR(upper, weight, 1e-8 * weight);
  for (int i = 1; i <= 2; ++i) {
    EXPECT_LT(bodies[std::size_t(i)].velocity.norm(), 1e-10);
    EXPECT_LT(bodies[std::size_t(i)].angular_velocity.norm(), 1e-10);
    EXPECT_LT(patches[std::size_t(i - 1)].impulse.norm(), 1e-8 * weight);
  }
}

}  // namespace
}  // namespace rigid
