// Rocking parameters of single-block scenes against the closed forms of a rectangular block
// (physics.md §2: tan alpha = b / h, p^2 = 3 g / (4 R)) and of a block that rests on a smaller
// pedestal top (the support polygon is the overlap, not the block's base).
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/library/builders.hpp"

namespace rigid::scenario {
using namespace library;
using namespace analysis;
namespace {

TEST(RockingParameters, RectangularBlockMatchesHousnerClosedForms) {
  for (const double alpha : {0.1, 0.2, 0.3, 0.4}) {
    const double h = 0.5, b = h * std::tan(alpha), depth = 0.5;
    const Scene scene = block_on_pedestal(b, h, depth);
    const auto r = rocking_parameters(scene);
    ASSERT_TRUE(r.has_value()) << alpha;
    const double radius = std::hypot(b, h);
    EXPECT_NEAR(r->alpha, alpha, 1e-9) << alpha;
    EXPECT_NEAR(r->radius, radius, 1e-9) << alpha;
    EXPECT_NEAR(r->p, std::sqrt(3 * kGravity / (4 * radius)), 1e-9) << alpha;
    // the weakest direction is across the narrow width (+x or -x)
    EXPECT_NEAR(std::abs(std::cos(r->azimuth)), 1.0, 1e-9) << alpha;
  }
}

TEST(RockingParameters, DeepBlockTipsAcrossItsShorterSide) {
  // 0.6 wide in x, 0.2 deep in y: it tips about an edge along x, towards +-y
  const Scene scene = block_on_pedestal(0.3, 0.5, 0.2);
  const auto r = rocking_parameters(scene);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->alpha, std::atan2(0.1, 0.5), 1e-9);
  EXPECT_NEAR(std::abs(std::sin(r->azimuth)), 1.0, 1e-9);
}

TEST(RockingParameters, YawedBlockKeepsItsParameters) {
  Scene scene = block_on_pedestal(0.1, 0.5, 0.5);
  const auto straight = rocking_parameters(scene);
  const Quat yaw(Eigen::AngleAxisd(0.7, Vec3::UnitZ()));
  for (auto& body : scene.bodies) {
    body.position = yaw * body.position;
    body.orientation = yaw * body.orientation;
  }
  const auto turned = rocking_parameters(scene);
  ASSERT_TRUE(straight && turned);
  EXPECT_NEAR(turned->alpha, straight->alpha, 1e-9);
  EXPECT_NEAR(turned->p, straight->p, 1e-9);
}

TEST(RockingParameters, NarrowPedestalTopSetsTheSupportPolygon) {
  // a 1 m cube on a pedestal 0.4 m wide and 0.3 m deep: it rests on the pedestal's top, so it
  // tips over the pedestal's long edges, d = 0.15 m below a centroid 0.5 m up
  Scene scene;
  scene.bodies.push_back(box_body("pedestal", Vec3(-0.2, -0.15, -1), Vec3(0.2, 0.15, 0), 2600, true));
  scene.bodies.push_back(box_body("block", Vec3(-0.5, -0.5, 0), Vec3(0.5, 0.5, 1), 2600, false));
  const auto r = rocking_parameters(scene);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->alpha, std::atan2(0.15, 0.5), 1e-9);
  // I about the edge: the cube's centroidal m/6 (side 1 m) plus m R^2
  const double radius = std::hypot(0.15, 0.5);
  EXPECT_NEAR(r->p, std::sqrt(kGravity * radius / (1.0 / 6.0 + radius * radius)), 1e-9);
}

TEST(RockingParameters, AlphaByAzimuthIsTheRayToTheBaseOverTheHeight) {
  // 0.4 wide (x), 0.6 deep (y), centroid 0.5 up: pushed along azimuth theta the block leans
  // towards -theta and its resultant leaves the base rectangle after s = min(b/|cos|, d/|sin|)
  const double b = 0.2, d = 0.3, h = 0.5;
  const Scene scene = block_on_pedestal(b, h, 2 * d);
  const auto r = rocking_parameters(scene);
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->alpha_by_azimuth.size(), std::size_t(kRockingAzimuths));
  for (int k = 0; k < kRockingAzimuths; ++k) {
    const double theta = 2 * kPi * k / kRockingAzimuths;
    const double c = std::abs(std::cos(theta)), s = std::abs(std::sin(theta));
    const double reach = std::min(c > 1e-12 ? b / c : 1e300, s > 1e-12 ? d / s : 1e300);
    EXPECT_NEAR(r->alpha_by_azimuth[k], std::atan2(reach, h), 1e-9) << k;
    EXPECT_GE(r->alpha_by_azimuth[k], r->alpha - 1e-12) << k;
  }
  // the support polygon is the base: four corners at (+-b, +-d) around the centroid
  ASSERT_EQ(r->support_polygon.size(), 4u);
  for (const auto& corner : r->support_polygon) {
    EXPECT_NEAR(std::abs(corner.x()), b, 1e-12);
    EXPECT_NEAR(std::abs(corner.y()), d, 1e-12);
  }
}

TEST(RockingParameters, StacksAndFloatingBlocksHaveNone) {
  Scene stack = block_on_pedestal(0.2, 0.5, 0.4);
  stack.bodies.push_back(box_body("top", Vec3(-0.2, -0.2, 1.0), Vec3(0.2, 0.2, 1.4), 2600, false));
  EXPECT_FALSE(rocking_parameters(stack).has_value());
  Scene floating = block_on_pedestal(0.2, 0.5, 0.4);
  for (auto& body : floating.bodies) {
    if (!body.fixed) body.position.z() += 0.1;
  }
  EXPECT_FALSE(rocking_parameters(floating).has_value());
}

}  // namespace
}  // namespace rigid::scenario
