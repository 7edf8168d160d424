// One case through scenario::simulate_case: the motion a case builds (target PGA, rotation, the 2D
// model's unrotated x) checked against measures recomputed on it, the outcome of both models
// against the 2D Housner threshold of a one-sine pulse (physics.md §2), and an error inside a case
// becoming a failed outcome that keeps its message.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/core/error.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/motion/measures.hpp"
#include "rigid/rocking/housner.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/rocking2d.hpp"

namespace rigid::scenario {
using namespace library;
namespace {

// Two horizontals of different amplitude and frequency, 20 s at 100 Hz (unit: m/s^2).
motion::GroundMotion two_sines() {
  motion::GroundMotion m;
  m.name = "two_sines";
  m.dt = 0.01;
  for (int i = 0; i < 2000; ++i) {
    const double t = i * m.dt;
    m.x.push_back(2.0 * std::sin(2 * kPi * 1.3 * t));
    m.y.push_back(1.1 * std::sin(2 * kPi * 0.7 * t + 0.4));
  }
  m.has_y = true;
  return m;
}

// a(t) = sin(2 pi t / T) for 0 <= t <= T along x (unit amplitude, m/s^2), then quiet.
motion::GroundMotion unit_one_sine(double period, double dt = 1e-3) {
  motion::GroundMotion m;
  m.name = "one_sine";
  m.dt = dt;
  const int n = int(std::lround(period / dt));
  for (int i = 0; i <= n; ++i) m.x.push_back(std::sin(2 * kPi * i * dt / period));
  return m;
}

Scene slender_block() { return block_on_pedestal(0.2, 1.0, 0.4); }  // alpha = atan(0.2) ~ 0.197

TEST(CaseMotion, ReachesTheTargetGMRotI50PGA) {
  const Model model(Engine::dem3d, {slender_block()}, {two_sines()}, RunSettings{});
  for (double target : {0.1, 0.37, 1.5}) {
    const motion::GroundMotion m = case_motion(model, Case{0, 0, target, 0.0});
    EXPECT_NEAR(motion::horizontal_measures(m).gmroti50_pga / kGravity, target, 1e-9 * target);
  }
}

TEST(CaseMotion, PrecomputedFactorGivesTheSameMotion) {
  const motion::GroundMotion record = two_sines();
  const Model computed(Engine::dem3d, {slender_block()}, {record}, RunSettings{});
  const Model given(Engine::dem3d, {slender_block()}, {record}, RunSettings{},
                    {motion::target_pga_factor(record, 1.0)});
  const Case c{0, 0, 0.42, 33.0};
  EXPECT_EQ(case_motion(computed, c).x, case_motion(given, c).x);
  EXPECT_EQ(case_motion(computed, c).y, case_motion(given, c).y);
}

TEST(CaseMotion, RotationTurnsTheHorizontalsCounterClockwise) {
  const motion::GroundMotion record = unit_one_sine(0.5);
  const Model model(Engine::dem3d, {slender_block()}, {record}, RunSettings{});
  const motion::GroundMotion m = case_motion(model, Case{0, 0, 0.0, 90.0});
  ASSERT_TRUE(m.has_y);
  for (std::size_t i = 0; i < record.x.size(); ++i) {
    EXPECT_NEAR(m.x[i], 0.0, 1e-12);
    EXPECT_NEAR(m.y[i], record.x[i], 1e-12);  // x turned 90 degrees toward y
  }
}

TEST(CaseMotion, TheTwoDimensionalModelIgnoresTheRotation) {
  const motion::GroundMotion record = unit_one_sine(0.5);
  const Model model(Engine::rocking2d, {slender_block()}, {record}, RunSettings{});
  EXPECT_EQ(case_motion(model, Case{0, 0, 0.0, 90.0}).x, record.x);
}

// Both models survive a one-sine pulse 5 % below the 2D Housner threshold and overturn 5 % above
// it; the amplitude is set through the case's target PGA (one horizontal: its peak).
TEST(Simulate, BothModelsBracketTheHousnerThreshold) {
  const Scene scene = slender_block();
  const double period = 0.6;
  const double threshold =
      rocking::min_overturning_amplitude(rocking_block_of(scene), rocking::PulseShape::one_sine, period);
  ASSERT_TRUE(std::isfinite(threshold));
  RunSettings run;
  run.free_time = 10.0;  // as the 2D threshold search: slow overturning after the pulse is caught
  for (Engine kind : {Engine::dem3d, Engine::rocking2d}) {
    const Model model(kind, {scene}, {unit_one_sine(period)}, run);
    const CaseOutcome below = simulate_case(model, Case{0, 0, 0.95 * threshold / kGravity, 0.0});
    const CaseOutcome above = simulate_case(model, Case{0, 0, 1.05 * threshold / kGravity, 0.0});
    EXPECT_EQ(below.outcome, CellOutcome::survived) << engine_name(kind);
    EXPECT_EQ(above.outcome, CellOutcome::overturned) << engine_name(kind);
    EXPECT_EQ(below.reason, FailureReason::none);
    EXPECT_TRUE(above.run.failure_time_s.has_value());
  }
}

TEST(Simulate, AnErrorInACaseIsAFailedOutcomeWithItsMessage) {
  motion::GroundMotion quiet = unit_one_sine(0.5);
  for (double& a : quiet.x) a = 0.0;  // nothing to scale: a target PGA cannot be reached
  const Model model(Engine::dem3d, {slender_block()}, {quiet}, RunSettings{});
  const CaseOutcome out = simulate_case(model, Case{0, 0, 0.3, 0.0});
  EXPECT_EQ(out.outcome, CellOutcome::failed);
  EXPECT_EQ(out.reason, FailureReason::exception);
  EXPECT_NE(out.message.find("horizontal acceleration is zero"), std::string::npos) << out.message;
  EXPECT_TRUE(out.error);
}

TEST(Engine, NamesRoundTripAndOthersAreRefused) {
  for (Engine k : {Engine::dem3d, Engine::rocking2d}) EXPECT_EQ(parse_engine(engine_name(k)), k);
  EXPECT_FALSE(parse_engine("rocking3d"));
  EXPECT_FALSE(parse_engine(""));
}

TEST(Model, RocksInTwoDimensionsOnlyABoxOnABox) {
  Scene two_free = slender_block();
  for (auto& b : two_free.bodies) b.fixed = false;
  const auto make = [&](Engine kind) { return Model(kind, {two_free}, {}, RunSettings{}); };
  EXPECT_THROW(make(Engine::rocking2d), InputError);
  EXPECT_NO_THROW(make(Engine::dem3d));
}

}  // namespace
}  // namespace rigid::scenario
