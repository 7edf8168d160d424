#include "rigid/dynamics/contact_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/LU>

namespace rigid::dynamics {

Vec3 relative_velocity(const SolverBody& a, const SolverBody& b, const Vec3& ra, const Vec3& rb) {
  return (b.velocity + b.angular_velocity.cross(rb)) - (a.velocity + a.angular_velocity.cross(ra));
}

namespace {

// A normal-only impulse p_n n on b, its opposite on a (lever terms precomputed).
void apply_normal(SolverBody& a, SolverBody& b, const ContactRow& r, double pn) {
  a.velocity -= (a.inverse_mass * pn) * r.normal;
  a.angular_velocity -= pn * r.turn_a;
  b.velocity += (b.inverse_mass * pn) * r.normal;
  b.angular_velocity += pn * r.turn_b;
}

// Relative normal velocity at a row's point: n . (v_b + w_b x r_b - v_a - w_a x r_a), with
// n . (w x r) = w . (r x n) precomputed.
double normal_velocity(const SolverBody& a, const SolverBody& b, const ContactRow& r) {
  return r.normal.dot(b.velocity - a.velocity) + b.angular_velocity.dot(r.rb_n) - a.angular_velocity.dot(r.ra_n);
}

// A patch impulse (force impulse along the tangents at the centre, twisting impulse about n).
void apply_patch(SolverBody& a, SolverBody& b, const FrictionPatch& p, const Eigen::Vector3d& impulse) {
  const Vec3 force = impulse.x() * p.tangent1 + impulse.y() * p.tangent2;
  const Vec3 twist = impulse.z() * p.normal;
  a.velocity -= a.inverse_mass * force;
  a.angular_velocity -= a.inverse_inertia * (p.ra.cross(force) + twist);
  b.velocity += b.inverse_mass * force;
  b.angular_velocity += b.inverse_inertia * (p.rb.cross(force) + twist);
}

// Sliding velocity at the patch centre along the tangents, and twisting rate about the normal.
Eigen::Vector3d patch_velocity(const SolverBody& a, const SolverBody& b, const FrictionPatch& p) {
  const Vec3 u = relative_velocity(a, b, p.ra, p.rb);
  return {p.tangent1.dot(u), p.tangent2.dot(u), p.normal.dot(b.angular_velocity - a.angular_velocity)};
}

// Normal row: p_n = max(0, p_n + m (target - u_n)). Returns the change.
double solve_normal(SolverBody& a, SolverBody& b, ContactRow& r) {
  const double un = normal_velocity(a, b, r);
  const double pn = std::max(0.0, r.normal_impulse + r.normal_mass * (r.target_normal_velocity - un));
  const double change = pn - r.normal_impulse;
  if (change != 0) {
    apply_normal(a, b, r, change);
    r.normal_impulse = pn;
  }
  return change;
}

// The largest change of any body's velocities since `before`, as a multiple of the tolerances.
double largest_motion_change(const std::vector<SolverBody>& bodies, const std::vector<SolverBody>& before,
                             const SolverSettings& settings) {
  double change = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].inverse_mass == 0) continue;
    change = std::max(
        {change, (bodies[i].velocity - before[i].velocity).cwiseAbs().maxCoeff() / settings.velocity_tolerance,
         (bodies[i].angular_velocity - before[i].angular_velocity).cwiseAbs().maxCoeff() / settings.angular_tolerance});
  }
  return change;
}

}  // namespace

void set_tangents(FrictionPatch& p) {
  // any orthonormal pair completing n: the limit is isotropic, so which one is immaterial
  const Vec3& n = p.normal;
  const Vec3 helper =
      std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57735 ? Vec3::UnitY() : Vec3::UnitZ());
  p.tangent1 = n.cross(helper).normalized();
  p.tangent2 = n.cross(p.tangent1);
}

void prepare(const std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows,
             std::vector<FrictionPatch>& patches) {
  for (auto& r : rows) {
    const SolverBody& a = bodies[r.a];
    const SolverBody& b = bodies[r.b];
    r.ra_n = r.ra.cross(r.normal);
    r.rb_n = r.rb.cross(r.normal);
    r.turn_a = a.inverse_inertia * r.ra_n;
    r.turn_b = b.inverse_inertia * r.rb_n;
    const double k = a.inverse_mass + b.inverse_mass + r.ra_n.dot(r.turn_a) + r.rb_n.dot(r.turn_b);
    r.normal_mass = k > 0 ? 1.0 / k : 0.0;
  }
  for (auto& p : patches) {
    const SolverBody& a = bodies[p.a];
    const SolverBody& b = bodies[p.b];
    // J = [t1 at the centre; t2 at the centre; rotation about n], K = J M^-1 J^T
    const Vec3 tangents[2] = {p.tangent1, p.tangent2};
    Vec3 angular_a[3], angular_b[3];
    for (int i = 0; i < 2; ++i) {
      angular_a[i] = p.ra.cross(tangents[i]);
      angular_b[i] = p.rb.cross(tangents[i]);
    }
    angular_a[2] = angular_b[2] = p.normal;
    Eigen::Matrix3d k;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double linear = (i < 2 && j < 2 && i == j) ? a.inverse_mass + b.inverse_mass : 0.0;
        k(i, j) = linear + angular_a[i].dot(a.inverse_inertia * angular_a[j]) +
                  angular_b[i].dot(b.inverse_inertia * angular_b[j]);
      }
    }
    p.mass.setZero();
    if (p.radius > 0) {
      if (k.determinant() > 0) p.mass = k.inverse();
    } else if (k.topLeftCorner<2, 2>().determinant() > 0) {
      // a point contact: sliding only, twisting is free
      p.mass.topLeftCorner<2, 2>() = k.topLeftCorner<2, 2>().inverse();
    }
  }
}

void warm_start(std::vector<SolverBody>& bodies, const std::vector<ContactRow>& rows,
                const std::vector<FrictionPatch>& patches) {
  for (const auto& r : rows) {
    if (r.normal_impulse != 0) apply_normal(bodies[r.a], bodies[r.b], r, r.normal_impulse);
  }
  for (const auto& p : patches) {
    if (!p.impulse.isZero()) apply_patch(bodies[p.a], bodies[p.b], p, p.impulse);
  }
}

SolverResult solve_velocities(std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows,
                              std::vector<FrictionPatch>& patches, const SolverSettings& settings,
                              std::vector<SolverBody>& scratch) {
  SolverResult result;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    scratch = bodies;
    for (auto& p : patches) {
      // invariant (debug builds): a patch names two bodies and a range of rows that exist
      assert(p.a >= 0 && p.b >= 0 && std::size_t(p.a) < bodies.size() && std::size_t(p.b) < bodies.size());
      assert(p.first_row >= 0 && p.row_count >= 0 && std::size_t(p.first_row + p.row_count) <= rows.size());
      SolverBody& a = bodies[p.a];
      SolverBody& b = bodies[p.b];
      double total = 0;
      for (int k = p.first_row; k < p.first_row + p.row_count; ++k) {
        solve_normal(a, b, rows[k]);
        total += rows[k].normal_impulse;
      }
      // Coulomb on the patch: the impulse that stops sliding and twisting, projected radially
      // onto the ellipsoid |(f_1, f_2, tau / radius)| <= mu N
      Eigen::Vector3d impulse = p.impulse - p.mass * patch_velocity(a, b, p);
      const double limit = p.friction * total;
      const double size = std::hypot(impulse.x(), impulse.y(), p.radius > 0 ? impulse.z() / p.radius : 0.0);
      if (size > limit) impulse *= size > 0 ? limit / size : 0.0;
      const Eigen::Vector3d change = impulse - p.impulse;
      if (!change.isZero()) {
        apply_patch(a, b, p, change);
        p.impulse = impulse;
      }
    }
    result.iterations = iteration + 1;
    if (largest_motion_change(bodies, scratch, settings) <= 1.0) {
      result.converged = true;
      break;
    }
  }
  // invariant (debug builds): contacts push, never pull (Signorini: p_n >= 0)
  for ([[maybe_unused]] const auto& r : rows) assert(r.normal_impulse >= 0);
  return result;
}

void solve_correction(const std::vector<SolverBody>& bodies, std::vector<SolverBody>& pseudo,
                      std::vector<ContactRow>& rows, const SolverSettings& settings, std::vector<SolverBody>& scratch) {
  pseudo.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    pseudo[i] = bodies[i];
    pseudo[i].velocity.setZero();
    pseudo[i].angular_velocity.setZero();
  }
  for (auto& r : rows) r.correction_impulse = 0;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    scratch = pseudo;
    for (auto& r : rows) {
      SolverBody& a = pseudo[r.a];
      SolverBody& b = pseudo[r.b];
      const double un = normal_velocity(a, b, r);
      const double p = std::max(0.0, r.correction_impulse + r.normal_mass * (r.correction_velocity - un));
      const double dp = p - r.correction_impulse;
      if (dp == 0) continue;
      apply_normal(a, b, r, dp);
      r.correction_impulse = p;
    }
    if (largest_motion_change(pseudo, scratch, settings) <= 1.0) break;
  }
}

}  // namespace rigid::dynamics
