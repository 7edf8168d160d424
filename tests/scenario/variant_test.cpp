// Variants of a scene (scenario/variant.hpp): the designs sample what they promise (a Latin
// hypercube uses every stratum of every range once; a grid is the full factorial), and each
// parameter changes the physics as closed forms say: rigid statics for a moved centre of mass,
// similitude for size (alpha kept, p ~ 1/sqrt(s)), mass proportional to density.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/analysis/tilt_test.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/scenario/variant.hpp"

namespace rigid::scenario {
using namespace library;
using namespace analysis;
namespace {

constexpr double kB = 0.2, kH = 0.5, kDepth = 0.4;  // block 0.4 wide, 1.0 tall: tan alpha = 0.4

VariantSpace one(VariantKey key, double value) {
  VariantSpace s;
  s.method = "list";
  s.keys = {key};
  s.variants = {{VariantValue{value, "", std::nullopt}}};
  return s;
}

TEST(VariantDesign, LatinHypercubeUsesEveryStratumOnce) {
  const std::vector<VariantDomain> domains{
      {VariantKey::friction, 0.4, 0.9, false, {}},
      {VariantKey::normal_stiffness, 1e7, 1e9, true, {}},
      {VariantKey::contact,
       0,
       0,
       false,
       {{0, "rigid", contact::ContactMethod::rigid}, {0, "penalty", contact::ContactMethod::penalty}}}};
  const int n = 20;
  const VariantSpace s = latin_hypercube(domains, n, 42);
  ASSERT_EQ(s.count(), n);
  std::set<int> friction_strata, stiffness_strata;
  int rigid = 0;
  for (const auto& row : s.variants) {
    const double u_friction = (row[0].number - 0.4) / 0.5;
    const double u_stiffness = (std::log(row[1].number) - std::log(1e7)) / (std::log(1e9) - std::log(1e7));
    friction_strata.insert(int(std::floor(u_friction * n)));
    stiffness_strata.insert(int(std::floor(u_stiffness * n)));
    rigid += row[2].text == "rigid";
  }
  EXPECT_EQ(friction_strata.size(), std::size_t(n));  // each of the n strata exactly once
  EXPECT_EQ(stiffness_strata.size(), std::size_t(n));
  EXPECT_EQ(*friction_strata.begin(), 0);
  EXPECT_EQ(*friction_strata.rbegin(), n - 1);
  EXPECT_EQ(rigid, n / 2);  // a list of two is split evenly
  // counter-based: the same seed gives the same design, another seed another pairing
  const VariantSpace again = latin_hypercube(domains, n, 42);
  const VariantSpace other = latin_hypercube(domains, n, 43);
  int same = 0;
  for (int v = 0; v < n; ++v) {
    EXPECT_EQ(again.variants[v][0].number, s.variants[v][0].number);
    same += other.variants[v][0].number == s.variants[v][0].number;
  }
  EXPECT_LT(same, n);
}

TEST(VariantDesign, GridIsTheFullFactorial) {
  const std::vector<VariantDomain> domains{
      {VariantKey::friction, 0.5, 0.9, false, {}},
      {VariantKey::com_offset_x,
       0,
       0,
       false,
       {{-0.01, "", std::nullopt}, {0.0, "", std::nullopt}, {0.02, "", std::nullopt}, {0.03, "", std::nullopt}}}};
  EXPECT_EQ(grid_size(domains, 3), 12.0);
  const VariantSpace s = grid_design(domains, 3);
  ASSERT_EQ(s.count(), 12);
  std::set<std::pair<double, double>> pairs;
  for (const auto& row : s.variants) pairs.insert({row[0].number, row[1].number});
  EXPECT_EQ(pairs.size(), 12u);
  EXPECT_DOUBLE_EQ(s.variants.front()[0].number, 0.5);
  EXPECT_DOUBLE_EQ(s.variants.back()[0].number, 0.9);
  EXPECT_DOUBLE_EQ(s.variants[4][0].number, 0.7);  // the first parameter varies slowest
}

TEST(VariantPhysics, CentreOfMassOffsetMovesTheTiltTestByRigidStatics) {
  // ground acceleration towards -x (azimuth 180 deg) leans the block over its +x edge, b - d from
  // a mass centre moved by d along +x: a/g = (b - d)/h
  TiltTestSettings settings;
  settings.relative_tolerance = 0.002;
  for (double d : {0.04, -0.04}) {
    Scene scene = block_on_pedestal(kB, kH, kDepth);
    apply_variant(one(VariantKey::com_offset_x, d), 0, scene);
    const TiltTestResult r = tilt_test(scene, kPi, settings);
    std::printf("offset %.2f m: tilt test %.4f g, statics %.4f g\n", d, r.acceleration, (kB - d) / kH);
    EXPECT_NEAR(r.acceleration / ((kB - d) / kH), 1.0, 0.01);
  }
}

TEST(VariantPhysics, SizeScaleIsASimilitude) {
  const Scene base = block_on_pedestal(kB, kH, kDepth);
  const auto before = rocking_parameters(base);
  ASSERT_TRUE(before.has_value());
  for (double s : {0.5, 2.0}) {
    Scene scene = base;
    apply_variant(one(VariantKey::size_scale, s), 0, scene);
    const auto after = rocking_parameters(scene);
    ASSERT_TRUE(after.has_value());
    EXPECT_NEAR(after->alpha, before->alpha, 1e-12);        // shape unchanged
    EXPECT_NEAR(after->radius, s * before->radius, 1e-12);  // lengths scale
    EXPECT_NEAR(after->p, before->p / std::sqrt(s), 1e-9);  // p = sqrt(3 g / 4 R) for a rectangle
    EXPECT_NEAR(after->p, std::sqrt(3 * kGravity / (4 * s * before->radius)), 1e-9);
    EXPECT_NEAR(scene.bodies[1].shape.mass, s * s * s * base.bodies[1].shape.mass, 1e-9 * base.bodies[1].shape.mass);
    // the block still rests on the pedestal: its lowest vertex meets the pedestal's top
    double block_bottom = 1e9, pedestal_top = -1e9;
    for (const Vec3& v : scene.bodies[1].shape.vertices)
      block_bottom = std::min(block_bottom, (scene.bodies[1].position + scene.bodies[1].orientation * v).z());
    for (const Vec3& v : scene.bodies[0].shape.vertices)
      pedestal_top = std::max(pedestal_top, (scene.bodies[0].position + scene.bodies[0].orientation * v).z());
    EXPECT_NEAR(block_bottom, pedestal_top, 1e-12);
  }
}

TEST(VariantPhysics, DensityScalesMassAndInertiaOnly) {
  const Scene base = block_on_pedestal(kB, kH, kDepth);
  Scene scene = base;
  apply_variant(one(VariantKey::density, 2 * base.density), 0, scene);
  EXPECT_NEAR(scene.bodies[1].shape.mass, 2 * base.bodies[1].shape.mass, 1e-9);
  EXPECT_NEAR(scene.bodies[1].shape.inertia.x(), 2 * base.bodies[1].shape.inertia.x(), 1e-9);
  EXPECT_NEAR(rocking_parameters(scene)->p, rocking_parameters(base)->p, 1e-12);  // p does not depend on density
}

TEST(VariantPhysics, ContactLawParameters) {
  Scene scene = block_on_pedestal(kB, kH, kDepth);
  VariantSpace s;
  s.keys = {VariantKey::friction, VariantKey::restitution, VariantKey::contact};
  s.variants = {{VariantValue{0.35, "", std::nullopt}, VariantValue{0.2, "", std::nullopt},
                 VariantValue{0, "penalty", contact::ContactMethod::penalty}}};
  apply_variant(s, 0, scene);
  EXPECT_EQ(scene.law.friction, 0.35);
  EXPECT_EQ(scene.law.restitution, 0.2);
  EXPECT_EQ(scene.law.method, contact::ContactMethod::penalty);
  Scene outside = block_on_pedestal(kB, kH, kDepth);
  EXPECT_THROW(apply_variant(one(VariantKey::com_offset_x, 0.3), 0, outside), std::invalid_argument);
}

TEST(VariantCatalogue, AdmittedValues) {
  EXPECT_TRUE(variant_value_problem(*find_variant_parameter("friction"), -0.1).has_value());
  EXPECT_TRUE(variant_value_problem(*find_variant_parameter("friction"), 0.0).has_value());
  EXPECT_FALSE(variant_value_problem(*find_variant_parameter("friction"), 0.6).has_value());
  EXPECT_TRUE(variant_value_problem(*find_variant_parameter("restitution"), 1.5).has_value());
  EXPECT_TRUE(variant_value_problem(*find_variant_parameter("size_scale"), std::nan("")).has_value());
  EXPECT_FALSE(variant_value_problem(*find_variant_parameter("com_offset_x_m"), -0.02).has_value());
  EXPECT_EQ(find_variant_parameter("viscosity"), nullptr);
}

}  // namespace
}  // namespace rigid::scenario
