// Mass properties of closed meshes against closed forms and an independent quadrature oracle.
#include <gtest/gtest.h>

#include "support/rng.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rigid/geometry/polyhedron.hpp"

namespace {

using rigid::Mat3;
using rigid::Vec3;
using namespace rigid::geometry;

constexpr double kRel = 1e-10;

ClosedMesh mesh_of(const TriangleSoup& soup) { return make_closed_mesh(soup, {}, "test"); }

void expect_rel(double actual, double expected, double rel, const char* what) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << what;
}

// every entry within rel of the matrix scale (off-diagonals may be zero)
void expect_mat_near(const Mat3& a, const Mat3& b, double rel) {
  const double scale = b.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a(i, j), b(i, j), rel * scale) << "entry " << i << j;
  }
}

void expect_principal_frame(const MassProperties& p) {
  const Mat3& r = p.principal_axes;
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_TRUE((r.transpose() * r).isApprox(Mat3::Identity(), 1e-12));
  EXPECT_LE(p.principal_moments[0], p.principal_moments[1]);
  EXPECT_LE(p.principal_moments[1], p.principal_moments[2]);
  // I = R diag(moments) R^T
  expect_mat_near(r * p.principal_moments.asDiagonal() * r.transpose(), p.inertia, kRel);
}

// Independent oracle: split the solid into tetrahedra (interior point q, outward triangle) and
// integrate 1, x, x x^T on each with the 4-point rule that is exact for quadratics.
struct Oracle {
  double volume = 0;
  Vec3 centroid = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();  // about the centroid, unit density
};

Oracle quadrature_oracle(const TriangleSoup& soup) {
  Vec3 q = Vec3::Zero();
  for (const auto& t : soup) q += (t.a + t.b + t.c) / 3.0;
  q /= static_cast<double>(soup.size());
  const double alpha = 0.5854101966249685, beta = 0.1381966011250105;  // Keast degree-2 rule
  double vol = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();  // about q
  for (const auto& t : soup) {
    const Vec3 p[4] = {Vec3::Zero(), t.a - q, t.b - q, t.c - q};
    const double v = (p[1]).dot(p[2].cross(p[3])) / 6.0;
    vol += v;
    for (int i = 0; i < 4; ++i) {
      Vec3 x = Vec3::Zero();
      for (int j = 0; j < 4; ++j) x += (i == j ? alpha : beta) * p[j];
      first += v / 4 * x;
      second += v / 4 * x * x.transpose();
    }
  }
  Oracle o;
  o.volume = vol;
  const Vec3 c = first / vol;
  o.centroid = q + c;
  const Mat3 cov = second - vol * c * c.transpose();
  o.inertia = cov.trace() * Mat3::Identity() - cov;
  return o;
}

std::vector<Vec3> random_cloud(std::uint64_t seed, int n) {
  std::vector<Vec3> pts;
  // an irregular ellipsoid-ish cloud: no symmetry, so every product of inertia is non-zero
  for (const Vec3& u : rigid::test::unit_ball_points(seed, n)) {
    pts.push_back(Vec3(1.7 * u.x() + 0.3 * u.y(), 0.9 * u.y() - 0.2 * u.z(), 0.6 * u.z() + 0.1 * u.x()));
  }
  return pts;
}

TEST(MassProperties, BoxMatchesClosedForm) {
  const double a = 2.0, b = 3.0, c = 5.0, rho = 2650.0;
  const Vec3 lo(-1.25, 0.5, 7.0);
  const auto p = mass_properties(mesh_of(box_soup(lo, lo + Vec3(a, b, c))), rho);
  const double m = rho * a * b * c;
  expect_rel(p.volume, a * b * c, kRel, "volume");
  expect_rel(p.mass, m, kRel, "mass");
  EXPECT_TRUE(p.centroid.isApprox(lo + 0.5 * Vec3(a, b, c), kRel));
  Mat3 expected = Mat3::Zero();
  expected.diagonal() << m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12;
  expect_mat_near(p.inertia, expected, kRel);
  // ascending principal moments are I_zz < I_yy < I_xx here, along the coordinate axes
  expect_rel(p.principal_moments[0], expected(2, 2), kRel, "I0");
  expect_rel(p.principal_moments[1], expected(1, 1), kRel, "I1");
  expect_rel(p.principal_moments[2], expected(0, 0), kRel, "I2");
  EXPECT_NEAR(std::abs(p.principal_axes(2, 0)), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p.principal_axes(1, 1)), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p.principal_axes(0, 2)), 1.0, 1e-12);
  expect_principal_frame(p);
}

TEST(MassProperties, UnitCubeHasIsotropicInertiaAndCoordinateAxes) {
  const auto p = mass_properties(mesh_of(box_soup(Vec3::Zero(), Vec3::Ones())), 1.0);
  // physics.md §7 check: unit cube I = m/6 1
  expect_mat_near(p.inertia, Mat3::Identity() / 6.0, kRel);
  // degenerate moments: axes stay the coordinate axes instead of an arbitrary rotation
  EXPECT_TRUE(p.principal_axes.cwiseAbs().isApprox(Mat3::Identity(), 1e-12));
}

TEST(MassProperties, FarFromOriginKeepsPrecision) {
  // exact inputs 1e5 m away: a naive origin-based sum would lose ~10 digits to cancellation
  const double a = 2.0, b = 3.0, c = 5.0;
  const Vec3 lo(1e5, -2e5, 3e5);
  const auto p = mass_properties(mesh_of(box_soup(lo, lo + Vec3(a, b, c))), 1.0);
  const double m = a * b * c;
  expect_rel(p.volume, m, kRel, "volume");
  expect_rel(p.inertia(0, 0), m * (b * b + c * c) / 12, kRel, "Ixx");
  expect_rel(p.inertia(1, 1), m * (a * a + c * c) / 12, kRel, "Iyy");
  expect_rel(p.inertia(2, 2), m * (a * a + b * b) / 12, kRel, "Izz");
  EXPECT_NEAR(p.inertia(0, 1), 0.0, kRel * m);
}

TEST(MassProperties, UnitRightTetrahedronMatchesDirichletIntegrals) {
  // integral of x^i y^j z^k over the unit right tetrahedron = i! j! k! / (i+j+k+3)!:
  // V = 1/6, centroid 1/4, about the origin xx = 1/60, xy = 1/120; about the centroid
  // xx = 1/60 - 1/96 = 1/160, xy = 1/120 - 1/96 = -1/480, so I_xx = 2/160 = 1/80, I_xy = 1/480
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  const TriangleSoup soup{{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}};
  const double rho = 3.0;
  const auto p = mass_properties(mesh_of(soup), rho);
  expect_rel(p.volume, 1.0 / 6, kRel, "volume");
  EXPECT_TRUE(p.centroid.isApprox(Vec3::Constant(0.25), kRel));
  Mat3 expected;
  expected << 1.0 / 80, 1.0 / 480, 1.0 / 480, 1.0 / 480, 1.0 / 80, 1.0 / 480, 1.0 / 480, 1.0 / 480, 1.0 / 80;
  expect_mat_near(p.inertia, rho * expected, kRel);
  // eigenvalues of a I + b (J - I): a - b (twice) and a + 2b
  expect_rel(p.principal_moments[0], rho * (1.0 / 80 - 1.0 / 480), kRel, "I0");
  expect_rel(p.principal_moments[1], rho * (1.0 / 80 - 1.0 / 480), kRel, "I1");
  expect_rel(p.principal_moments[2], rho * (1.0 / 80 + 2.0 / 480), kRel, "I2");
  expect_principal_frame(p);
}

TEST(MassProperties, RegularTetrahedronHasInertiaMassEdgeSquaredOverTwenty) {
  // closed form: a regular tetrahedron of edge L has I = m L^2 / 20 about any centroidal axis
  const std::vector<Vec3> pts{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const double edge = std::sqrt(8.0);
  const auto p = mass_properties(mesh_of(convex_hull(pts)), 2.0);
  expect_rel(p.volume, edge * edge * edge / (6 * std::sqrt(2.0)), kRel, "volume");
  expect_mat_near(p.inertia, p.mass * edge * edge / 20 * Mat3::Identity(), kRel);
}

TEST(MassProperties, OctahedronHasInertiaMassASquaredOverFive) {
  // |x|+|y|+|z| <= a: eight right tetrahedra of leg a, V = 4a^3/3, integral of x^2 = 8 a^5/60,
  // so I = (2 * 8 a^5 / 60) / V m = m a^2 / 5
  const double a = 1.5;
  const std::vector<Vec3> pts{{a, 0, 0}, {-a, 0, 0}, {0, a, 0}, {0, -a, 0}, {0, 0, a}, {0, 0, -a}};
  const auto p = mass_properties(mesh_of(convex_hull(pts)), 1.0);
  expect_rel(p.volume, 4 * a * a * a / 3, kRel, "volume");
  expect_mat_near(p.inertia, p.mass * a * a / 5 * Mat3::Identity(), kRel);
}

TEST(MassProperties, IrregularHullMatchesTetrahedralQuadrature) {
  const TriangleSoup soup = convex_hull(random_cloud(42, 300));
  const auto p = mass_properties(mesh_of(soup), 1.0);
  const Oracle o = quadrature_oracle(soup);
  expect_rel(p.volume, o.volume, kRel, "volume");
  EXPECT_LT((p.centroid - o.centroid).norm(), kRel * std::cbrt(o.volume));
  expect_mat_near(p.inertia, o.inertia, kRel);
  // an irregular body: the products of inertia really are exercised
  EXPECT_GT(std::abs(o.inertia(0, 1)), 1e-3 * o.inertia.trace());
  expect_principal_frame(p);
}

TEST(MassProperties, RigidMotionRotatesInertiaAndKeepsPrincipalMoments) {
  const TriangleSoup soup = convex_hull(random_cloud(7, 200));
  const rigid::Quat q = rigid::Quat(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  const Mat3 r = q.toRotationMatrix();
  const Vec3 shift(120.0, -340.0, 56.0);
  TriangleSoup moved;
  for (const auto& t : soup) moved.push_back({r * t.a + shift, r * t.b + shift, r * t.c + shift});
  const double rho = 2650.0;
  const auto p = mass_properties(mesh_of(soup), rho);
  const auto pm = mass_properties(mesh_of(moved), rho);
  expect_rel(pm.volume, p.volume, kRel, "volume");
  expect_rel(pm.mass, p.mass, kRel, "mass");
  EXPECT_LT((pm.centroid - (r * p.centroid + shift)).norm(), kRel * shift.norm());
  expect_mat_near(pm.inertia, r * p.inertia * r.transpose(), kRel);
  for (int k = 0; k < 3; ++k) expect_rel(pm.principal_moments[k], p.principal_moments[k], kRel, "moment");
  // the moved body also agrees with the independent oracle
  const Oracle o = quadrature_oracle(moved);
  expect_mat_near(pm.inertia, rho * o.inertia, kRel);
}

TEST(MassProperties, RejectsNonPositiveOrNonFiniteDensity) {
  const ClosedMesh mesh = mesh_of(box_soup(Vec3::Zero(), Vec3::Ones()));
  for (double rho : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(mass_properties(mesh, rho), std::invalid_argument) << rho;
  }
}

}  // namespace
