// Splitting a closed mesh by a horizontal plane: each part is a closed, outward mesh, and the
// parts' volumes, centroids and the cut's area follow from the shapes' closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "rigid/geometry/contact_shape.hpp"
#include "rigid/geometry/mesh_split.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {
namespace {

ClosedMesh closed(const TriangleSoup& soup) {
  MeshOptions options;
  options.require_convex = false;
  return make_closed_mesh(soup, options, "part");
}

TEST(MeshSplit, BoxSplitsIntoTwoBoxes) {
  const ClosedMesh box = closed(box_soup(Vec3(-0.3, -0.2, 0), Vec3(0.3, 0.2, 1.0)));
  const SplitMesh parts = split_by_plane(box, 0.25);
  EXPECT_EQ(parts.level, 0.25);
  const MassProperties above = mass_properties(closed(parts.above), 1.0);
  const MassProperties below = mass_properties(closed(parts.below), 1.0);
  EXPECT_NEAR(above.volume, 0.6 * 0.4 * 0.75, 1e-12);
  EXPECT_NEAR(below.volume, 0.6 * 0.4 * 0.25, 1e-12);
  EXPECT_NEAR(above.centroid.z(), 0.625, 1e-12);
  EXPECT_NEAR(below.centroid.z(), 0.125, 1e-12);
}

// A U (three boxes' outline, x-z) extruded along y: 1 x 1 with a 0.4 x 0.7 notch from the top.
ClosedMesh u_shape() {
  const std::vector<Eigen::Vector2d> u{{0, 0}, {1, 0}, {1, 1}, {0.7, 1}, {0.7, 0.3}, {0.3, 0.3}, {0.3, 1}, {0, 1}};
  TriangleSoup soup;
  const double y0 = 0, y1 = 0.5;
  auto at = [&](int i, double y) { return Vec3(u[i].x(), y, u[i].y()); };
  // caps: the U as four rectangles' fans around its reflex corners 4 and 5
  const int caps[][3] = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 7}};
  for (const auto& t : caps) {
    soup.push_back({at(t[0], y0), at(t[1], y0), at(t[2], y0)});
    soup.push_back({at(t[0], y1), at(t[2], y1), at(t[1], y1)});
  }
  for (int i = 0; i < 8; ++i) {
    const int j = (i + 1) % 8;
    soup.push_back({at(i, y0), at(j, y1), at(j, y0)});
    soup.push_back({at(i, y0), at(i, y1), at(j, y1)});
  }
  return closed(soup);
}

TEST(MeshSplit, ConcaveCrossSectionIsCappedExactly) {
  // cut through both arms: two arm stubs above, the U's base and the arms' roots below; volumes
  // from the outline's areas
  const ClosedMesh mesh = u_shape();
  const double whole = mass_properties(mesh, 1.0).volume;
  ASSERT_NEAR(std::abs(whole), (1.0 - 0.4 * 0.7) * 0.5, 1e-12);
  const SplitMesh parts = split_by_plane(mesh, 0.6);
  // above: the two arm stubs, two closed parts (soup_volume sums any closed soup)
  const double above = soup_volume(parts.above);
  const double below = mass_properties(closed(parts.below), 1.0).volume;
  EXPECT_NEAR(above, 2 * 0.3 * 0.4 * 0.5, 1e-12);  // two arms 0.3 wide, 0.4 above the cut
  EXPECT_NEAR(above + below, std::abs(whole), 1e-12);
}

TEST(MeshSplit, PlaneOffTheMeshIsRefused) {
  const ClosedMesh box = closed(box_soup(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  EXPECT_THROW(split_by_plane(box, 2.0), std::invalid_argument);
  // a plane through vertices (the notch's floor at z = 0.3) moves off them, by micrometres
  const ClosedMesh u = u_shape();
  const SplitMesh parts = split_by_plane(u, 0.3);
  EXPECT_NE(parts.level, 0.3);
  EXPECT_NEAR(parts.level, 0.3, 1e-5);
  EXPECT_NEAR(soup_volume(parts.above) + mass_properties(closed(parts.below), 1.0).volume,
              mass_properties(u, 1.0).volume, 1e-12);
}

}  // namespace
}  // namespace rigid::geometry
