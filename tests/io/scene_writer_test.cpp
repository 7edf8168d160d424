// The scene writer against the scene reader: what write_scene is told must be what load_scene
// reads back (names, fixed blocks, failure rule, density through the blocks' masses), and
// impossible scenes or unwritable paths are refused without leaving a file.
#include "rigid/io/scene_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "rigid/core/error.hpp"
#include "rigid/geometry/polyhedron.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/stl.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

class SceneWriter : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rigid_scene_writer_test_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // a 2 x 2 x 0.5 m pedestal top at z = 0 and a 1 m cube on it
    write_stl_ascii((dir_ / "pedestal.stl").string(), geometry::box_soup(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), "p");
    write_stl_ascii((dir_ / "rock.stl").string(), geometry::box_soup(Vec3(-0.5, -0.5, 0), Vec3(0.5, 0.5, 1)), "r");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(SceneWriter, WhatIsWrittenIsWhatTheReaderReads) {
  SceneFile file;
  file.comments = {"a test scene", "with a line\nbreak inside one comment"};
  file.density = 2700.5;
  file.tilt_rule_deg = 25.0;
  file.blocks = {{"pedestal", "pedestal.stl", true, {}}, {"rock \"R\\1\"", "rock.stl", false, {"rock.stl"}}};
  write_scene(path("s.toml"), file);

  const scenario::Scene scene = load_scene(path("s.toml"));
  ASSERT_EQ(scene.bodies.size(), 2u);
  EXPECT_EQ(scene.bodies[0].name, "pedestal");
  EXPECT_TRUE(scene.bodies[0].fixed);
  EXPECT_EQ(scene.bodies[1].name, "rock \"R\\1\"");
  EXPECT_FALSE(scene.bodies[1].fixed);
  // a 1 m^3 cube: its mass is the density
  EXPECT_NEAR(scene.bodies[1].shape.mass, 2700.5, 1e-9 * 2700.5);
  EXPECT_EQ(scene.failure.kind, scenario::FailureRule::Kind::tilt);
  EXPECT_NEAR(scene.failure.tilt_angle, 25.0 * M_PI / 180.0, 1e-15);

  // every comment line is one line of the file, before the first table
  std::ifstream in(path("s.toml"));
  std::string first, second, third;
  std::getline(in, first);
  std::getline(in, second);
  std::getline(in, third);
  EXPECT_EQ(first, "# a test scene");
  EXPECT_EQ(second, "# with a line break inside one comment");
  EXPECT_EQ(third.rfind("[physics]", 0), 0u) << third;
}

TEST_F(SceneWriter, WithoutATiltAngleTheRuleIsBelowThePedestal) {
  SceneFile file;
  file.blocks = {{"pedestal", "pedestal.stl", true, {}}, {"rock", "rock.stl", false, {}}};
  write_scene(path("s.toml"), file);
  const scenario::Scene scene = load_scene(path("s.toml"));
  EXPECT_EQ(scene.failure.kind, scenario::FailureRule::Kind::below);
  EXPECT_NEAR(scene.bodies[1].shape.mass, 2600.0, 1e-9 * 2600.0);  // the default density
}

TEST_F(SceneWriter, AModelFileAndItsSceneReadBack) {
  write_model_file(path("m.model"), {{"pedestal", "pedestal.stl", true, {}}, {"rock", "rock.stl", false, {}}});
  SceneFile file;
  file.model = "m.model";
  write_scene(path("m.toml"), file);
  const scenario::Scene scene = load_scene(path("m.toml"));
  ASSERT_EQ(scene.bodies.size(), 2u);
  EXPECT_TRUE(scene.bodies[0].fixed);
  EXPECT_FALSE(scene.bodies[1].fixed);
  EXPECT_NEAR(scene.bodies[1].shape.mass, 2600.0, 1e-9 * 2600.0);
}

TEST_F(SceneWriter, ImpossibleScenesAreRefusedAndLeaveNoFile) {
  SceneFile none;  // neither blocks nor a model
  EXPECT_THROW(write_scene(path("a.toml"), none), InputError);
  SceneFile bad;
  bad.blocks = {{"rock", "rock.stl", false, {}}};
  bad.density = std::nan("");
  EXPECT_THROW(write_scene(path("b.toml"), bad), InputError);
  bad.density = 2600;
  bad.tilt_rule_deg = 95;
  EXPECT_THROW(write_scene(path("c.toml"), bad), InputError);
  EXPECT_THROW(write_model_file(path("d.model"), {}), InputError);
  for (const char* name : {"a.toml", "b.toml", "c.toml", "d.model"}) EXPECT_FALSE(fs::exists(path(name))) << name;
}

TEST_F(SceneWriter, AnUnwritablePathIsAnInputErrorNamingIt) {
  SceneFile file;
  file.blocks = {{"rock", "rock.stl", false, {}}};
  const std::string where = path("no/such/folder/s.toml");
  try {
    write_scene(where, file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rigid::io
