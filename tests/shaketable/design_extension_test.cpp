// Edge extension of a calibration's design, without simulation: a planted closed-form simulator
// (a rock overturns when the test's PGA exceeds a threshold that grows with K_N and is lowest at
// one damping D*) makes the outcomes of a "real" rock with a planted K_N* outside the first
// design; the design functions must walk to it and find it interior, or stop at a physical limit
// or at the budget and say so. Oracles: the planted parameters, and the limits set by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/core/types.hpp"
#include "rigid/shaketable/design_extension.hpp"

using namespace rigid;
using shaketable::EdgeStatus;
using shaketable::LawParameter;
using shaketable::ParameterReport;
using shaketable::Physics;

namespace {

constexpr double kPlantedStiffness = 1.25e5;  // two halvings below the design's softest, 5e5
constexpr double kPlantedDamping = 2.0;

// The planted simulator: overturns when PGA > 0.2 g (K_N / 1e6)^0.3 (1 + 0.1 (D - D*)^2); friction
// and heading change nothing.
double threshold_g(double k, double d) {
  return 0.2 * std::pow(k / 1e6, 0.3) * (1 + 0.1 * (d - kPlantedDamping) * (d - kPlantedDamping));
}

std::vector<double> test_pgas() {
  std::vector<double> pga;
  for (int t = 0; t < 80; ++t) pga.push_back(0.02 * std::pow(1.06, t));  // 0.02 to 2 g
  return pga;
}

const std::vector<double> kHeadings{140, 150, 160, 170, 180};

calibration::OutcomeGrid simulate(const std::vector<Physics>& physics) {
  const std::vector<double> pga = test_pgas();
  calibration::OutcomeGrid grid(int(physics.size()), int(pga.size()), kHeadings);
  for (std::size_t v = 0; v < physics.size(); ++v) {
    const double thr = threshold_g(physics[v].law.normal_stiffness, physics[v].law.damping);
    for (std::size_t t = 0; t < pga.size(); ++t) {
      for (int h = 0; h < grid.headings(); ++h) grid.set(int(v), int(t), h, pga[t] > thr);
    }
  }
  return grid;
}

std::vector<int> planted_outcomes() {
  std::vector<int> y;
  for (double a : test_pgas()) y.push_back(a > threshold_g(kPlantedStiffness, kPlantedDamping) ? 1 : 0);
  return y;
}

Physics penalty(double k, double d, double mu) {
  Physics p;
  p.base = "flat_5mm";
  p.base_scene = "/scenes/flat_5mm_k.toml";
  p.law.method = contact::ContactMethod::penalty;
  p.law.normal_stiffness = k;
  p.law.damping = d;
  p.law.friction = mu;
  return p;
}

// The calibration's first two stages as calibrate designs them: stage 1 the stiffnesses at
// D = 2, mu = 0.6; stage 2 the best (5e5, the softest) x D {2, 1, 4} x mu {0.6, 0.9}.
struct Design {
  std::vector<Physics> earlier{penalty(5e5, 2, 0.6), penalty(1e6, 2, 0.6), penalty(2e6, 2, 0.6)};
  std::vector<Physics> fitted;
  Design() {
    for (double d : {2.0, 1.0, 4.0}) {
      for (double mu : {0.6, 0.9}) fitted.push_back(penalty(5e5, d, mu));
    }
  }
};

struct Outcome {
  Physics best;
  std::vector<ParameterReport> parameters;
  int stages = 0;
};

// The Calibrator's loop: fit, design the next stage, "simulate" it, until nothing is proposed.
Outcome run_extension(const shaketable::PhysicalLimits& limits, int budget) {
  Design design;
  const std::vector<int> y = planted_outcomes();
  Outcome out;
  for (;;) {
    const calibration::OutcomeGrid grid = simulate(design.fitted);
    const auto stage =
        shaketable::extension_stage(grid, y, design.fitted, design.earlier, {}, limits, out.stages < budget);
    out.best = design.fitted[std::size_t(stage.best_variant)];
    out.parameters = stage.parameters;
    if (stage.physics.empty()) return out;
    for (const Physics& p : stage.physics) {
      // a new stiffness is settled anew by the caller: the design says so by clearing its scene
      EXPECT_EQ(p.base_scene.empty(), p.law.normal_stiffness != out.best.law.normal_stiffness);
    }
    design.fitted.insert(design.fitted.end(), stage.physics.begin(), stage.physics.end());
    for (Physics& p : design.fitted) {
      if (p.base_scene.empty()) p.base_scene = "/scenes/settled_anew.toml";
    }
    ++out.stages;
    if (out.stages > 20) {
      ADD_FAILURE() << "the extension does not end";
      return out;
    }
  }
}

const ParameterReport& parameter(const Outcome& o, const std::string& name) {
  for (const ParameterReport& p : o.parameters) {
    if (p.name == name) return p;
  }
  throw std::runtime_error("no parameter " + name);
}

shaketable::PhysicalLimits wide_limits() {
  shaketable::PhysicalLimits limits;
  limits.normal_stiffness = {1e4, 1e13};
  return limits;
}

}  // namespace

TEST(DesignExtension, FindsAPlantedStiffnessOutsideTheFirstDesignAndMarksItInterior) {
  const Outcome o = run_extension(wide_limits(), 10);
  EXPECT_DOUBLE_EQ(o.best.law.normal_stiffness, kPlantedStiffness);
  EXPECT_DOUBLE_EQ(o.best.law.damping, kPlantedDamping);
  const ParameterReport& k = parameter(o, "K_N");
  EXPECT_EQ(k.status, EdgeStatus::interior);
  // the design's own ratio (2) below its softest value: 2.5e5, 1.25e5, then 6.25e4 beyond the best;
  // 1e6 from stage 1 above it
  EXPECT_EQ(k.tried, (std::vector<double>{6.25e4, 1.25e5, 2.5e5, 5e5, 1e6}));
  EXPECT_EQ(parameter(o, "D").status, EdgeStatus::interior);
  // friction changes no outcome of the planted simulator: the data cannot place it
  EXPECT_EQ(parameter(o, "mu").status, EdgeStatus::not_identified);
  EXPECT_LE(o.stages, 4);
}

TEST(DesignExtension, APhysicalLimitStopsItAndIsMarked) {
  shaketable::PhysicalLimits limits = wide_limits();
  limits.normal_stiffness.low = 2e5;  // above the planted 1.25e5
  const Outcome o = run_extension(limits, 10);
  const ParameterReport& k = parameter(o, "K_N");
  EXPECT_DOUBLE_EQ(o.best.law.normal_stiffness, 2e5);  // the step to 1.25e5 clamped to the limit
  EXPECT_EQ(k.status, EdgeStatus::at_physical_limit);
  EXPECT_DOUBLE_EQ(k.tried.front(), 2e5);
}

TEST(DesignExtension, TheBudgetStopsItAndIsMarked) {
  const Outcome one = run_extension(wide_limits(), 1);
  EXPECT_EQ(one.stages, 1);
  EXPECT_DOUBLE_EQ(one.best.law.normal_stiffness, 2.5e5);  // one step towards the planted value
  EXPECT_EQ(parameter(one, "K_N").status, EdgeStatus::at_edge_budget);
  const Outcome none = run_extension(wide_limits(), 0);
  EXPECT_EQ(none.stages, 0);
  EXPECT_DOUBLE_EQ(none.best.law.normal_stiffness, 5e5);
  EXPECT_EQ(parameter(none, "K_N").status, EdgeStatus::at_edge_budget);
}

TEST(DesignExtension, StepsFollowTheDesignsOwnStep) {
  // outcomes that favour the highest threshold: D = 4 (the top of {1, 2, 4}) is best, and the
  // design's own step at its top, 4 - 2, gives 6
  Design design;
  std::vector<int> y(test_pgas().size(), 0);
  y.back() = 1;
  const calibration::OutcomeGrid grid = simulate(design.fitted);
  const auto stage =
      shaketable::extension_stage(grid, y, design.fitted, design.earlier, {}, shaketable::PhysicalLimits{}, true);
  const Physics& best = design.fitted[std::size_t(stage.best_variant)];
  ASSERT_DOUBLE_EQ(best.law.damping, 4.0);
  std::vector<std::string> expected{"D up to 6"};
  std::vector<std::string> damping_moves;
  for (const std::string& m : stage.moves) {
    if (m.rfind("D ", 0) == 0) damping_moves.push_back(m);
  }
  EXPECT_EQ(damping_moves, expected);
  EXPECT_EQ(shaketable::stage_purpose(3, stage.moves).rfind("stage 3 (extend ", 0), 0u);
  // a damping already at the physical limit is not extended beyond it
  shaketable::PhysicalLimits capped;
  capped.damping.high = 4.0;
  const auto at_limit = shaketable::extension_stage(grid, y, design.fitted, design.earlier, {}, capped, true);
  for (const std::string& m : at_limit.moves) EXPECT_NE(m.rfind("D ", 0), 0u) << m;
  for (const ParameterReport& p : at_limit.parameters) {
    if (p.name == "D") {
      EXPECT_EQ(p.status, EdgeStatus::at_physical_limit);
    }
  }
}

TEST(DesignExtension, AParameterGivenOneValueStaysFixed) {
  // friction given one value (--friction 0.6): not extended, whatever the outcomes
  std::vector<Physics> fitted;
  for (double d : {2.0, 1.0, 4.0}) fitted.push_back(penalty(5e5, d, 0.6));
  const std::vector<Physics> earlier{penalty(5e5, 2, 0.6), penalty(1e6, 2, 0.6)};
  const auto stage =
      shaketable::extension_stage(simulate(fitted), planted_outcomes(), fitted, earlier, {}, wide_limits(), true);
  for (const std::string& m : stage.moves) EXPECT_NE(m.rfind("mu ", 0), 0u) << m;
  bool seen = false;
  for (const ParameterReport& p : stage.parameters) {
    if (p.name == "mu") {
      seen = true;
      EXPECT_EQ(p.status, EdgeStatus::fixed);
    }
  }
  EXPECT_TRUE(seen);
}

TEST(DesignExtension, LapseExtendsToItsOptimumOrItsLimits) {
  const std::vector<Physics> one{penalty(kPlantedStiffness, kPlantedDamping, 0.6)};
  const calibration::OutcomeGrid grid = simulate(one);
  std::vector<int> y = planted_outcomes();
  const shaketable::Range limits{0.0, 0.5};
  // the planted model explains every outcome: the lapse walks down to 0, its limit
  auto exact = shaketable::extend_lapses(grid, y, {}, limits);
  EXPECT_EQ(exact.report.value, 0.0);
  EXPECT_EQ(exact.report.status, EdgeStatus::at_physical_limit);
  // one outcome in eight flipped: a lapse of 2/8 (half of a lapse's coin tosses flip), interior
  for (std::size_t t = 0; t < y.size(); t += 8) y[t] = 1 - y[t];
  auto noisy = shaketable::extend_lapses(grid, y, {}, limits);
  EXPECT_EQ(noisy.report.status, EdgeStatus::interior);
  EXPECT_GE(noisy.report.value, 0.2);
  EXPECT_LE(noisy.report.value, 0.3);
  // outcomes the model gets all wrong: the lapse climbs to its limit, 0.5, and no further
  for (int& o : y) o = 1 - o;
  auto wrong = shaketable::extend_lapses(grid, y, {}, limits);
  EXPECT_EQ(wrong.report.value, 0.5);
  EXPECT_EQ(wrong.report.status, EdgeStatus::at_physical_limit);
  EXPECT_EQ(wrong.search.lapses.back(), 0.5);
}

TEST(DesignExtension, StiffnessLimitsOfARock) {
  // a 20 kg block of bounding radius 0.2 m on a base of half-width 0.01 m: Hertz sinkage
  // (m g / K)^(2/3) = 0.01 m at K = m g / 0.01^1.5, and 1 um at K = m g / 1e-9
  dynamics::BodyDef rock;
  rock.shape.mass = 20;
  rock.shape.inertia = Vec3(0.3, 0.3, 0.2);
  rock.shape.bounding_radius = 0.2;
  rock.shape.vertices = {Vec3(0.05, 0.05, -0.15), Vec3(-0.05, -0.05, -0.15), Vec3(0.1, 0, 0.15)};
  dynamics::BodyDef table;
  table.fixed = true;
  const std::vector<dynamics::BodyDef> bodies{table, rock};
  const double weight = 20 * kGravity;
  const shaketable::Range k = shaketable::stiffness_limits(bodies, 0.01);
  EXPECT_NEAR(k.high, weight / 1e-9, 1e-6 * weight / 1e-9);
  EXPECT_NEAR(k.low, weight / std::pow(0.01, 1.5), 1e-12 * weight / std::pow(0.01, 1.5));
  // a wide base sinks nowhere near its half-width: the design's floor of 1e5 decides (the penalty
  // step, stable for any K_N, bounds nothing)
  EXPECT_EQ(shaketable::stiffness_limits(bodies, 10.0).low, 1e5);
}
