// make_polyhedron / build_block: body frame, merged planar faces, feature edges, adjacency.
#include "rigid/geometry/polyhedron.hpp"

#include <gtest/gtest.h>

#include "support/rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

#include "rigid/core/error.hpp"

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::Vec3;
using namespace rigid::geometry;

using rigid::test::Rng;

// Structural invariants every block must satisfy, whatever its shape.
void expect_consistent(const ConvexPolyhedron& p) {
  const double tol = 1e-9 * p.bounding_radius;
  // faces: unit normals, planar CCW loops, every vertex of the block on or below each plane
  for (const Face& f : p.faces) {
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
    ASSERT_GE(f.vertices.size(), 3u);
    Vec3 twice_area = Vec3::Zero();
    for (std::size_t k = 0; k < f.vertices.size(); ++k) {
      const Vec3& a = p.vertices[f.vertices[k]];
      const Vec3& b = p.vertices[f.vertices[(k + 1) % f.vertices.size()]];
      twice_area += a.cross(b);
      EXPECT_NEAR(f.normal.dot(a), f.offset, tol);
    }
    EXPECT_GT(twice_area.dot(f.normal), 0) << "loop is not counter-clockwise from outside";
    for (const Vec3& v : p.vertices) EXPECT_LE(f.normal.dot(v) - f.offset, tol);
  }
  // edges: v0 -> v1 consecutive on face_left's loop and v1 -> v0 on face_right's loop
  auto runs = [&](int face, int a, int b) {
    const auto& loop = p.faces[face].vertices;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      if (loop[k] == a && loop[(k + 1) % loop.size()] == b) return true;
    }
    return false;
  };
  std::size_t loop_edges = 0;
  for (const Face& f : p.faces) loop_edges += f.vertices.size();
  EXPECT_EQ(2 * p.edges.size(), loop_edges);
  std::set<std::pair<int, int>> seen;
  for (const Edge& e : p.edges) {
    EXPECT_TRUE(runs(e.face_left, e.v0, e.v1));
    EXPECT_TRUE(runs(e.face_right, e.v1, e.v0));
    EXPECT_NE(e.face_left, e.face_right);
    EXPECT_TRUE(seen.insert({std::min(e.v0, e.v1), std::max(e.v0, e.v1)}).second);
  }
  // Euler's formula over the vertices that lie on feature edges
  std::size_t corners = 0;
  for (const auto& nb : p.vertex_neighbors) corners += !nb.empty();
  EXPECT_EQ(static_cast<long>(corners) - static_cast<long>(p.edges.size()) + static_cast<long>(p.faces.size()), 2);
  // neighbour lists are symmetric
  for (std::size_t v = 0; v < p.vertex_neighbors.size(); ++v) {
    for (int w : p.vertex_neighbors[v]) {
      const auto& back = p.vertex_neighbors[w];
      EXPECT_TRUE(std::find(back.begin(), back.end(), static_cast<int>(v)) != back.end());
    }
  }
  for (std::size_t f = 0; f < p.face_neighbors.size(); ++f) {
    for (int g : p.face_neighbors[f]) {
      const auto& back = p.face_neighbors[g];
      EXPECT_TRUE(std::find(back.begin(), back.end(), static_cast<int>(f)) != back.end());
    }
  }
  // the body frame is centred at the centroid
  double r = 0;
  for (const Vec3& v : p.vertices) r = std::max(r, v.norm());
  EXPECT_EQ(p.bounding_radius, r);
}

TEST(Polyhedron, BoxHasSixFacesTwelveEdgesAndEightThreeWayCorners) {
  const double a = 1.0, b = 2.0, c = 3.0;
  const Vec3 lo(10, -5, 2);
  const TriangleSoup soup = box_soup(lo, lo + Vec3(a, b, c));
  const ConvexPolyhedron p = build_block(soup, 2000.0, {}, "box");
  ASSERT_EQ(p.faces.size(), 6u);
  EXPECT_EQ(p.edges.size(), 12u);
  ASSERT_EQ(p.vertices.size(), 8u);
  for (const auto& nb : p.vertex_neighbors) EXPECT_EQ(nb.size(), 3u);
  for (const auto& nb : p.face_neighbors) EXPECT_EQ(nb.size(), 4u);
  for (const Face& f : p.faces) EXPECT_EQ(f.vertices.size(), 4u);
  expect_consistent(p);
  // principal body frame: each face offset is half an edge, corners at half the diagonal
  std::multiset<long> offsets;
  for (const Face& f : p.faces) offsets.insert(std::lround(f.offset * 1e6));
  EXPECT_EQ(offsets, (std::multiset<long>{500000, 500000, 1000000, 1000000, 1500000, 1500000}));
  EXPECT_NEAR(p.bounding_radius, 0.5 * std::sqrt(a * a + b * b + c * c), 1e-12);
  // x_body along the smallest moment: the longest side (c) lies on body x
  EXPECT_NEAR(p.inertia[0], p.mass * (a * a + b * b) / 12, 1e-10 * p.inertia[0]);
  for (const Vec3& v : p.vertices) EXPECT_NEAR(std::abs(v.x()), c / 2, 1e-12);
  EXPECT_NEAR(p.volume, a * b * c, 1e-12);
  EXPECT_NEAR(p.mass, 2000.0 * a * b * c, 1e-9);
}

TEST(Polyhedron, PoseMapsBodyVerticesBackToTheMesh) {
  // an irregular block: x_mesh = rotation * x_body + translation for every vertex
  Rng rng{3};
  std::vector<Vec3> pts;
  for (int i = 0; i < 60; ++i) {
    pts.push_back(Vec3(5 + 2 * rng.uniform(), -1 + rng.uniform(), 3 + 0.5 * rng.uniform()));
  }
  const TriangleSoup soup = convex_hull(pts);
  const ClosedMesh mesh = make_closed_mesh(soup, {}, "rock");
  const MassProperties props = mass_properties(mesh, 2650.0);
  const ConvexPolyhedron p = make_polyhedron(mesh, props, {});
  ASSERT_EQ(p.vertices.size(), mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    EXPECT_LT((p.rotation * p.vertices[i] + p.translation - mesh.vertices[i]).norm(), 1e-12);
  }
  EXPECT_NEAR(p.rotation.norm(), 1.0, 1e-15);
  // the inertia in the body frame is diagonal: R^T I R = diag(moments)
  const Mat3 r = p.rotation.toRotationMatrix();
  const Mat3 body = r.transpose() * props.inertia * r;
  const double scale = props.principal_moments.maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(body(i, j), i == j ? p.inertia[i] : 0.0, 1e-10 * scale);
    }
  }
  // and the centroid sits at the body origin
  Vec3 sum = Vec3::Zero();
  for (const auto& t : mesh.triangles) {
    const Vec3 &x = p.vertices[t[0]], &y = p.vertices[t[1]], &z = p.vertices[t[2]];
    sum += x.dot(y.cross(z)) * (x + y + z) / 24;
  }
  EXPECT_LT(sum.norm(), 1e-12 * p.volume);
  expect_consistent(p);
}

TEST(Polyhedron, FanAroundAFaceCentreMergesIntoOneFace) {
  TriangleSoup soup = box_soup(Vec3::Zero(), Vec3::Ones());
  soup.erase(soup.begin() + 10, soup.end());
  const Vec3 q[4] = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 4; ++i) soup.push_back({q[i], q[(i + 1) % 4], Vec3(0.5, 0.5, 1)});
  const ConvexPolyhedron p = build_block(soup, 1.0, {}, "fan");
  EXPECT_EQ(p.faces.size(), 6u);
  EXPECT_EQ(p.edges.size(), 12u);
  EXPECT_EQ(p.vertices.size(), 9u);  // the centre stays, with no feature edge
  int isolated = 0;
  for (const auto& nb : p.vertex_neighbors) isolated += nb.empty();
  EXPECT_EQ(isolated, 1);
  expect_consistent(p);
}

TEST(Polyhedron, HullOfCubeWithInteriorAndCoplanarPointsHasSixFaces) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  Rng rng{11};
  for (int i = 0; i < 40; ++i) {
    const Vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
    pts.push_back(0.1 * Vec3::Ones() + 0.8 * u);  // interior
    Vec3 w = u;
    w[i % 3] = (i / 3) % 2;  // on a face
    pts.push_back(w);
  }
  pts.push_back(Vec3(0.5, 0, 0));  // on an edge
  pts.push_back(Vec3(1, 1, 1));    // a duplicate corner
  const ConvexPolyhedron p = build_block(convex_hull(pts), 1.0, {}, "cube");
  EXPECT_EQ(p.faces.size(), 6u);
  EXPECT_NEAR(p.volume, 1.0, 1e-12);
  for (const auto& f : p.faces) {
    EXPECT_NEAR(f.offset, 0.5, 1e-12);
    EXPECT_NEAR(f.normal.cwiseAbs().maxCoeff(), 1.0, 1e-12);
  }
  expect_consistent(p);
}

TEST(Polyhedron, GeodesicSphereKeepsEveryTriangleAsAFace) {
  // icosahedron subdivided twice and projected on the unit sphere: no two facets are coplanar
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> pts;
  for (double s : {-1.0, 1.0}) {
    for (double t : {-1.0, 1.0}) {
      pts.push_back(Vec3(0, s, t * g).normalized());
      pts.push_back(Vec3(s, t * g, 0).normalized());
      pts.push_back(Vec3(t * g, 0, s).normalized());
    }
  }
  for (int level = 0; level < 2; ++level) {
    const TriangleSoup hull = convex_hull(pts);
    for (const auto& t : hull) {
      for (const Vec3& m : {Vec3(t.a + t.b), Vec3(t.b + t.c), Vec3(t.c + t.a)}) {
        const Vec3 v = m.normalized();
        bool dup = false;
        for (const Vec3& q : pts) dup = dup || (q - v).norm() < 1e-12;
        if (!dup) pts.push_back(v);
      }
    }
  }
  ASSERT_EQ(pts.size(), 162u);
  const ConvexPolyhedron p = build_block(convex_hull(pts), 1.0, {}, "sphere");
  EXPECT_EQ(p.faces.size(), 320u);
  EXPECT_EQ(p.edges.size(), 480u);
  expect_consistent(p);
  // nearly a sphere: volume below 4/3 pi and close to it
  EXPECT_LT(p.volume, 4.0 / 3.0 * rigid::kPi);
  EXPECT_GT(p.volume, 0.95 * 4.0 / 3.0 * rigid::kPi);
  EXPECT_NEAR(p.inertia[0] / p.inertia[2], 1.0, 1e-3);
}

TEST(Polyhedron, BuildIsDeterministic) {
  Rng rng{5};
  std::vector<Vec3> pts;
  for (int i = 0; i < 200; ++i) pts.push_back(Vec3(rng.uniform(), 2 * rng.uniform(), rng.uniform()));
  const TriangleSoup soup = convex_hull(pts);
  const ConvexPolyhedron a = build_block(soup, 2650.0, {}, "r");
  const ConvexPolyhedron b = build_block(soup, 2650.0, {}, "r");
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t i = 0; i < a.faces.size(); ++i) EXPECT_EQ(a.faces[i].vertices, b.faces[i].vertices);
  EXPECT_EQ(a.inertia, b.inertia);
  EXPECT_EQ(a.rotation.coeffs(), b.rotation.coeffs());
  expect_consistent(a);
}

TEST(Polyhedron, BuildBlockReportsWarningsAndRejectsBadDensity) {
  TriangleSoup inward = box_soup(Vec3::Zero(), Vec3::Ones());
  for (auto& t : inward) std::swap(t.b, t.c);
  std::vector<std::string> warnings;
  const ConvexPolyhedron p = build_block(inward, 1.0, {}, "box", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("inward"), std::string::npos);
  EXPECT_NEAR(p.volume, 1.0, 1e-14);
  EXPECT_THROW(build_block(inward, -1.0, {}, "box"), std::invalid_argument);
  EXPECT_THROW(build_block({}, 1.0, {}, "box"), rigid::InputError);
}

TEST(Polyhedron, MakePolyhedronRejectsAnOpenMesh) {
  ClosedMesh mesh = make_closed_mesh(box_soup(Vec3::Zero(), Vec3::Ones()), {}, "box");
  const MassProperties props = mass_properties(mesh, 1.0);
  mesh.triangles.pop_back();
  EXPECT_THROW(make_polyhedron(mesh, props, {}), std::invalid_argument);
  mesh.triangles.push_back({0, 1, 99});
  EXPECT_THROW(make_polyhedron(mesh, props, {}), std::invalid_argument);
}

}  // namespace
