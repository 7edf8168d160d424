// Compound bodies (one rigid body, several convex contact pieces) against rigid statics: an
// L-shaped block on a flat pedestal, a square prism nested in a V-groove pedestal, and a box cut
// into two pieces that must behave as the box. Mass properties of a non-convex mesh against the
// closed form of its two boxes; penalty contact independent of how finely a face is meshed.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rigid/analysis/tilt_test.hpp"
#include "rigid/geometry/polyhedron.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {
using namespace library;
using namespace analysis;
namespace {

using geometry::ClosedMesh;
using geometry::TriangleSoup;
using P2 = Eigen::Vector2d;

double cross2(const P2& a, const P2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Ear clipping of a simple counter-clockwise polygon (small polygons: O(n^3) is fine here).
std::vector<std::array<int, 3>> triangulate(const std::vector<P2>& polygon) {
  std::vector<int> left(polygon.size());
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = int(i);
  std::vector<std::array<int, 3>> out;
  while (left.size() > 3) {
    for (std::size_t k = 0; k < left.size(); ++k) {
      const int a = left[(k + left.size() - 1) % left.size()], b = left[k], c = left[(k + 1) % left.size()];
      if (cross2(polygon[b] - polygon[a], polygon[c] - polygon[b]) <= 0) continue;  // reflex
      bool empty = true;
      for (int p : left) {
        if (p == a || p == b || p == c) continue;
        const P2& q = polygon[p];
        if (cross2(polygon[b] - polygon[a], q - polygon[a]) >= 0 &&
            cross2(polygon[c] - polygon[b], q - polygon[b]) >= 0 &&
            cross2(polygon[a] - polygon[c], q - polygon[c]) >= 0)
          empty = false;
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + long(k));
      break;
    }
  }
  out.push_back({left[0], left[1], left[2]});
  return out;
}

// A prism: the counter-clockwise polygon (x, z) extruded over y in [y0, y1], outward facets.
TriangleSoup extrude(const std::vector<P2>& xz, double y0, double y1) {
  auto at = [&](int i, double y) { return Vec3(xz[i].x(), y, xz[i].y()); };
  TriangleSoup soup;
  // counter-clockwise in (x, z) is clockwise seen from +y: the y1 cap is wound reversed
  for (const auto& t : triangulate(xz)) {
    soup.push_back({at(t[0], y0), at(t[1], y0), at(t[2], y0)});
    soup.push_back({at(t[0], y1), at(t[2], y1), at(t[1], y1)});
  }
  const int n = int(xz.size());
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    soup.push_back({at(i, y0), at(j, y1), at(j, y0)});
    soup.push_back({at(i, y0), at(i, y1), at(j, y1)});
  }
  return soup;
}

ClosedMesh closed(const TriangleSoup& soup, bool convex) {
  geometry::MeshOptions options;
  options.require_convex = convex;
  return geometry::make_closed_mesh(soup, options, "test mesh");
}

dynamics::BodyDef compound_body(const std::string& name, const TriangleSoup& mesh,
                                const std::vector<TriangleSoup>& pieces, double density, bool fixed) {
  std::vector<ClosedMesh> convex;
  for (const auto& p : pieces) convex.push_back(closed(p, true));
  geometry::CompoundBody c = geometry::build_compound(closed(mesh, false), convex, density, geometry::MeshOptions{});
  dynamics::BodyDef body;
  body.name = name;
  body.shape = std::move(c.shape);
  body.pieces = std::move(c.pieces);
  body.fixed = fixed;
  body.position = body.shape.translation;
  body.orientation = body.shape.rotation;
  return body;
}

// The L: a foot [0, 1.0] x [0, 0.3] (x, z) and a column [0, 0.4] x [0.3, 1.0] on it, 0.3 m deep.
constexpr double kFootLength = 1.0, kFootHeight = 0.3, kColumnWidth = 0.4, kTop = 1.0, kDepth = 0.3;

Scene l_block_scene() {
  const std::vector<P2> outline{
      {0, 0},   {kFootLength, 0}, {kFootLength, kFootHeight}, {kColumnWidth, kFootHeight}, {kColumnWidth, kTop},
      {0, kTop}};
  const double y0 = -0.5 * kDepth, y1 = 0.5 * kDepth;
  Scene scene;
  scene.law.friction = 1.2;  // it must tip, not slide: sliding starts at a = mu g
  scene.bodies.push_back(box_body("pedestal", Vec3(-0.02, -0.3, -0.2), Vec3(kFootLength + 0.02, 0.3, 0), 2600, true));
  scene.bodies.push_back(compound_body("l_block", extrude(outline, y0, y1),
                                       {geometry::box_soup(Vec3(0, y0, 0), Vec3(kFootLength, y1, kFootHeight)),
                                        geometry::box_soup(Vec3(0, y0, kFootHeight), Vec3(kColumnWidth, y1, kTop))},
                                       2600, false));
  return scene;
}

TEST(CompoundBody, LBlockMassPropertiesAreThoseOfItsTwoBoxes) {
  const Scene scene = l_block_scene();
  const auto& l = scene.bodies[1];
  const double v_foot = kFootLength * kFootHeight * kDepth, v_column = kColumnWidth * (kTop - kFootHeight) * kDepth;
  const Vec3 c_foot(0.5 * kFootLength, 0, 0.5 * kFootHeight),
      c_column(0.5 * kColumnWidth, 0, 0.5 * (kFootHeight + kTop));
  const Vec3 centroid = (v_foot * c_foot + v_column * c_column) / (v_foot + v_column);
  EXPECT_NEAR(l.shape.volume, v_foot + v_column, 1e-12);
  EXPECT_NEAR(l.shape.mass, 2600 * (v_foot + v_column), 1e-8);
  EXPECT_LT((l.position - centroid).norm(), 1e-12);
  // the moment about y (the L's plane) by parallel axes: each box's own plus m d^2
  auto box_iyy = [](double m, double w, double h) { return m * (w * w + h * h) / 12.0; };
  const double m_foot = 2600 * v_foot, m_column = 2600 * v_column;
  const double iyy = box_iyy(m_foot, kFootLength, kFootHeight) + m_foot * (c_foot - centroid).squaredNorm() +
                     box_iyy(m_column, kColumnWidth, kTop - kFootHeight) +
                     m_column * (c_column - centroid).squaredNorm();
  const Mat3 r = l.orientation.toRotationMatrix();
  const Mat3 inertia = r * l.shape.inertia.asDiagonal() * r.transpose();
  EXPECT_NEAR(inertia(1, 1) / iyy, 1.0, 1e-9);
  ASSERT_EQ(l.pieces.size(), 2u);
  EXPECT_NEAR(l.pieces[0].volume + l.pieces[1].volume, v_foot + v_column, 1e-12);
}

TEST(CompoundBody, LBlockTopplesAtRigidStaticsInBothDirections) {
  const Scene scene = l_block_scene();
  const Vec3 c = scene.bodies[1].position;
  // pushed along +x the L leans back (-x) over its heel at x = 0; along -x forward over its toe
  const double heel = c.x() / c.z(), toe = (kFootLength - c.x()) / c.z();
  TiltTestSettings settings;
  settings.relative_tolerance = 0.002;
  const auto back = tilt_test(scene, 0.0, settings);
  const auto forward = tilt_test(scene, kPi, settings);
  std::printf("L block: +x %.4f g (statics %.4f), -x %.4f g (statics %.4f)\n", back.acceleration, heel,
              forward.acceleration, toe);
  EXPECT_NEAR(back.acceleration / heel, 1.0, 0.01);
  // the toe is 1.6 g away: it stands the 1 g the test goes to
  EXPECT_GT(toe, 1.0);
  EXPECT_TRUE(std::isinf(forward.acceleration)) << forward.acceleration;
}

TEST(CompoundBody, PrismInAVGrooveTopplesOverTheFlankTop) {
  // a square prism (side a) nested in a 90-degree groove, diagonal vertical: its faces lie on the
  // flanks, its centroid a/sqrt2 above the groove's bottom line. The flanks end at height k below
  // the prism's side corners, so pushed along +x it pivots about the left flank's top edge
  // Q = (-k, k): gravity's lever arm is k, the inertial force's a/sqrt2 - k, and
  // a/g = k / (a/sqrt2 - k). Frictionless, so no friction moment at the bottom corner, which
  // slides up the right flank; the groove holds the prism up to a = g (both flanks push), so this
  // is the first way out when it is below 1 g.
  const double a = 0.4, k = 0.1, depth = 0.5, wide = 0.4, deep = 0.3;
  const double half = a / std::sqrt(2.0);
  const std::vector<P2> left{{0, -deep}, {0, 0}, {-k, k}, {-wide, k}, {-wide, -deep}};
  std::vector<P2> right;
  for (auto it = left.rbegin(); it != left.rend(); ++it) right.push_back({-it->x(), it->y()});
  const std::vector<P2> v_shape{{-wide, -deep}, {wide, -deep}, {wide, k}, {k, k}, {0, 0}, {-k, k}, {-wide, k}};
  const double y0 = -0.5 * depth - 0.05, y1 = 0.5 * depth + 0.05;
  Scene scene;
  scene.law.friction = 0;
  scene.bodies.push_back(
      compound_body("groove", extrude(v_shape, y0, y1), {extrude(left, y0, y1), extrude(right, y0, y1)}, 2600, true));
  const std::vector<P2> square{{0, 0}, {half, half}, {0, 2 * half}, {-half, half}};
  const TriangleSoup prism = extrude(square, -0.5 * depth, 0.5 * depth);
  scene.bodies.push_back(compound_body("prism", prism, {prism}, 2600, false));
  EXPECT_NEAR(scene.bodies[1].position.z(), half, 1e-12);
  TiltTestSettings settings;
  settings.relative_tolerance = 0.002;
  const double statics = k / (half - k);
  const auto r = tilt_test(scene, 0.0, settings);
  const auto mirrored = tilt_test(scene, kPi, settings);
  std::printf("V-groove: +x %.4f g, -x %.4f g, statics %.4f g\n", r.acceleration, mirrored.acceleration, statics);
  EXPECT_NEAR(r.acceleration / statics, 1.0, 0.01);
  EXPECT_NEAR(mirrored.acceleration / statics, 1.0, 0.01);
}

TEST(CompoundBody, BoxCutInTwoBehavesAsTheBox) {
  // a 0.4 x 0.5 x 1.0 box as one block and as two convex halves glued (cut at x = 0.05)
  const Vec3 lo(-0.2, -0.25, 0), hi(0.2, 0.25, 1.0);
  Scene whole = block_on_pedestal(0.2, 0.5, 0.5);
  Scene cut = whole;
  cut.bodies[1] = compound_body(
      "block", geometry::box_soup(lo, hi),
      {geometry::box_soup(lo, Vec3(0.05, hi.y(), hi.z())), geometry::box_soup(Vec3(0.05, lo.y(), lo.z()), hi)}, 2600,
      false);
  EXPECT_LT((cut.bodies[1].position - whole.bodies[1].position).norm(), 1e-12);
  EXPECT_NEAR(cut.bodies[1].shape.mass, whole.bodies[1].shape.mass, 1e-9);
  for (const double azimuth : {0.0, kPi}) {
    const double a_whole = tilt_test(whole, azimuth).acceleration, a_cut = tilt_test(cut, azimuth).acceleration;
    EXPECT_NEAR(a_cut / a_whole, 1.0, 0.01) << azimuth;
    EXPECT_NEAR(a_cut / 0.4, 1.0, 0.01) << azimuth;  // b / h = 0.2 / 0.5
  }
}

// A convex rock with a flat base: the hull of an ellipsoid's points at `around` azimuths and
// `up` latitudes, cut flat at z = -0.6 c. The finer sampling is the same rock meshed finer.
TriangleSoup flat_based_rock(int around, int up) {
  const double a = 0.3, b = 0.25, c = 0.5, base = -0.6 * c;
  std::vector<Vec3> points;
  for (int j = 0; j <= up; ++j) {
    const double phi = -0.5 * kPi + kPi * j / up;
    for (int i = 0; i < around; ++i) {
      const double theta = 2 * kPi * i / around;
      Vec3 p(a * std::cos(theta) * std::cos(phi), b * std::sin(theta) * std::cos(phi), c * std::sin(phi));
      if (p.z() < base) continue;
      points.push_back(p);
    }
  }
  // the base: the ellipse where the cut meets the surface
  const double shrink = std::sqrt(1 - 0.36);
  for (int i = 0; i < around; ++i) {
    const double theta = 2 * kPi * i / around;
    points.emplace_back(a * shrink * std::cos(theta), b * shrink * std::sin(theta), base);
  }
  return geometry::convex_hull(points);
}

Scene rock_on_pedestal(int around, int up, contact::ContactMethod model) {
  Scene scene;
  scene.law.method = model;
  scene.law.friction = 1.2;  // it must tip, not slide: sliding starts at a = mu g
  scene.bodies.push_back(box_body("pedestal", Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, -0.3), 2600, true));
  dynamics::BodyDef rock;
  rock.name = "rock";
  rock.shape = geometry::build_block(flat_based_rock(around, up), 2600, geometry::MeshOptions{}, "rock");
  rock.position = rock.shape.translation;
  rock.orientation = rock.shape.rotation;
  scene.bodies.push_back(rock);
  return scene;
}

TEST(TessellationIndependence, PenaltyContactCarriesTheSameRockOnTheSameIndentation) {
  // 32 vs 128 base vertices: per-vertex springs would sink the coarse rock (128/32)^(2/3) = 2.5
  // times deeper; per-patch springs (four subcontacts' worth) sink both by (m g / 4 K_N)^(2/3)
  const Scene coarse = rock_on_pedestal(32, 16, contact::ContactMethod::penalty);
  const Scene fine = rock_on_pedestal(128, 64, contact::ContactMethod::penalty);
  const Scene settled_coarse = equilibrate(coarse, {}), settled_fine = equilibrate(fine, {});
  auto sink = [](const Scene& before, const Scene& after) {
    return before.bodies[1].position.z() - after.bodies[1].position.z();
  };
  const double m = coarse.bodies[1].shape.mass;
  const double expected = std::pow(m * kGravity / (4 * coarse.law.normal_stiffness), 2.0 / 3.0);
  std::printf("sink: coarse %.4g m, fine %.4g m, per-patch statics %.4g m\n", sink(coarse, settled_coarse),
              sink(fine, settled_fine), expected);
  EXPECT_NEAR(sink(coarse, settled_coarse) / expected, 1.0, 0.05);
  EXPECT_NEAR(sink(fine, settled_fine) / expected, 1.0, 0.05);
  const double a_coarse = tilt_test(settled_coarse, 0.0).acceleration,
               a_fine = tilt_test(settled_fine, 0.0).acceleration;
  std::printf("tilt test (penalty): coarse %.4f g, fine %.4f g\n", a_coarse, a_fine);
  EXPECT_NEAR(a_fine / a_coarse, 1.0, 0.02);
}

TEST(TessellationIndependence, RigidContactTiltTestIsTheSameForBothMeshes) {
  const Scene coarse = rock_on_pedestal(32, 16, contact::ContactMethod::rigid);
  const Scene fine = rock_on_pedestal(128, 64, contact::ContactMethod::rigid);
  // rigid statics of the base ellipse (semi-axes 0.8 a, 0.8 b at z = -0.3 c... relative to the
  // centroid): along x the rock leans over the base's end at 0.24 m
  const double a_coarse = tilt_test(coarse, 0.0).acceleration, a_fine = tilt_test(fine, 0.0).acceleration;
  const double statics = 0.24 / (fine.bodies[1].position.z() - (-0.3));
  std::printf("tilt test (rigid): coarse %.4f g, fine %.4f g, statics of the ellipse %.4f g\n", a_coarse, a_fine,
              statics);
  EXPECT_NEAR(a_fine / a_coarse, 1.0, 0.01);
  EXPECT_NEAR(a_fine / statics, 1.0, 0.01);
}

}  // namespace
}  // namespace rigid::scenario
