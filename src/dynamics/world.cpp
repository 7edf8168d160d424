#include "rigid/dynamics/world.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace rigid::dynamics {

namespace {

// Speed of the reference impact that sets the largest expected overlap (physics.md §10)
constexpr double kReferenceImpactSpeed = 1.0;  // unit: m/s

// Central-difference critical step of a mass-spring-dashpot of circular frequency omega and
// damping ratio zeta (physics.md §10): damping shortens it, to 1 / (zeta omega) when heavy.
double damped_critical_step(double omega, double zeta) { return 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta); }

}  // namespace

double critical_time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law) {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& body : bodies) {
    if (body.fixed) continue;
    const auto& s = body.shape;
    const double m = s.mass;
    // inverse effective mass of the stiffest mode: translation plus the largest lever arm over the
    // moment of inertia, per principal axis
    double rotational = 0;
    for (int axis = 0; axis < 3; ++axis) {
      double r2 = 0;
      for (const auto& v : s.vertices) r2 = std::max(r2, v.squaredNorm() - v[axis] * v[axis]);
      rotational = std::max(rotational, r2 / s.inertia[axis]);
    }
    const double inverse_mass = 1.0 / m + rotational;
    // the largest expected overlap: the whole block on one subcontact, either striking it at the
    // reference speed (Hertz: 0.4 K_N d^2.5 = m v^2 / 2) or resting its weight on it
    const double v = kReferenceImpactSpeed;
    const double impact = std::pow(5.0 * m * v * v / (4.0 * law.normal_stiffness), 0.4);
    const double resting = std::pow(m * kGravity / law.normal_stiffness, 2.0 / 3.0);
    const double depth = std::max(impact, resting);
    // four subcontacts at that overlap: the Hertz tangent stiffness dF/dd = 1.5 K_N d^0.5 and the
    // damper dF/d(dd/dt) = D K_N d^1.5 of F = K_N d^1.5 (1 + D dd/dt); the linear shear spring K_S
    const double normal_stiffness = 1.5 * law.normal_stiffness * std::sqrt(depth);
    const double normal_damping = law.damping * law.normal_stiffness * depth * std::sqrt(depth);
    const double omega_normal = std::sqrt(4.0 * normal_stiffness * inverse_mass);
    const double zeta = 4.0 * normal_damping * inverse_mass / (2.0 * omega_normal);
    const double omega_shear = std::sqrt(4.0 * law.shear_stiffness * inverse_mass);
    dt = std::min({dt, damped_critical_step(omega_normal, std::max(0.0, zeta)), 2.0 / omega_shear});
  }
  return std::isfinite(dt) ? dt : 1e-3;
}

double rigid_time_step(const std::vector<BodyDef>& bodies, double safety) {
  double radius = std::numeric_limits<double>::infinity();
  for (const auto& body : bodies) {
    if (!body.fixed) radius = std::min(radius, body.shape.bounding_radius);
  }
  if (!std::isfinite(radius)) return 1e-3;
  return safety / 50.0 * std::sqrt(radius / kGravity);
}

double time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law, const StepSettings& settings) {
  if (settings.dt > 0) return settings.dt;
  if (law.method == contact::ContactMethod::rigid) return rigid_time_step(bodies, settings.safety);
  // the stability limit, and never coarser than the rigid model's step: a soft spring's long
  // period does not make a coarse step resolve the rocking
  return settings.safety * std::min(critical_time_step(bodies, law), rigid_time_step(bodies, 1.0));
}

namespace {

// The stepper of the law's contact model, its buffers sized for the core's pairs.
std::variant<PenaltyStepper, RigidStepper> make_stepper(const WorldCore& core) {
  if (core.law.method == contact::ContactMethod::rigid) return RigidStepper(core);
  return PenaltyStepper(core);
}

}  // namespace

World::World(std::vector<BodyDef> bodies, const contact::ContactLaw& law, const StepSettings& settings)
    : core_(std::move(bodies), law, settings), stepper_(make_stepper(core_)) {
  core_.dt = time_step(core_.defs, core_.law, core_.settings);
  refresh();
}

void World::refresh() {
  core_.refresh_geometry();
  // the rigid model finds its contacts at the start of each step; the penalty model needs the
  // forces of the current state for its first half kick
  if (auto* penalty = std::get_if<PenaltyStepper>(&stepper_)) penalty->compute_forces(core_, 0.0);
}

void World::step(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end) {
  std::visit([&](auto& stepper) { stepper.step(core_, dt, ground_velocity_start, ground_velocity_end); }, stepper_);
#ifndef NDEBUG
  // invariant (debug builds): every block's attitude stays a unit quaternion (a non-finite state is
  // an outcome the run reports, not a broken invariant)
  for (const auto& s : core_.states) {
    assert(!s.orientation.coeffs().allFinite() || std::abs(s.orientation.norm() - 1.0) < 1e-9);
  }
#endif
}

void World::carry_with_ground(double t_end, const Vec3& displacement, const Vec3& v_start, const Vec3& v_end) {
  if (auto* rigid = std::get_if<RigidStepper>(&stepper_)) rigid->set_pedestal_velocity(v_end);
  core_.carry_with_ground(t_end, displacement, v_start, v_end);
}

double World::subcontact_load(std::size_t pair, std::size_t k) const {
  return std::visit([&](const auto& stepper) { return stepper.subcontact_load(core_, pair, k); }, stepper_);
}

void World::summarize_contacts(ContactSummary& out) const {
  out.pairs.clear();
  out.points.clear();
  for (std::size_t j = 0; j < core_.pairs.size(); ++j) {
    const PairContact& p = core_.pairs[j];
    ContactSummary::Pair s;
    s.a = p.a;
    s.b = p.b;
    s.normal = p.normal;
    s.first = out.points.size();
    for (std::size_t k = 0; k < p.points.size(); ++k) {
      const double load = subcontact_load(j, k);
      if (load > 0) out.points.push_back({p.points[k].point, load});
    }
    s.loaded = out.points.size() - s.first;
    out.pairs.push_back(s);
  }
}

double World::elastic_energy() const {
  const auto* penalty = std::get_if<PenaltyStepper>(&stepper_);
  return penalty ? penalty->elastic_energy(core_) : 0.0;  // rigid contacts store no energy
}

}  // namespace rigid::dynamics
