// find_self_intersection: crossing facets found whatever the mix of facet sizes, none reported on
// a clean closed surface. Oracle: the construction (a sphere is embedded; a plane through its
// centre crosses it along a great circle).
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <utility>
#include <vector>

#include "rigid/geometry/contact_shape.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {
namespace {

// Unit sphere: an octahedron subdivided `levels` times, vertices pushed onto the sphere
// (8 * 4^levels facets, outward).
ClosedMesh sphere(int levels) {
  ClosedMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      if (const auto it = midpoint.find(key); it != midpoint.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return midpoint[key] = int(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : m.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    m.triangles = std::move(finer);
  }
  return m;
}

int add_triangle(ClosedMesh& m, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int first = int(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {a, b, c});
  m.triangles.push_back({first, first + 1, first + 2});
  return int(m.triangles.size()) - 1;
}

TEST(SelfIntersection, FineSphereHasNone) {
  const ClosedMesh m = sphere(6);  // 32768 facets
  EXPECT_EQ(find_self_intersection(m), (std::array<int, 2>{-1, -1}));
}

TEST(SelfIntersection, LargeFacetThroughAFineSphereIsFound) {
  ClosedMesh m = sphere(6);
  // one facet 60 times the sphere's facets across, slanted so its box spans the whole mesh (the
  // grid must coarsen for it), through the centre: it crosses the sphere along a great circle
  const int big = add_triangle(m, {-3, -3, -3}, {3, -3, 3}, {0, 3, 0});
  const std::array<int, 2> found = find_self_intersection(m);
  ASSERT_NE(found[0], -1);
  EXPECT_EQ(found[1], big);
}

TEST(SelfIntersection, LargeFacetBesideTheSphereIsNot) {
  ClosedMesh m = sphere(6);
  add_triangle(m, {-3, -3, 1.5}, {3, -3, 4}, {0, 3, 2.5});  // above the sphere everywhere
  EXPECT_EQ(find_self_intersection(m), (std::array<int, 2>{-1, -1}));
}

TEST(SelfIntersection, SmallFacetPiercingOneSphereFacetIsFound) {
  ClosedMesh m = sphere(5);
  // a sliver through the surface near the north pole, far smaller than the sphere's facets
  const int sliver = add_triangle(m, {0.01, 0.01, 0.99}, {0.012, 0.01, 1.01}, {0.01, 0.012, 1.005});
  const std::array<int, 2> found = find_self_intersection(m);
  ASSERT_NE(found[0], -1);
  EXPECT_EQ(found[1], sliver);
}

}  // namespace
}  // namespace rigid::geometry
