// The accuracy study as a library: its case and setting lists are well formed, and the oracle
// values it checks the engine against equal their closed forms (g tan(alpha) of a rectangular
// block, rigid-statics toppling of a two-box stack), computed here from the scenes' dimensions.
#include "rigid/study/accuracy_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace rigid::study {
namespace {

// A stand-in record: 10 s of a 1 Hz sine (the quick cases do not use it)
motion::GroundMotion sine_record() {
  motion::GroundMotion m;
  m.name = "sine";
  m.dt = 0.01;
  for (int i = 0; i <= 1000; ++i) m.x.push_back(2.0 * std::sin(2 * kPi * i * m.dt));
  return m;
}

const Case& find_case(const std::vector<Case>& cases, const std::string& scene, const std::string& motion) {
  for (const auto& c : cases) {
    if (c.scene == scene && c.motion == motion) return c;
  }
  throw std::runtime_error("no case " + scene + "/" + motion);
}

TEST(AccuracyStudy, QuickCaseListIsWellFormed) {
  StudyOptions o;
  o.quick = true;
  const std::vector<Case> cases = study_cases(o, sine_record());
  // one-sine pulses on the slender and stocky blocks, the sliding block, the geode drop
  ASSERT_EQ(cases.size(), 4u);
  std::set<std::string> names;
  for (const auto& c : cases) {
    EXPECT_TRUE(names.insert(c.scene + "/" + c.motion).second) << "duplicate " << c.scene << "/" << c.motion;
    ASSERT_TRUE(c.build) << c.scene;
    const scenario::Scene scene = c.build(c.law);
    int fixed = 0;
    for (const auto& b : scene.bodies) fixed += b.fixed;
    EXPECT_GE(fixed, 1) << c.scene;
    EXPECT_GE(int(scene.bodies.size()) - fixed, 1) << c.scene;
    EXPECT_NE(c.oracle, Oracle::none) << c.scene;
    EXPECT_FALSE(c.model_quantity.empty()) << c.scene;
  }
  EXPECT_EQ(find_case(cases, "slender", "pulse").oracle, Oracle::housner_pulse);
  EXPECT_GT(find_case(cases, "stocky", "pulse").pulse_period, 0);
  const Case& sliding = find_case(cases, "sliding", "pulse");
  EXPECT_EQ(sliding.oracle, Oracle::newmark_slide);
  EXPECT_FALSE(sliding.ground.x.empty());
  const Case& geode = find_case(cases, "geode", "drop");
  EXPECT_TRUE(geode.conservative);
  EXPECT_EQ(geode.law.friction, 0.0);
  EXPECT_EQ(geode.law.damping, 0.0);

  o.only = {"geode"};
  EXPECT_EQ(study_cases(o, sine_record()).size(), 1u);
}

TEST(AccuracyStudy, SettingsStartWithTheConvergedReference) {
  StudyOptions o;
  o.quick = true;
  o.reference_safety = 0.01;
  const std::vector<Setting> settings = study_settings(o);
  ASSERT_FALSE(settings.empty());
  EXPECT_EQ(settings.front().axis, "converged");
  EXPECT_EQ(settings.front().safety, 0.01);
  EXPECT_FALSE(settings.front().select_effects);
  std::set<std::string> labels;
  for (const auto& s : settings) EXPECT_TRUE(labels.insert(s.label).second) << "duplicate " << s.label;
  o.contact = "penalty";
  for (const auto& s : study_settings(o)) EXPECT_NE(s.axis, "rigid");
  o.contact = "rigid";
  for (const auto& s : study_settings(o)) EXPECT_NE(s.axis, "stiffness");
}

TEST(AccuracyStudy, TiltTestOracleIsGTanAlphaOfTheBlock) {
  const std::vector<Case> cases = study_cases(StudyOptions{}, sine_record());
  // block_a01: half-width 0.5 tan(0.1) m, half-height 0.5 m, so tan(alpha) = b / h = tan(0.1)
  const Case& slender = find_case(cases, "slender", "quasi-static");
  ASSERT_EQ(slender.oracle, Oracle::g_tan_alpha);
  EXPECT_NEAR(oracle_value(slender), std::tan(0.1), 1e-12);
  const Case& stocky = find_case(cases, "stocky", "quasi-static");
  EXPECT_NEAR(oracle_value(stocky), std::tan(0.4), 1e-12);
}

TEST(AccuracyStudy, StackOracleIsRigidStaticsToppling) {
  const std::vector<Case> cases = study_cases(StudyOptions{}, sine_record());
  const Case& stack = find_case(cases, "stack", "quasi-static");
  ASSERT_EQ(stack.oracle, Oracle::rigid_statics);
  // upper box 0.2 m wide in x, 0.6 m tall, resting on the lower one: it tips about its own edge at
  // a/g = 0.1 / 0.3. Both boxes about the lower one's edge: masses in proportion to the volumes
  // 0.1 and 0.036 m^3, combined centroid (0.1 * 0.2 + 0.036 * 0.7) / 0.136 m above the pedestal,
  // lever 0.25 m: a/g = 0.752, larger. The smaller is the oracle.
  const double upper = 0.1 / 0.3;
  const double both = 0.25 / ((0.1 * 0.2 + 0.036 * 0.7) / 0.136);
  ASSERT_LT(upper, both);
  EXPECT_NEAR(oracle_value(stack), upper, 1e-9);
}

}  // namespace
}  // namespace rigid::study
