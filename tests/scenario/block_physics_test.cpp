// A rectangular block on a pedestal against closed forms: rest, quasi-static tipping at
// g tan(alpha), Coulomb sliding at mu g, invariance under rotation about z, and the one-sine
// pulse overturning threshold of the 2D Housner model (physics.md §2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rigid/library/builders.hpp"
#include "rigid/rocking/housner.hpp"

namespace rigid {
namespace {

constexpr double kHeight = 1.0;  // block height (m)
constexpr double kDepth = 0.5;   // block depth (m)

scenario::Scene settled_block(double alpha, const contact::ContactLaw& law = {}) {
  const double h = 0.5 * kHeight;
  const scenario::Scene s = library::block_on_pedestal(h * std::tan(alpha), h, kDepth, law);
  return scenario::equilibrate(s, dynamics::StepSettings{});
}

TEST(BlockAtRest, StaysPutFor20Seconds) {
  const scenario::Scene scene = settled_block(0.2);
  dynamics::World world(scene.bodies, scene.law, dynamics::StepSettings{});
  const Vec3 x0 = world.states()[1].position;
  const Quat q0 = world.states()[1].orientation;
  const double dt = world.dt();
  double drift = 0, turn = 0;
  for (double t = 0; t < 20.0; t += dt) {
    world.step(dt, Vec3::Zero(), Vec3::Zero());
    drift = std::max(drift, (world.states()[1].position - x0).norm());
    turn = std::max(turn, q0.angularDistance(world.states()[1].orientation));
  }
  EXPECT_LT(drift, 1e-6);
  EXPECT_LT(turn, 1e-6);
}

// Ground acceleration ramped slowly from zero at `rate` (m/s^3): a(t) = rate t, v = rate t^2 / 2.
struct Ramp {
  double rate;
  Vec3 velocity(double t) const { return Vec3(0.5 * rate * t * t, 0, 0); }
};

// The oracle g tan(alpha) is rigid-block statics. With the study's soft Hertz contacts
// (K_N = 1e8) the block first tilts elastically on its springs, which moves the centroid towards
// the toe by about h (d_toe - d_heel) / 2b and lowers the uplift acceleration by 1-3 %; stiff
// contacts (1e10) approach the rigid limit, and that is what the 2 % criterion tests.
contact::ContactLaw stiff_contacts() {
  contact::ContactLaw law;
  law.method = contact::ContactMethod::penalty;  // the rigid model's own tests: rigid_contact_test.cpp
  law.normal_stiffness = 1e10;
  law.shear_stiffness = 1e10;
  return law;
}

class QuasiStaticTipping : public ::testing::TestWithParam<double> {};

TEST_P(QuasiStaticTipping, UpliftStartsAtGTanAlphaWithoutSliding) {
  const double alpha = GetParam();
  const scenario::Scene scene = settled_block(alpha, stiff_contacts());
  dynamics::World world(scene.bodies, scene.law, dynamics::StepSettings{});
  const Ramp ramp{0.02 * kGravity};
  const double dt = world.dt();
  double uplift = -1;
  for (double t = 0; t < 30.0; t += dt) {
    world.step(dt, ramp.velocity(t), ramp.velocity(t + dt));
    // the heel lifts: only the two toe corners remain in contact
    if (world.pairs()[0].points.size() <= 2) {
      uplift = ramp.rate * (t + dt);
      break;
    }
  }
  ASSERT_GT(uplift, 0) << "the block never tipped";
  const double expected = kGravity * std::tan(alpha);
  EXPECT_NEAR(uplift / expected, 1.0, 0.02);
  // single heel subcontacts micro-slip as their load vanishes; the block itself must not slide
  EXPECT_LT(world.slip()[1], 1e-4) << "a block with friction 0.6 > tan(alpha) must not slide";
}

INSTANTIATE_TEST_SUITE_P(Alphas, QuasiStaticTipping, ::testing::Values(0.1, 0.2, 0.3));

class CoulombSliding : public ::testing::TestWithParam<double> {};

TEST_P(CoulombSliding, SlidesAtMuGWhenFrictionIsBelowTanAlpha) {
  const double alpha = 0.3;
  const double mu = GetParam();
  contact::ContactLaw law = stiff_contacts();
  law.friction = mu;
  const scenario::Scene scene = settled_block(alpha, law);
  dynamics::World world(scene.bodies, scene.law, dynamics::StepSettings{});
  const Ramp ramp{0.01 * kGravity};
  const double dt = world.dt();
  // slip is measured at the base (mean of the four lowest vertices), where elastic tilting of
  // the block moves nothing
  auto base_x = [&] {
    std::vector<Vec3> v = world.world_vertices(1);
    std::sort(v.begin(), v.end(), [](const Vec3& p, const Vec3& q) { return p.z() < q.z(); });
    return 0.25 * (v[0].x() + v[1].x() + v[2].x() + v[3].x()) - world.states()[0].position.x();
  };
  const double x_rel0 = base_x();
  double onset = -1;
  double t = 0;
  for (; t < 40.0; t += dt) {
    world.step(dt, ramp.velocity(t), ramp.velocity(t + dt));
    if (std::abs(base_x() - x_rel0) > 1e-5) {
      onset = ramp.rate * (t + dt);
      break;
    }
  }
  ASSERT_GT(onset, 0) << "the block never slid";
  EXPECT_NEAR(onset / (mu * kGravity), 1.0, 0.02);
  // while sliding, friction alone accelerates the block: a = mu g
  const double v0 = world.states()[1].velocity.x();
  const double window = 0.5;
  for (double s = 0; s < window; s += dt) {
    world.step(dt, ramp.velocity(t + s), ramp.velocity(t + s + dt));
  }
  const double a = (world.states()[1].velocity.x() - v0) / window;
  EXPECT_NEAR(a / (mu * kGravity), 1.0, 0.02);
  EXPECT_LT(world.states()[1].orientation.angularDistance(scene.bodies[1].orientation), 0.01)
      << "a sliding block should not tip";
}

INSTANTIATE_TEST_SUITE_P(Frictions, CoulombSliding, ::testing::Values(0.15, 0.25));

scenario::GroundDrive one_sine(double amplitude, double period, const Vec3& direction) {
  // a(t) = A sin(2 pi t / T) for one period; v(t) = A T / (2 pi) (1 - cos(2 pi t / T))
  scenario::GroundDrive drive;
  drive.dt = 1e-3;
  const long n = std::lround(period / drive.dt);
  for (long i = 0; i <= n; ++i) {
    const double t = double(i) * drive.dt;
    const double v = amplitude * period / (2 * kPi) * (1 - std::cos(2 * kPi * t / period));
    drive.velocity.push_back(v * direction);
  }
  return drive;
}

TEST(RotationInvariance, RotatingSceneAndMotionTogetherKeepsTheOutcome) {
  const double alpha = 0.2;
  const scenario::Scene scene = settled_block(alpha);
  scenario::RunSettings settings;
  settings.free_time = 4.0;
  for (double amplitude_g : {0.3, 0.6}) {
    const auto base = scenario::run(scene, one_sine(amplitude_g * kGravity, 0.5, Vec3::UnitX()), settings);
    for (double angle : {0.7, 2.0}) {
      const Quat turn(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
      scenario::Scene turned = scene;
      for (auto& b : turned.bodies) {
        b.position = turn * b.position;
        b.orientation = turn * b.orientation;
      }
      const auto r = scenario::run(turned, one_sine(amplitude_g * kGravity, 0.5, turn * Vec3::UnitX()), settings);
      EXPECT_EQ(r.overturned, base.overturned) << "amplitude " << amplitude_g << " g, angle " << angle;
      EXPECT_NEAR(r.max_tilt_rad, base.max_tilt_rad, 0.01 * base.max_tilt_rad + 1e-4);
    }
  }
}

struct PulseCase {
  double period;     // one-sine period (s)
  double stiffness;  // K_N = K_S
};

class HousnerPulse : public ::testing::TestWithParam<PulseCase> {};

// The 3D engine against the 2D Housner model (rigid contact, angular-momentum impacts). At the
// study's stiffness (1e8) the threshold agrees within 10 % at these periods; the T = 0.5 s case
// (3D 12 % lower at 1e8: elastic tilting on soft contacts) converges to the 2D value as the
// contacts stiffen, which the 1e10 case checks.
TEST_P(HousnerPulse, OneSineThresholdWithinTenPercentOf2DModel) {
  const double period = GetParam().period;
  const double alpha = 0.2;
  const double h = 0.5 * kHeight, b = h * std::tan(alpha);
  const auto block2d = rocking::RockingBlock::rectangular(b, h);
  const double a2d = rocking::min_overturning_amplitude(block2d, rocking::PulseShape::one_sine, period);
  ASSERT_TRUE(std::isfinite(a2d));
  contact::ContactLaw law;
  law.method = contact::ContactMethod::penalty;
  law.normal_stiffness = law.shear_stiffness = GetParam().stiffness;
  const scenario::Scene scene = settled_block(alpha, law);
  scenario::RunSettings settings;
  settings.free_time = 6.0;
  // scan upward in 2% steps from 80% of the 2D threshold: the first amplitude that overturns
  double a3d = -1;
  for (double ratio = 0.80; ratio <= 1.3; ratio += 0.02) {
    const auto r = scenario::run(scene, one_sine(ratio * a2d, period, Vec3::UnitX()), settings);
    if (r.overturned) {
      a3d = ratio * a2d;
      break;
    }
  }
  ASSERT_GT(a3d, 0) << "no overturning up to 1.3x the 2D threshold";
  std::printf("T = %.2f s, K = %.0e: 2D threshold %.4f g, 3D %.4f g (ratio %.3f)\n", period, GetParam().stiffness,
              a2d / kGravity, a3d / kGravity, a3d / a2d);
  EXPECT_NEAR(a3d / a2d, 1.0, 0.10);
}

INSTANTIATE_TEST_SUITE_P(Periods, HousnerPulse,
                         ::testing::Values(PulseCase{0.25, 1e8}, PulseCase{1.0, 1e8}, PulseCase{2.0, 1e8},
                                           PulseCase{0.5, 1e10}),
                         [](const ::testing::TestParamInfo<PulseCase>& info) {
                           return "T" + std::to_string(int(1000 * info.param.period)) + "ms_K1e" +
                                  std::to_string(int(std::lround(std::log10(info.param.stiffness))));
                         });

}  // namespace
}  // namespace rigid
