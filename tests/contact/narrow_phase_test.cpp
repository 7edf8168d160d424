// The narrow phase on its own (common plane, subcontacts), against configurations whose answer
// follows from the boxes' dimensions and poses: face-face, vertex-face, edge-edge, deep overlap
// with a poor starting normal, separated pairs, and the symmetries (swap, translation).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::contact {
namespace {

// The iteration of the overlap step and the distance query converge to rounding, then the normal
// is snapped to the face's own normal: 1e-9 m (and rad) is far below anything a step resolves.
constexpr double kTol = 1e-9;

// A box block placed in the world: its mesh frame (where box_soup's lo/hi are given) at
// (rotation, translation); the hull's body frame sits at the centroid on principal axes.
struct PlacedBox {
  geometry::ConvexPolyhedron shape;
  std::vector<Vec3> world;
  Mat3 rotation = Mat3::Identity();
  Vec3 position{0, 0, 0};

  PlacedBox(const Vec3& lo, const Vec3& hi, const Mat3& mesh_rotation, const Vec3& mesh_translation)
      : shape(geometry::build_block(geometry::box_soup(lo, hi), 2600, {}, "box")) {
    rotation = mesh_rotation * shape.rotation.toRotationMatrix();
    position = mesh_rotation * shape.translation + mesh_translation;
    world.resize(shape.vertices.size());
    for (std::size_t k = 0; k < world.size(); ++k) world[k] = rotation * shape.vertices[k] + position;
  }
  PlacedHull hull() const { return {&shape, world.data(), Vec3::Zero(), rotation, position}; }
  void translate(const Vec3& d) {
    position += d;
    for (auto& w : world) w += d;
  }
};

// The pedestal: a 2 m x 2 m slab whose top face is z = 0.
PlacedBox slab() { return PlacedBox(Vec3(-1, -1, -0.2), Vec3(1, 1, 0), Mat3::Identity(), Vec3::Zero()); }

Mat3 about(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

struct Found {
  CommonPlane plane;
  std::vector<SubcontactPoint> points;
};

Found contact_of(const PlacedBox& a, const PlacedBox& b, const Vec3& previous_normal = Vec3::UnitZ()) {
  SupportHints hints;
  Found f;
  f.plane = find_common_plane(a.hull(), b.hull(), previous_normal, hints);
  if (f.plane.overlap > 0) collect_subcontacts(a.hull(), b.hull(), f.plane, f.points);
  return f;
}

void expect_vec(const Vec3& got, const Vec3& want, double tol, const char* what) {
  EXPECT_LT((got - want).norm(), tol) << what << ": got " << got.transpose() << ", want " << want.transpose();
}

TEST(NarrowPhase, FaceOnFaceGivesTheFourCornersAtHalfTheIndentation) {
  const double depth = 1e-4, hx = 0.25, hy = 0.15;
  const PlacedBox a = slab();
  const PlacedBox b(Vec3(-hx, -hy, 0), Vec3(hx, hy, 0.6), Mat3::Identity(), Vec3(0.1, -0.2, -depth));
  const Found f = contact_of(a, b);
  expect_vec(f.plane.normal, Vec3::UnitZ(), kTol, "normal");
  EXPECT_NEAR(f.plane.overlap, depth, kTol);
  ASSERT_EQ(f.points.size(), 4u);
  std::vector<Vec3> corners = {{0.1 - hx, -0.2 - hy, -depth / 2},
                               {0.1 + hx, -0.2 - hy, -depth / 2},
                               {0.1 + hx, -0.2 + hy, -depth / 2},
                               {0.1 - hx, -0.2 + hy, -depth / 2}};
  for (const auto& p : f.points) {
    EXPECT_NEAR(p.overlap, depth, kTol);
    EXPECT_NE(p.key, kEdgeSubcontact);
    bool matched = false;
    for (const auto& c : corners) matched = matched || (p.point - c).norm() < kTol;
    EXPECT_TRUE(matched) << "no corner at " << p.point.transpose();
  }
}

TEST(NarrowPhase, VertexDownGivesOneSubcontactAtTheVertex) {
  // a 0.3 m cube with its body diagonal vertical: the vertex (h, h, h) points straight down
  const double h = 0.15, depth = 2e-4;
  const Mat3 down = Quat::FromTwoVectors(Vec3(1, 1, 1), -Vec3::UnitZ()).toRotationMatrix();
  const Vec3 centre(0.3, 0.1, std::sqrt(3.0) * h - depth);
  const PlacedBox b(Vec3(-h, -h, -h), Vec3(h, h, h), down, centre);
  const Found f = contact_of(slab(), b);
  expect_vec(f.plane.normal, Vec3::UnitZ(), kTol, "normal");
  EXPECT_NEAR(f.plane.overlap, depth, kTol);
  ASSERT_EQ(f.points.size(), 1u);
  EXPECT_NEAR(f.points[0].overlap, depth, kTol);
  expect_vec(f.points[0].point, Vec3(0.3, 0.1, -depth / 2), kTol, "vertex subcontact");
}

TEST(NarrowPhase, CrossingEdgesGiveOneSubcontactAtTheCrossing) {
  // two 0.4 m cubes standing on an edge: A's top edge along x at z = 0.2 sqrt 2, B's bottom edge
  // along y, pressed into it by `depth`; no vertex of either is inside the other
  const double s = 0.2, depth = 1e-4, ridge = s * std::sqrt(2.0);
  const PlacedBox a(Vec3(-s, -s, -s), Vec3(s, s, s), about(Vec3::UnitX(), kPi / 4), Vec3::Zero());
  const PlacedBox b(Vec3(-s, -s, -s), Vec3(s, s, s), about(Vec3::UnitY(), kPi / 4), Vec3(0, 0, 2 * ridge - depth));
  const Found f = contact_of(a, b);
  expect_vec(f.plane.normal, Vec3::UnitZ(), kTol, "normal");
  EXPECT_NEAR(f.plane.overlap, depth, kTol);
  ASSERT_EQ(f.points.size(), 1u);
  EXPECT_EQ(f.points[0].key, kEdgeSubcontact);
  EXPECT_NEAR(f.points[0].overlap, depth, kTol);
  expect_vec(f.points[0].point, Vec3(0, 0, ridge - depth / 2), kTol, "edge-edge subcontact");
}

TEST(NarrowPhase, DeepOverlapFindsTheLeastOverlapDirectionFromATiltedGuess) {
  // 1 cm into the slab, the previous normal 20 deg off: the overlap step must still settle on z
  const double depth = 0.01;
  const PlacedBox b(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, 0.5), Mat3::Identity(), Vec3(0, 0, -depth));
  const Vec3 guess = about(Vec3::UnitX(), 20.0 * kPi / 180.0) * Vec3::UnitZ();
  const Found f = contact_of(slab(), b, guess);
  expect_vec(f.plane.normal, Vec3::UnitZ(), kTol, "normal");
  EXPECT_NEAR(f.plane.overlap, depth, kTol);
  ASSERT_EQ(f.points.size(), 4u);
  for (const auto& p : f.points) EXPECT_NEAR(p.overlap, depth, kTol);
}

TEST(NarrowPhase, NearlyParallelFacesTouchOnlyAtTheLowerEdge) {
  // the block tilted by 1e-6 rad about x: its -y bottom edge is lower by 2 hy 1e-6 = 4e-7 m. With
  // that edge 1e-7 m into the slab only its two corners penetrate, by 1e-7 m
  const double hy = 0.2, tilt = 1e-6, depth = 1e-7;
  const Mat3 r = about(Vec3::UnitX(), tilt);  // +y side rises
  const Vec3 low_corner = r * Vec3(0, -hy, 0);
  const PlacedBox b(Vec3(-0.3, -hy, 0), Vec3(0.3, hy, 0.5), r, Vec3(0, 0, -low_corner.z() - depth));
  const Found f = contact_of(slab(), b);
  EXPECT_LT((f.plane.normal - Vec3::UnitZ()).norm(), 2 * tilt);
  EXPECT_NEAR(f.plane.overlap, depth, kTol);
  ASSERT_EQ(f.points.size(), 2u);
  for (const auto& p : f.points) {
    EXPECT_NEAR(p.point.y(), -hy, 1e-6);
    EXPECT_NEAR(p.overlap, depth, kTol);
  }
}

TEST(NarrowPhase, SeparatedPairsReportMinusTheirDistance) {
  const double gap = 0.05;
  const PlacedBox face(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, 0.5), Mat3::Identity(), Vec3(0, 0, gap));
  const Found f = contact_of(slab(), face);
  expect_vec(f.plane.normal, Vec3::UnitZ(), kTol, "normal");
  EXPECT_NEAR(f.plane.overlap, -gap, kTol);
  // beside the slab: the distance is the corner-to-corner diagonal
  const PlacedBox corner(Vec3(0, 0, 0), Vec3(0.3, 0.3, 0.3), Mat3::Identity(), Vec3(1.03, 1.04, 0.05));
  const Found g = contact_of(slab(), corner);
  EXPECT_NEAR(g.plane.overlap, -std::sqrt(0.03 * 0.03 + 0.04 * 0.04 + 0.05 * 0.05), kTol);
  expect_vec(g.plane.normal, Vec3(0.03, 0.04, 0.05).normalized(), kTol, "corner normal");
}

TEST(NarrowPhase, SwappingTheBlocksFlipsTheNormalAndKeepsTheOverlap) {
  const PlacedBox a = slab();
  const PlacedBox b(Vec3(-0.2, -0.1, 0), Vec3(0.2, 0.1, 0.4), about(Vec3(1, 2, 0), 0.3), Vec3(0.05, 0, 0.02));
  const Found ab = contact_of(a, b);
  const Found ba = contact_of(b, a, -ab.plane.normal);
  ASSERT_GT(ab.plane.overlap, 0.0);
  expect_vec(ba.plane.normal, -ab.plane.normal, kTol, "normal");
  EXPECT_NEAR(ba.plane.overlap, ab.plane.overlap, kTol);
}

TEST(NarrowPhase, TranslatingBothBlocksShiftsThePointsOnly) {
  PlacedBox a = slab();
  PlacedBox b(Vec3(-0.2, -0.1, 0), Vec3(0.2, 0.1, 0.4), about(Vec3(1, 2, 0), 0.3), Vec3(0.05, 0, 0.02));
  const Found before = contact_of(a, b);
  const Vec3 shift(3.0, -2.0, 1.0);
  a.translate(shift);
  b.translate(shift);
  const Found after = contact_of(a, b);
  expect_vec(after.plane.normal, before.plane.normal, kTol, "normal");
  EXPECT_NEAR(after.plane.overlap, before.plane.overlap, kTol);
  ASSERT_EQ(after.points.size(), before.points.size());
  for (std::size_t i = 0; i < after.points.size(); ++i) {
    EXPECT_EQ(after.points[i].key, before.points[i].key);
    expect_vec(after.points[i].point, before.points[i].point + shift, kTol, "point");
  }
}

}  // namespace
}  // namespace rigid::contact
