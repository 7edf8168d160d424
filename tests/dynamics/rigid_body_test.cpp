// Free rigid-body rotation against independent oracles: conservation laws and a separately
// integrated Euler equation.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/dynamics/world.hpp"
#include "rigid/library/builders.hpp"

namespace rigid {
namespace {

// Euler's equations in the principal frame, I1 w1' = (I2 - I3) w2 w3 (cyclic), integrated by
// fine-step RK4: an oracle that shares no code with the engine.
Vec3 euler_reference(const Vec3& inertia, Vec3 w, double duration) {
  auto f = [&](const Vec3& x) {
    return Vec3((inertia[1] - inertia[2]) * x[1] * x[2] / inertia[0],
                (inertia[2] - inertia[0]) * x[2] * x[0] / inertia[1],
                (inertia[0] - inertia[1]) * x[0] * x[1] / inertia[2]);
  };
  const double h = 1e-5;
  const long n = std::lround(duration / h);
  for (long i = 0; i < n; ++i) {
    const Vec3 k1 = f(w), k2 = f(w + 0.5 * h * k1), k3 = f(w + 0.5 * h * k2), k4 = f(w + h * k3);
    w += (h / 6.0) * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return w;
}

class TorqueFreeSpin : public ::testing::TestWithParam<dynamics::RotationIntegrator> {};

TEST_P(TorqueFreeSpin, ConservesMomentumAndEnergyAndFlipsAboutIntermediateAxis) {
  // an asymmetric box, spun mostly about its intermediate axis (Dzhanibekov effect)
  auto body = library::box_body("brick", Vec3(0, 0, 0), Vec3(0.3, 0.6, 1.2), 2600, false);
  const Vec3 inertia = body.shape.inertia;  // ascending: axis 1 is the intermediate one
  const Vec3 w_body(0.05, 3.0, 0.0);
  body.angular_velocity = body.orientation * w_body;
  dynamics::StepSettings settings;
  settings.gravity = 0;
  settings.dt = 1e-4;
  settings.rotation = GetParam();
  dynamics::World world({body}, contact::ContactLaw{}, settings);
  const Vec3 l0 = world.states()[0].angular_momentum;
  const double e0 = world.kinetic_energy();
  double min_l2 = 1e30, max_l2 = -1e30;
  for (int k = 0; k < 100000; ++k) {  // 10 s
    world.step(1e-4, Vec3::Zero(), Vec3::Zero());
    const auto& s = world.states()[0];
    const Vec3 lb = s.orientation.conjugate() * s.angular_momentum;
    min_l2 = std::min(min_l2, lb[1]);
    max_l2 = std::max(max_l2, lb[1]);
  }
  const auto& s = world.states()[0];
  EXPECT_LT((s.angular_momentum - l0).norm() / l0.norm(), 1e-6);
  EXPECT_LT(std::abs(world.kinetic_energy() - e0) / e0, 1e-6);
  // the intermediate-axis component reversed sign: the body flipped
  EXPECT_LT(min_l2, -0.9 * inertia[1] * w_body[1]);
  EXPECT_GT(max_l2, 0.9 * inertia[1] * w_body[1]);
  // body-frame angular velocity agrees with an independent integration of Euler's equations
  const Vec3 w_ref = euler_reference(inertia, w_body, 10.0);
  const Vec3 w_sim = (s.orientation.conjugate() * s.angular_momentum).cwiseQuotient(inertia);
  EXPECT_LT((w_sim - w_ref).norm() / w_body.norm(), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Integrators, TorqueFreeSpin,
                         ::testing::Values(dynamics::RotationIntegrator::splitting, dynamics::RotationIntegrator::rk4));

TEST(FreeFall, MatchesClosedFormAtSeveralSteps) {
  for (double dt : {1e-3, 1e-4}) {
    auto body = library::box_body("b", Vec3(0, 0, 0), Vec3(1, 1, 1), 2600, false);
    body.velocity = Vec3(1.0, 0, 2.0);
    dynamics::StepSettings settings;
    settings.dt = dt;
    dynamics::World world({body}, contact::ContactLaw{}, settings);
    const long n = std::lround(1.0 / dt);
    for (long k = 0; k < n; ++k) world.step(dt, Vec3::Zero(), Vec3::Zero());
    const Vec3 x = world.states()[0].position;
    // velocity Verlet is exact for constant acceleration
    EXPECT_NEAR(x.x(), 0.5 + 1.0, 1e-9);
    EXPECT_NEAR(x.z(), 0.5 + 2.0 - 0.5 * kGravity, 1e-9);
    EXPECT_NEAR(world.states()[0].velocity.z(), 2.0 - kGravity, 1e-9);
  }
}

}  // namespace
}  // namespace rigid
