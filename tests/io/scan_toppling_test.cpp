// The real scans as rocks on a flat pedestal: the quasi-static toppling acceleration (tilt test,
// eight azimuths, rigid contact) of the two tessellations of one rock, and of its hull against its
// convex decomposition, agree; both agree with the rigid statics of the settled rock's support
// polygon (analysis::rocking_parameters). Skipped when ../shared is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/analysis/tilt_test.hpp"
#include "rigid/geometry/contact_shape.hpp"
#include "rigid/geometry/polygon2d.hpp"
#include "rigid/io/mesh_import.hpp"
#include "rigid/library/builders.hpp"

namespace rigid {
namespace {

namespace fs = std::filesystem;

std::string scan(const char* name) { return (fs::path(RIGID_SHARED_DIR) / "scans" / name).string(); }

// The rock of a scan, base cut flat at z = 0.005, on a box pedestal 2 cm wider than its footprint; its
// contact shape is the hull (96 vertices) or a convex decomposition.
// The rigid statics of the flattened mesh itself, independent of any contact shape: its centroid
// and the 2D hull of the vertices on the cut base give a / g = s / h per azimuth.
struct MeshStatics {
  geometry::Polygon2 base;
  Vec3 centroid;
  double level = 0;
  double toppling(double azimuth) const {
    const Eigen::Vector2d lean(-std::cos(azimuth), -std::sin(azimuth));
    return geometry::ray_to_boundary(base, centroid.head<2>(), lean) / (centroid.z() - level);
  }
};
MeshStatics mesh_statics;

scenario::Scene rock_scene(const std::string& path, bool decompose) {
  std::vector<std::string> warnings;
  geometry::ClosedMesh mesh = io::read_scan(path, 1.0, Mat3::Identity(), warnings);
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 shift(-0.5 * (lo.x() + hi.x()), -0.5 * (lo.y() + hi.y()), -lo.z());
  for (Vec3& v : mesh.vertices) v += shift;
  // the cut base, rough at the millimetre scale, made flat 5 mm above its lowest point (see
  // geometry::cut_base_flat: on its raw asperities the rock rests on a noise-chosen tripod)
  geometry::cut_base_flat(mesh, 0.005);
  mesh_statics.level = 0.005;
  mesh_statics.centroid = geometry::mass_properties(mesh, 2600).centroid;
  std::vector<Eigen::Vector2d> base;
  for (const Vec3& v : mesh.vertices) {
    if (v.z() == 0.005) base.push_back(v.head<2>());
  }
  mesh_statics.base = geometry::convex_hull_2d(base);
  std::vector<geometry::ConvexPiece> pieces;
  if (decompose) {
    pieces = geometry::convex_decomposition(mesh, {}).pieces;
  } else {
    pieces.push_back(geometry::reduced_hull(mesh.vertices, 96));
  }
  std::vector<geometry::ClosedMesh> convex;
  for (const auto& p : pieces) convex.push_back(geometry::make_closed_mesh(p.soup, {}, "piece"));
  geometry::CompoundBody body = geometry::build_compound(mesh, convex, 2600, {});
  scenario::Scene scene;
  scene.law.friction = 1.5;  // tipping, not sliding: the scan topples at 0.19-1.1 g
  const Vec3 half = 0.5 * (hi - lo);
  scene.bodies.push_back(library::box_body("pedestal", Vec3(-half.x() - 0.02, -half.y() - 0.02, -0.2),
                                           Vec3(half.x() + 0.02, half.y() + 0.02, 0), 2600, true));
  dynamics::BodyDef rock;
  rock.name = "rock";
  rock.shape = std::move(body.shape);
  rock.pieces = std::move(body.pieces);
  rock.position = rock.shape.translation;
  rock.orientation = rock.shape.rotation;
  scene.bodies.push_back(std::move(rock));
  return scenario::equilibrate(scene, {});
}

TEST(ScanToppling, TwoTessellationsHullAndDecompositionToppleAlike) {
  if (!fs::exists(scan("sp1_rock.obj")) || !fs::exists(scan("sp1_rock_dense.ply")))
    GTEST_SKIP() << "../shared/scans is absent: the real scans are not part of the repository";
  const scenario::Scene ply = rock_scene(scan("sp1_rock_dense.ply"), false);
  const scenario::Scene pieces = rock_scene(scan("sp1_rock.obj"), true);
  const scenario::Scene obj = rock_scene(scan("sp1_rock.obj"), false);  // last: mesh_statics is the OBJ's
  const auto statics = analysis::rocking_parameters(obj);
  const auto statics_ply = analysis::rocking_parameters(ply);
  ASSERT_TRUE(statics && statics_ply);
  EXPECT_NEAR(statics_ply->alpha / statics->alpha, 1.0, 0.01);
  for (int k = 0; k < 8; ++k) {
    const double azimuth = 2 * kPi * k / 8;
    const double a_statics = mesh_statics.toppling(azimuth);
    analysis::TiltTestSettings settings;
    settings.max_acceleration = 1.25 * a_statics;  // what stands there is far from statics anyway
    const double a_obj = analysis::tilt_test(obj, azimuth, settings).acceleration;
    const double a_ply = analysis::tilt_test(ply, azimuth, settings).acceleration;
    const double a_pieces = analysis::tilt_test(pieces, azimuth, settings).acceleration;
    // the contact shape's own statics (rigid inspect, the cube): every 45 degrees is every other
    // one of the 16 directions
    const double a_shape = std::tan(statics->alpha_by_azimuth[2 * k]);
    std::printf(
        "azimuth %3d deg: obj %.4f g, ply %.4f g, decomposed %.4f g; statics of the mesh %.4f g, of the hull %.4f g\n",
        45 * k, a_obj, a_ply, a_pieces, a_statics, a_shape);
    EXPECT_NEAR(a_shape / a_statics, 1.0, 0.01) << k;
    EXPECT_NEAR(a_ply / a_obj, 1.0, 0.02) << k;
    EXPECT_NEAR(a_pieces / a_obj, 1.0, 0.02) << k;
    EXPECT_NEAR(a_obj / a_statics, 1.0, 0.01) << k;
  }
}

}  // namespace
}  // namespace rigid
