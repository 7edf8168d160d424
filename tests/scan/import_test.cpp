// The scan import on a box the test writes: its volume and mass, its placement, and its rocking
// parameters against the closed forms of a rectangular block (Housner 1963), and the scene it
// writes read back by io; a failed import leaves nothing behind.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "rigid/core/error.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/scan/import.hpp"

namespace rigid::scan {
namespace {

namespace fs = std::filesystem;

class ScanImport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rigid_scan_import_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // An OBJ of the box [x0, x0 + a] x [y0, y0 + b] x [z0, z0 + c], facets outward.
  std::string write_box(double x0, double y0, double z0) {
    const std::string path = (dir_ / "box.obj").string();
    std::ofstream f(path);
    for (int i = 0; i < 8; ++i) {  // corner 4i + 2j + k at (x0 + i a, y0 + j b, z0 + k c)
      f << "v " << x0 + a * (i >> 2) << " " << y0 + b * ((i >> 1) & 1) << " " << z0 + c * (i & 1) << "\n";
    }
    f << "f 1 3 7\nf 1 7 5\nf 2 6 8\nf 2 8 4\nf 1 2 4\nf 1 4 3\n"
         "f 5 7 8\nf 5 8 6\nf 1 5 6\nf 1 6 2\nf 3 4 8\nf 3 8 7\n";
    return path;
  }
  const double a = 0.4, b = 0.3, c = 1.0;  // unit: m
  fs::path dir_;
};

TEST_F(ScanImport, ABoxHasItsClosedFormVolumeMassPlacementAndRockingParameters) {
  ImportOptions o;
  o.scan = write_box(2.0, -1.0, 5.0);
  o.out = (dir_ / "out" / "box").string();
  o.density = 2000;
  const ImportResult r = import_scan(o);

  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(r.scene_warnings.empty());
  EXPECT_EQ(r.scan_facets, 12u);
  ASSERT_EQ(r.bodies.size(), 1u);  // the rock; the pedestal is a box
  // the mesh readers keep single precision (assimp): 1e-6 relative
  EXPECT_NEAR(r.bodies[0].mesh_volume, a * b * c, 1e-6 * a * b * c);
  EXPECT_NEAR(r.bodies[0].contact_volume, a * b * c, 1e-6 * a * b * c);  // a box is its own hull
  // the base at z = 0 over the origin
  EXPECT_NEAR((r.shift - Vec3(-2.0 - a / 2, 1.0 - b / 2, -5.0)).norm(), 0, 1e-6);
  // Housner's block: tan(alpha) = b / c on its narrow side, R the half-diagonal, p = sqrt(3 g / 4 R)
  ASSERT_TRUE(r.rocking.has_value());
  const double R = 0.5 * std::hypot(b, c);
  EXPECT_NEAR(r.rocking->alpha, std::atan(b / c), 2e-3);
  EXPECT_NEAR(r.rocking->radius, R, 2e-3);
  EXPECT_NEAR(r.rocking->p, std::sqrt(3 * kGravity / (4 * R)), 1e-2);

  const std::string scene_path = o.out + ".toml";
  for (const char* suffix : {".toml", ".state.toml", ".import.json", "_rock.stl", "_pedestal.stl"}) {
    EXPECT_NE(std::find(r.written.begin(), r.written.end(), o.out + suffix), r.written.end()) << suffix;
  }
  const scenario::Scene scene = io::load_scene(scene_path);
  ASSERT_EQ(scene.bodies.size(), 2u);
  const auto rock =
      std::find_if(scene.bodies.begin(), scene.bodies.end(), [](const auto& body) { return !body.fixed; });
  ASSERT_NE(rock, scene.bodies.end());
  EXPECT_NEAR(rock->shape.mass, a * b * c * 2000, 1e-6 * a * b * c * 2000);  // the STL is single precision
  EXPECT_NEAR(rock->position.z(), c / 2, 1e-3);                              // settled on the pedestal's top at z = 0
}

TEST_F(ScanImport, AFailedImportLeavesNothingBehind) {
  ImportOptions o;
  o.scan = write_box(0, 0, 0);
  o.scale = 1e-3;  // a 0.4 mm block: the scene it writes is refused when read back to settle
  o.out = (dir_ / "new" / "box").string();
  EXPECT_THROW(import_scan(o), InputError);
  EXPECT_FALSE(fs::exists(dir_ / "new"));

  o.scale = 1;
  o.scan = (dir_ / "absent.obj").string();
  try {
    import_scan(o);
    ADD_FAILURE() << "an absent scan was imported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.obj"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "new"));
}

}  // namespace
}  // namespace rigid::scan
