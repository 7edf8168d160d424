/// Volume, centroid and inertia tensor of a homogeneous closed triangle mesh (physics.md §7).
#include <Eigen/Eigenvalues>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {
namespace {

struct Moments {
  double volume = 0;
  Vec3 first = Vec3::Zero();   // integral of x dV, relative to the origin used
  Mat3 second = Mat3::Zero();  // covariance: integral of x x^T dV, relative to the origin
};

// Blow & Binstock: one signed tetrahedron (origin, a, b, c) per outward triangle (physics.md §7).
Moments integrate(const ClosedMesh& mesh, const Vec3& origin) {
  Moments m;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - origin;
    const Vec3 b = mesh.vertices[t[1]] - origin;
    const Vec3 c = mesh.vertices[t[2]] - origin;
    const double det = a.dot(b.cross(c));
    const Vec3 s = a + b + c;
    m.volume += det / 6.0;
    m.first += (det / 24.0) * s;
    m.second += (det / 120.0) * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  return m;
}

}  // namespace

MassProperties mass_properties(const ClosedMesh& mesh, double density) {
  if (!(std::isfinite(density) && density > 0)) {
    throw std::invalid_argument("mass_properties: density must be positive and finite");
  }
  const auto nv = static_cast<long long>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    for (int v : t) {
      if (v < 0 || v >= nv) throw std::invalid_argument("mass_properties: vertex index out of range");
    }
  }
  if (mesh.triangles.empty()) throw std::invalid_argument("mass_properties: mesh has no triangles");

  // two passes: the vertex mean, then the centroid as origin, so the parallel-axis correction
  // (a difference of large numbers for a far-off mesh) is almost zero
  Vec3 origin = Vec3::Zero();
  for (const Vec3& p : mesh.vertices) origin += p;
  origin /= static_cast<double>(mesh.vertices.size());
  Moments m = integrate(mesh, origin);
  if (!(m.volume > 0) || !std::isfinite(m.volume)) {
    throw std::invalid_argument("mass_properties: mesh encloses no positive volume");
  }
  origin += m.first / m.volume;
  m = integrate(mesh, origin);

  MassProperties p;
  p.volume = m.volume;
  p.mass = density * m.volume;
  const Vec3 offset = m.first / m.volume;  // residual centroid offset, ~rounding
  p.centroid = origin + offset;
  // covariance about the centroid, then I = tr(C) 1 - C (physics.md §7)
  const Mat3 cov = density * m.second - p.mass * offset * offset.transpose();
  Mat3 inertia = cov.trace() * Mat3::Identity() - cov;
  inertia = 0.5 * (inertia + inertia.transpose());
  p.inertia = inertia;
  if (!p.inertia.allFinite() || !std::isfinite(p.mass)) {
    throw std::invalid_argument("mass_properties: mass or inertia overflows");
  }

  // products of inertia at rounding level are zeroed before diagonalising, so a mesh already
  // aligned with its principal axes (a box, a cube) keeps exact coordinate axes
  Mat3 clean = inertia;
  const double scale = inertia.diagonal().cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != j && std::abs(clean(i, j)) <= 1e-14 * scale) clean(i, j) = 0;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(clean);
  p.principal_moments = eig.eigenvalues();  // ascending
  Mat3 axes = eig.eigenvectors();
  // deterministic signs: the largest component of each axis positive, then det = +1
  for (int k = 0; k < 3; ++k) {
    Eigen::Index big = 0;
    axes.col(k).cwiseAbs().maxCoeff(&big);
    if (axes(big, k) < 0) axes.col(k) = -axes.col(k);
  }
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  p.principal_axes = axes;
  // invariants (debug builds): a closed mesh of positive volume has positive mass and principal
  // moments that are non-negative up to rounding, and a proper rotation as its principal axes
  assert(p.mass > 0 && p.volume > 0);
  assert(p.principal_moments.minCoeff() >= -1e-12 * p.principal_moments.cwiseAbs().maxCoeff());
  assert(std::abs(p.principal_axes.determinant() - 1.0) < 1e-9);
  return p;
}

}  // namespace rigid::geometry
