// Accuracy presets (scenario/accuracy.hpp): the three names, what each sets, the precedence of
// explicit settings, and that no preset touches the physics.
#include <gtest/gtest.h>

#include "rigid/scenario/accuracy.hpp"

namespace rigid::scenario {
namespace {

using dynamics::RotationIntegrator;

TEST(AccuracyPresets, ThreeNamedPresetsCheapestFirst) {
  const auto& presets = accuracy_presets();
  ASSERT_EQ(presets.size(), 3u);
  EXPECT_EQ(presets[0].name, "fast");
  EXPECT_EQ(presets[1].name, "balanced");
  EXPECT_EQ(presets[2].name, "reference");
  // cheaper = larger time step and looser (or equal) at-rest stop
  for (std::size_t i = 1; i < presets.size(); ++i) {
    EXPECT_LT(presets[i].safety, presets[i - 1].safety);
    EXPECT_LE(presets[i].rest_speed, presets[i - 1].rest_speed);
    EXPECT_GE(presets[i].rest_time, presets[i - 1].rest_time);
  }
  for (const auto& p : presets) {
    EXPECT_EQ(find_accuracy_preset(p.name), &p);
    EXPECT_FALSE(p.summary.empty());
  }
  EXPECT_EQ(accuracy_preset_list(), "fast, balanced or reference");
}

TEST(AccuracyPresets, UnknownNamesAreNotFound) {
  EXPECT_EQ(find_accuracy_preset(""), nullptr);
  EXPECT_EQ(find_accuracy_preset("Fast"), nullptr);
  EXPECT_EQ(find_accuracy_preset("precise"), nullptr);
  EXPECT_NE(find_accuracy_preset(kDefaultAccuracy), nullptr);
}

TEST(AccuracyPresets, BalancedIsTheEnginesDefaults) {
  // RunSettings{} and StepSettings{} are what the tests and the library use without a preset
  const AccuracyPreset& b = *find_accuracy_preset("balanced");
  const RunSettings defaults;
  EXPECT_EQ(b.safety, defaults.step.safety);
  EXPECT_EQ(b.rotation, defaults.step.rotation);
  EXPECT_EQ(b.rest_speed, defaults.rest_speed);
  EXPECT_EQ(b.rest_angular_speed, defaults.rest_angular_speed);
  EXPECT_EQ(b.rest_time, defaults.rest_time);
}

TEST(AccuracyPresets, ApplySetsOnlyNumericalSettings) {
  RunSettings s;
  s.step.dt = 1e-4;  // replaced: a preset means the automatic step
  s.duration = 12.0;
  s.free_time = 3.0;
  s.step.local_damping = 0.3;
  s.step.gravity = 9.0;
  const AccuracyPreset& fast = *find_accuracy_preset("fast");
  apply_accuracy(fast, {}, s);
  EXPECT_EQ(s.step.dt, 0.0);
  EXPECT_EQ(s.step.safety, fast.safety);
  EXPECT_EQ(s.step.rotation, fast.rotation);
  EXPECT_EQ(s.rest_speed, fast.rest_speed);
  EXPECT_EQ(s.rest_angular_speed, fast.rest_angular_speed);
  EXPECT_EQ(s.rest_time, fast.rest_time);
  // not numerical settings: left alone
  EXPECT_EQ(s.duration, 12.0);
  EXPECT_EQ(s.free_time, 3.0);
  EXPECT_EQ(s.step.local_damping, 0.3);
  EXPECT_EQ(s.step.gravity, 9.0);
}

TEST(AccuracyPresets, ExplicitSettingsOverrideThePreset) {
  RunSettings s;
  AccuracyOverrides o;
  o.safety = 0.33;
  o.rotation = RotationIntegrator::rk4;
  const AccuracyPreset& ref = *find_accuracy_preset("reference");
  apply_accuracy(ref, o, s);
  EXPECT_EQ(s.step.safety, 0.33);
  EXPECT_EQ(s.step.rotation, RotationIntegrator::rk4);
  EXPECT_EQ(s.rest_speed, ref.rest_speed);  // not overridden
  o = {};
  o.dt = 2e-5;
  apply_accuracy(ref, o, s);
  EXPECT_EQ(s.step.dt, 2e-5);
  EXPECT_EQ(s.step.safety, ref.safety);
}

TEST(AccuracyPresets, IntegratorNames) {
  EXPECT_EQ(parse_integrator("splitting"), RotationIntegrator::splitting);
  EXPECT_EQ(parse_integrator("rk4"), RotationIntegrator::rk4);
  EXPECT_FALSE(parse_integrator("RK4"));
  EXPECT_FALSE(parse_integrator("verlet"));
  EXPECT_STREQ(integrator_name(RotationIntegrator::rk4), "rk4");
  EXPECT_STREQ(integrator_name(RotationIntegrator::splitting), "splitting");
}

}  // namespace
}  // namespace rigid::scenario
