// make_closed_mesh: welding, orientation repair and rejection of bad meshes with the facet named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace {

using rigid::InputError;
using rigid::Vec3;
using namespace rigid::geometry;

TriangleSoup unit_box() { return box_soup(Vec3::Zero(), Vec3::Ones()); }

TriangleSoup flipped(TriangleSoup soup) {
  for (auto& t : soup) std::swap(t.b, t.c);
  return soup;
}

double signed_volume(const ClosedMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6;
  }
  return v;
}

// Prism over a counter-clockwise polygon (z in [0, h]); caps are fans from polygon vertex 0.
TriangleSoup prism(const std::vector<Vec3>& poly, double h) {
  TriangleSoup s;
  const Vec3 up(0, 0, h);
  const std::size_t n = poly.size();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    s.push_back({poly[0], poly[i + 1], poly[i]});                 // bottom, facing -z
    s.push_back({poly[0] + up, poly[i] + up, poly[i + 1] + up});  // top, facing +z
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 &a = poly[i], &b = poly[(i + 1) % n];
    s.push_back({a, b, b + up});
    s.push_back({a, b + up, a + up});
  }
  return s;
}

// The error is one line "SOURCE: facet N: ..." and contains `words`; returns N.
int expect_facet_error(const TriangleSoup& soup, const std::string& words) {
  try {
    make_closed_mesh(soup, {}, "rock.stl");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(e.file(), "rock.stl");
    EXPECT_EQ(e.line(), 0);
    int facet = -1;
    char colon = 0;
    const bool numbered = std::sscanf(msg.c_str(), "rock.stl: facet %d%c", &facet, &colon) == 2 && colon == ':';
    EXPECT_TRUE(numbered && msg.rfind("rock.stl: facet ", 0) == 0) << msg;
    EXPECT_NE(msg.find(words), std::string::npos) << msg;
    return numbered ? facet : -1;
  }
  ADD_FAILURE() << "no InputError; expected one about " << words;
  return -1;
}

std::string mesh_error(const TriangleSoup& soup) {
  try {
    make_closed_mesh(soup, {}, "rock.stl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ClosedMesh, WeldsTheThirtySixCornersOfABoxIntoEight) {
  const TriangleSoup soup = unit_box();
  const ClosedMesh m = make_closed_mesh(soup, {}, "box");
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_TRUE(m.warnings.empty());
  // the first occurrence keeps its index and exact position
  EXPECT_EQ(m.vertices[0], soup[0].a);
  EXPECT_EQ(m.vertices[1], soup[0].b);
  EXPECT_EQ(m.vertices[2], soup[0].c);
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-14);
}

TEST(ClosedMesh, WeldsVerticesWithinToleranceAndNotBeyond) {
  TriangleSoup soup = unit_box();
  // jitter each repeated corner by far less than weld_tolerance * diagonal (1e-9 * sqrt 3)
  double sign = 1;
  for (std::size_t i = 1; i < soup.size(); ++i) {
    soup[i].a += Vec3(1e-12 * sign, -2e-12, 0);
    soup[i].c += Vec3(0, 0, 3e-12 * sign);
    sign = -sign;
  }
  EXPECT_EQ(make_closed_mesh(soup, {}, "box").vertices.size(), 8u);
  // a gap of 1e-6 is far above the tolerance: the corner splits and leaves open edges
  soup[5].b += Vec3(1e-6, 0, 0);
  expect_facet_error(soup, "not closed");
}

TEST(ClosedMesh, InwardMeshIsFlippedWithAWarning) {
  const ClosedMesh m = make_closed_mesh(flipped(unit_box()), {}, "box");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("orientation was inward; flipped"), std::string::npos);
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-14);
}

TEST(ClosedMesh, InconsistentFacetsAreReorientedWithAWarning) {
  TriangleSoup soup = unit_box();
  std::swap(soup[3].b, soup[3].c);
  std::swap(soup[8].b, soup[8].c);
  const ClosedMesh m = make_closed_mesh(soup, {}, "box");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("2 of 12 facets"), std::string::npos) << m.warnings[0];
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-14);
  // every directed edge now appears exactly once
  const auto nb = triangle_neighbors(m);
  for (const auto& n : nb) {
    for (int k : n) EXPECT_GE(k, 0);
  }
}

TEST(ClosedMesh, OpenMeshIsRejectedNamingAFacetBesideTheHole) {
  TriangleSoup soup = unit_box();
  const Triangle removed = soup[7];
  soup.erase(soup.begin() + 7);
  const int f = expect_facet_error(soup, "open edge");
  ASSERT_GE(f, 0);
  // the named facet shares two corners (an edge) with the removed one
  int shared = 0;
  for (const Vec3* p : {&soup[f].a, &soup[f].b, &soup[f].c}) {
    shared += *p == removed.a || *p == removed.b || *p == removed.c;
  }
  EXPECT_EQ(shared, 2);
}

TEST(ClosedMesh, NonManifoldEdgeIsRejected) {
  // two boxes touching along one vertical edge: that edge has four facets
  TriangleSoup soup = unit_box();
  const TriangleSoup other = box_soup(Vec3(1, 1, 0), Vec3(2, 2, 1));
  soup.insert(soup.end(), other.begin(), other.end());
  expect_facet_error(soup, "non-manifold edge");
}

TEST(ClosedMesh, DisconnectedPartsAreRejected) {
  TriangleSoup soup = unit_box();
  const TriangleSoup other = box_soup(Vec3(3, 0, 0), Vec3(4, 1, 1));
  soup.insert(soup.end(), other.begin(), other.end());
  EXPECT_EQ(expect_facet_error(soup, "more than one part"), 12);
}

TEST(ClosedMesh, LShapedPrismIsRejectedAsNonConvex) {
  const std::vector<Vec3> ell{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  const TriangleSoup soup = prism(ell, 1.0);
  const int f = expect_facet_error(soup, "not convex");
  ASSERT_GE(f, 0);
  // the named facet really has a vertex above its plane
  const Vec3 n = (soup[f].b - soup[f].a).cross(soup[f].c - soup[f].a).normalized();
  double worst = -1;
  for (const auto& t : soup) {
    for (const Vec3* p : {&t.a, &t.b, &t.c}) worst = std::max(worst, n.dot(*p - soup[f].a));
  }
  EXPECT_GT(worst, 0.5);
  // the same prism over the convex hull of the L is accepted
  const std::vector<Vec3> hull{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  EXPECT_NO_THROW(make_closed_mesh(prism(hull, 1.0), {}, "ok"));
}

TEST(ClosedMesh, ConvexityToleranceAcceptsRoundingButNotADent) {
  // the +z face split as a fan around its centre, which is then pushed along z
  auto fan_box = [](double dz) {
    TriangleSoup soup = box_soup(Vec3::Zero(), Vec3::Ones());
    soup.erase(soup.begin() + 10, soup.end());  // drop the two +z triangles
    const Vec3 c(0.5, 0.5, 1 + dz);
    const Vec3 q[4] = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (int i = 0; i < 4; ++i) soup.push_back({q[i], q[(i + 1) % 4], c});
    return soup;
  };
  EXPECT_NO_THROW(make_closed_mesh(fan_box(0.0), {}, "ok"));
  EXPECT_NO_THROW(make_closed_mesh(fan_box(1e-8), {}, "ok"));  // 6e-9 of the diagonal
  EXPECT_NO_THROW(make_closed_mesh(fan_box(-1e-8), {}, "ok"));
  const int f = expect_facet_error(fan_box(-1e-3), "not convex");  // a dent
  EXPECT_GE(f, 10);  // the dented fan facets see the other fan vertices above them
}

TEST(ClosedMesh, DegenerateTrianglesAreRejected) {
  // a zero-area sliver: split the +x face's first triangle at an edge midpoint
  TriangleSoup soup = unit_box();
  const Triangle t = soup[2];
  const Vec3 mid = 0.5 * (t.a + t.b);
  soup[2] = {t.a, mid, t.c};
  soup.push_back({mid, t.b, t.c});
  soup.push_back({t.a, t.b, mid});  // collinear: zero area
  EXPECT_EQ(expect_facet_error(soup, "degenerate triangle"), 13);
  // two corners welded together
  TriangleSoup welded = unit_box();
  welded[4].b = welded[4].a + Vec3(1e-13, 0, 0);
  EXPECT_EQ(expect_facet_error(welded, "coincide"), 4);
}

TEST(ClosedMesh, NanAndInfiniteCoordinatesAreRejected) {
  TriangleSoup soup = unit_box();
  soup[3].b.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(expect_facet_error(soup, "NaN or infinite"), 3);
  soup = unit_box();
  soup[9].c.z() = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(expect_facet_error(soup, "NaN or infinite"), 9);
  soup = unit_box();
  soup[6].a.y() = 1e300;
  EXPECT_EQ(expect_facet_error(soup, "from the origin"), 6);
}

TEST(ClosedMesh, FlatDoubleCoveredTriangleIsRejected) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const std::string msg = mesh_error({{a, b, c}, {a, c, b}});
  EXPECT_NE(msg.find("encloses no volume"), std::string::npos) << msg;
}

TEST(ClosedMesh, NonOrientableOrUnclosableInputsNeverPass) {
  EXPECT_NE(mesh_error({}).find("no facets"), std::string::npos);
  // a single triangle
  EXPECT_NE(mesh_error({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}}).find("open edge"), std::string::npos);
  // the same triangle twice in the same direction: each edge used twice the same way
  const Triangle t{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const std::string msg = mesh_error({t, t});
  EXPECT_FALSE(msg.empty());
}

TEST(ClosedMesh, InvalidOptionsThrowInvalidArgument) {
  MeshOptions bad;
  bad.weld_tolerance = -1;
  EXPECT_THROW(make_closed_mesh(unit_box(), bad, "x"), std::invalid_argument);
  bad = {};
  bad.convexity_tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(make_closed_mesh(unit_box(), bad, "x"), std::invalid_argument);
}

TEST(ClosedMesh, ZeroWeldToleranceStillWeldsExactDuplicates) {
  MeshOptions exact;
  exact.weld_tolerance = 0;
  EXPECT_EQ(make_closed_mesh(unit_box(), exact, "box").vertices.size(), 8u);
}

}  // namespace
