// convex_hull and box_soup: containment, extremality, degenerate inputs, determinism.
// Its speed is a benchmark: tests/bench/hull_bench.cpp.
#include <gtest/gtest.h>

#include "support/rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rigid/geometry/polyhedron.hpp"

namespace {

using rigid::Vec3;
using namespace rigid::geometry;

using rigid::test::Rng;
using rigid::test::unit_ball_points;

bool contains(const std::vector<Vec3>& pts, const Vec3& v) { return std::find(pts.begin(), pts.end(), v) != pts.end(); }

// Containment oracle: every input point lies on or below every outward facet plane.
void expect_contains_all(const TriangleSoup& hull, const std::vector<Vec3>& pts, double tol) {
  for (const auto& t : hull) {
    const Vec3 n = (t.b - t.a).cross(t.c - t.a).normalized();
    for (const Vec3& p : pts) ASSERT_LE(n.dot(p - t.a), tol);
  }
}

TEST(ConvexHull, RandomBallHullContainsEveryPointAndUsesOnlyInputPoints) {
  const std::vector<Vec3> pts = unit_ball_points(1, 400);
  const TriangleSoup hull = convex_hull(pts);
  expect_contains_all(hull, pts, 1e-7);
  for (const auto& t : hull) {
    EXPECT_TRUE(contains(pts, t.a) && contains(pts, t.b) && contains(pts, t.c));
  }
  // a valid closed convex mesh
  const ClosedMesh m = make_closed_mesh(hull, {}, "hull");
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_EQ(m.triangles.size(), 2 * m.vertices.size() - 4);  // simplicial sphere
}

TEST(ConvexHull, PointsOnASphereAreAllHullVertices) {
  // every point is extreme, so the hull has all n vertices and 2n - 4 triangles
  std::vector<Vec3> pts = unit_ball_points(2, 500);
  for (Vec3& p : pts) p = 3.0 * p.normalized() + Vec3(100, 200, -50);
  const TriangleSoup hull = convex_hull(pts);
  EXPECT_EQ(hull.size(), 2 * pts.size() - 4);
  const ClosedMesh m = make_closed_mesh(hull, {}, "sphere");
  EXPECT_EQ(m.vertices.size(), pts.size());
  expect_contains_all(hull, pts, 1e-7);
}

TEST(ConvexHull, CubeCornersWithInteriorCoplanarAndDuplicatePointsGiveTwelveTriangles) {
  std::vector<Vec3> pts;
  Rng rng{4};
  // face points first, so the incremental hull meets them before the corners
  for (int i = 0; i < 60; ++i) {
    Vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
    u[i % 3] = (i / 3) % 2;
    pts.push_back(u);
    pts.push_back(Vec3(0.5, 0.5, 0.5) + 0.3 * Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
  }
  for (double s : {0.25, 0.5, 0.75}) pts.push_back(Vec3(s, 0, 1));  // on an edge
  for (int rep = 0; rep < 2; ++rep) {
    for (int i = 0; i < 8; ++i) pts.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  }
  const TriangleSoup hull = convex_hull(pts);
  EXPECT_EQ(hull.size(), 12u);
  for (const auto& t : hull) {
    for (const Vec3* p : {&t.a, &t.b, &t.c}) {
      EXPECT_TRUE((p->array() == 0 || p->array() == 1).all()) << p->transpose();
    }
  }
  const ConvexPolyhedron block = build_block(hull, 1.0, {}, "cube");
  EXPECT_EQ(block.faces.size(), 6u);
  EXPECT_EQ(block.vertices.size(), 8u);
}

TEST(ConvexHull, IsDeterministicAndIndependentOfInputOrderInShape) {
  std::vector<Vec3> pts = unit_ball_points(5, 300);
  const TriangleSoup a = convex_hull(pts);
  const TriangleSoup b = convex_hull(pts);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].a, b[i].a);
    EXPECT_EQ(a[i].b, b[i].b);
    EXPECT_EQ(a[i].c, b[i].c);
  }
  std::reverse(pts.begin(), pts.end());
  const TriangleSoup c = convex_hull(pts);
  EXPECT_EQ(c.size(), a.size());
  const double va = mass_properties(make_closed_mesh(a, {}, "a"), 1.0).volume;
  const double vc = mass_properties(make_closed_mesh(c, {}, "c"), 1.0).volume;
  EXPECT_NEAR(va, vc, 1e-12 * va);
}

TEST(ConvexHull, NearlyCoplanarClusterStaysAValidMesh) {
  // many points within 1e-12 of one face plane plus points just above it
  std::vector<Vec3> pts;
  Rng rng{6};
  for (int i = 0; i < 300; ++i) {
    pts.push_back(Vec3(rng.uniform(), rng.uniform(), 1 + 1e-12 * (rng.uniform() - 0.5)));
  }
  pts.push_back(Vec3(0.5, 0.5, 0));
  for (int i = 0; i < 50; ++i) pts.push_back(Vec3(rng.uniform(), rng.uniform(), 1 + 1e-3 * rng.uniform()));
  const TriangleSoup hull = convex_hull(pts);
  EXPECT_NO_THROW(build_block(hull, 1.0, {}, "slab"));
  expect_contains_all(hull, pts, 1e-7);
}

TEST(ConvexHull, RejectsTooFewCollinearCoplanarNonFiniteOrExtremePoints) {
  EXPECT_THROW(convex_hull({}), std::invalid_argument);
  EXPECT_THROW(convex_hull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}), std::invalid_argument);
  std::vector<Vec3> same(10, Vec3(1, 2, 3));
  EXPECT_THROW(convex_hull(same), std::invalid_argument);
  std::vector<Vec3> line, plane;
  for (int i = 0; i < 10; ++i) {
    line.push_back(Vec3(i, 2 * i, -i));
    plane.push_back(Vec3(i % 3, i / 3, 0.5));
  }
  EXPECT_THROW(convex_hull(line), std::invalid_argument);
  EXPECT_THROW(convex_hull(plane), std::invalid_argument);
  // scales whose coordinate products would overflow or underflow
  std::vector<Vec3> huge = unit_ball_points(8, 20), tiny = unit_ball_points(8, 20), small = unit_ball_points(8, 20);
  for (Vec3& p : huge) p *= 1e150;
  for (Vec3& p : tiny) p *= 1e-150;
  for (Vec3& p : small) p *= 1e-60;
  EXPECT_THROW(convex_hull(huge), std::invalid_argument);
  EXPECT_THROW(convex_hull(tiny), std::invalid_argument);
  EXPECT_EQ(convex_hull(small).size(), convex_hull(unit_ball_points(8, 20)).size());
  std::vector<Vec3> bad = unit_ball_points(7, 10);
  bad[4].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(convex_hull(bad), std::invalid_argument);
}

TEST(BoxSoup, TwelveOutwardTrianglesEnclosingTheBox) {
  const Vec3 lo(-1, 2, 3), hi(4, 5, 7);
  const TriangleSoup soup = box_soup(lo, hi);
  ASSERT_EQ(soup.size(), 12u);
  const Vec3 centre = 0.5 * (lo + hi);
  double volume = 0;
  for (const auto& t : soup) {
    const Vec3 n = (t.b - t.a).cross(t.c - t.a);
    EXPECT_GT(n.dot(t.a - centre), 0);  // outward
    volume += (t.a - centre).dot((t.b - centre).cross(t.c - centre)) / 6;
  }
  EXPECT_NEAR(volume, 5.0 * 3.0 * 4.0, 1e-12);
  EXPECT_THROW(box_soup(hi, lo), std::invalid_argument);
}

}  // namespace
