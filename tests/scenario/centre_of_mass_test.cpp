// A block's centre of mass moved off its centroid (scenario::offset_centre_of_mass, a scene's
// [centre_of_mass_offset]): the mesh stays where it was, and the quasi-static toppling
// acceleration of a rectangular block follows rigid statics, g s / h with s the horizontal
// distance from the centre of mass to the pivot edge and h its height above the base.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/analysis/tilt_test.hpp"
#include "rigid/core/error.hpp"
#include "rigid/geometry/polyhedron.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/stl.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {
using namespace library;
using namespace analysis;
namespace {

constexpr double kB = 0.2, kH = 0.5, kDepth = 0.4;  // block 0.4 wide, 1.0 tall: tan alpha = 0.4

std::vector<Vec3> world_vertices(const dynamics::BodyDef& b) {
  std::vector<Vec3> out;
  for (const Vec3& v : b.shape.vertices) out.push_back(b.position + b.orientation * v);
  return out;
}

TEST(CentreOfMass, OffsetMovesTheMassCentreAndKeepsTheMesh) {
  Scene scene = block_on_pedestal(kB, kH, kDepth);
  dynamics::BodyDef& block = scene.bodies[1];
  const std::vector<Vec3> before = world_vertices(block);
  const Vec3 centroid = block.position;
  const Vec3 inertia = block.shape.inertia;
  const Vec3 offset(0.05, -0.03, 0.1);
  offset_centre_of_mass(block, offset);
  EXPECT_LT((block.position - (centroid + offset)).norm(), 1e-12);
  const std::vector<Vec3> after = world_vertices(block);
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_LT((after[i] - before[i]).norm(), 1e-12) << i;
  EXPECT_EQ(block.shape.inertia, inertia);
  // every face plane still passes through its vertices in the shifted frame
  for (const auto& f : block.shape.faces) {
    for (int v : f.vertices) EXPECT_NEAR(f.normal.dot(block.shape.vertices[v]), f.offset, 1e-12);
  }
  EXPECT_THROW(offset_centre_of_mass(block, Vec3(0.3, 0, 0)), std::invalid_argument);  // beyond the 0.2 half-width
  EXPECT_THROW(offset_centre_of_mass(scene.bodies[0], Vec3(0.01, 0, 0)), std::invalid_argument);  // the pedestal
}

TEST(CentreOfMass, TiltTestFollowsRigidStatics) {
  TiltTestSettings settings;
  settings.relative_tolerance = 0.002;
  struct Case {
    Vec3 offset;
    double azimuth, statics;
  };
  // ground acceleration along +x: the block pivots over its -x edge, b + dx from the mass centre
  const double d = 0.05, dz = 0.1;
  const Case cases[] = {
      {Vec3(d, 0, 0), 0.0, (kB + d) / kH}, {Vec3(d, 0, 0), kPi, (kB - d) / kH}, {Vec3(0, 0, dz), 0.0, kB / (kH + dz)}};
  for (const Case& c : cases) {
    Scene scene = block_on_pedestal(kB, kH, kDepth);
    offset_centre_of_mass(scene.bodies[1], c.offset);
    const TiltTestResult r = tilt_test(scene, c.azimuth, settings);
    std::printf("offset (%.2f, %.2f, %.2f) azimuth %.0f deg: %.4f g, statics %.4f g\n", c.offset.x(), c.offset.y(),
                c.offset.z(), c.azimuth * 180 / kPi, r.acceleration, c.statics);
    EXPECT_NEAR(r.acceleration / c.statics, 1.0, 0.01);
  }
}

TEST(CentreOfMass, RockingParametersFollowTheMassCentre) {
  // azimuth 0 (ground acceleration +x) leans the block over its -x edge, azimuth 180 over its +x
  // edge: tan alpha = (b + d) / h and (b - d) / h; the weakest direction turns to +x
  Scene scene = block_on_pedestal(kB, kH, kDepth);
  const double d = 0.05;
  offset_centre_of_mass(scene.bodies[1], Vec3(d, 0, 0));
  const auto p = rocking_parameters(scene);
  ASSERT_TRUE(p.has_value());
  const std::size_t n = p->alpha_by_azimuth.size();
  ASSERT_EQ(n % 2, 0u);
  EXPECT_NEAR(p->alpha_by_azimuth[0], std::atan((kB + d) / kH), 1e-9);
  EXPECT_NEAR(p->alpha_by_azimuth[n / 2], std::atan((kB - d) / kH), 1e-9);
  EXPECT_NEAR(p->alpha, std::atan((kB - d) / kH), 1e-9);
}

class SceneOffset : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("rigid_com_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    io::write_stl_binary((dir_ / "pedestal.stl").string(),
                         geometry::box_soup(Vec3(-0.3, -0.3, -0.2), Vec3(0.3, 0.3, 0)));
    io::write_stl_binary((dir_ / "rock.stl").string(),
                         geometry::box_soup(Vec3(-kB, -kDepth / 2, 0), Vec3(kB, kDepth / 2, 2 * kH)));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string scene(const std::string& offset_table) {
    const std::string path = (dir_ / "scene.toml").string();
    std::ofstream(path) << "[[block]]\nstl = \"pedestal.stl\"\nfixed = true\n\n[[block]]\nstl = \"rock.stl\"\n\n"
                        << offset_table;
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(SceneOffset, SceneFileOffsetsTheBlockAndStatesKeepTheCentroid) {
  const Scene plain = io::load_scene(scene(""));
  const Scene shifted = io::load_scene(scene("[centre_of_mass_offset]\nrock = [0.05, 0.0, 0.1]\n"));
  EXPECT_LT((shifted.bodies[1].position - plain.bodies[1].position - Vec3(0.05, 0, 0.1)).norm(), 1e-12);
  // a state saved from the shifted scene holds the centroid, so the plain scene reads it unchanged
  const std::string state = (dir_ / "state.toml").string();
  io::save_state(state, shifted);
  Scene again = io::load_scene(scene(""));
  io::apply_state(state, again);
  EXPECT_LT((again.bodies[1].position - plain.bodies[1].position).norm(), 1e-12);
  Scene shifted_again = io::load_scene(scene("[centre_of_mass_offset]\nrock = [0.05, 0.0, 0.1]\n"));
  io::apply_state(state, shifted_again);
  EXPECT_LT((shifted_again.bodies[1].position - shifted.bodies[1].position).norm(), 1e-12);
}

TEST_F(SceneOffset, BadOffsetsNameTheLine) {
  auto message = [&](const std::string& table) {
    try {
      io::load_scene(scene(table));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("[centre_of_mass_offset]\nboulder = [0.0, 0.0, 0.1]\n")
                .find("scene.toml:9: centre_of_mass_offset: the scene has no block 'boulder'"),
            std::string::npos)
      << message("[centre_of_mass_offset]\nboulder = [0.0, 0.0, 0.1]\n");
  EXPECT_NE(message("[centre_of_mass_offset]\nrock = [0.5, 0.0, 0.0]\n").find("outside the block"), std::string::npos);
  EXPECT_NE(message("[centre_of_mass_offset]\nrock = [0.1, 0.0]\n").find("needs 3 numbers"), std::string::npos);
  EXPECT_NE(message("[centre_of_mass_offset]\npedestal = [0.01, 0.0, 0.0]\n").find("fixed block"), std::string::npos);
  EXPECT_NE(message("[centre_of_mass_offset]\nrock = [nan, 0.0, 0.0]\n").find("finite"), std::string::npos);
}

}  // namespace
}  // namespace rigid::scenario
