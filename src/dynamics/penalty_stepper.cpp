#include "rigid/dynamics/penalty_stepper.hpp"

#include <algorithm>
#include <cmath>

namespace rigid::dynamics {

PenaltyStepper::PenaltyStepper(const WorldCore& world)
    : springs_(world.pairs.size()),
      forces_(world.defs.size(), Vec3::Zero()),
      torques_(world.defs.size(), Vec3::Zero()) {
  for (std::size_t j = 0; j < world.pairs.size(); ++j) {
    const std::size_t cap = world.pairs[j].points.capacity();
    springs_[j].subs.reserve(cap);
    springs_[j].next_subs.reserve(cap);
  }
}

void PenaltyStepper::step(WorldCore& world, double dt, const Vec3& ground_velocity_start,
                          const Vec3& ground_velocity_end) {
  const auto& defs = world.defs;
  const Vec3 ground_velocity = 0.5 * (ground_velocity_start + ground_velocity_end);
  // contact force on the pedestals at the start of the step (all move with the same velocity)
  Vec3 pedestal_force_start = Vec3::Zero();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) pedestal_force_start += world.contact_force[i];
  }
  world.move_pedestals(dt, ground_velocity);
  for (std::size_t i = 0; i < defs.size(); ++i) {
    auto& s = world.states[i];
    if (defs[i].fixed) continue;
    s.velocity += (0.5 * dt / defs[i].shape.mass) * forces_[i];
    s.angular_momentum += 0.5 * dt * torques_[i];
    s.position += dt * s.velocity;
    if (world.effects.distance_skin) world.travel[i] += dt * (s.velocity - ground_velocity).norm();
    world.drift_rotation(static_cast<int>(i), dt);
    world.rotations[i] = s.orientation.toRotationMatrix();
    world.update_world_vertices(static_cast<int>(i));
  }
  world.time += dt;
  compute_forces(world, dt);
  // Work of the pedestals on the free blocks over the step: their displacement dt * v_mid against
  // the mean of the contact forces at both ends (trapezoid). This is what the velocity-Verlet kicks
  // transmit, so kinetic + potential + elastic energy changes by exactly this work, up to a bounded
  // O(dt^2) term and the contacts' dissipation. (The end-of-step force alone made an O(dt) error
  // that accumulated: -1.6 J in 30 s for a 166 kg block riding a 0.3 g, 2 Hz pedestal.)
  Vec3 pedestal_force_end = Vec3::Zero();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) pedestal_force_end += world.contact_force[i];
  }
  world.pedestal_work -= 0.5 * dt * (pedestal_force_start + pedestal_force_end).dot(ground_velocity);
  for (std::size_t i = 0; i < defs.size(); ++i) {
    auto& s = world.states[i];
    if (defs[i].fixed) {
      s.velocity = ground_velocity_end;
      continue;
    }
    s.velocity += (0.5 * dt / defs[i].shape.mass) * forces_[i];
    s.angular_momentum += 0.5 * dt * torques_[i];
  }
  ++world.stats.steps;
}

void PenaltyStepper::compute_forces(WorldCore& world, double dt) {
  const auto& defs = world.defs;
  const contact::ContactLaw& base_law = world.law;
  const std::size_t n = defs.size();
  for (std::size_t i = 0; i < n; ++i) {
    forces_[i] = defs[i].fixed ? Vec3::Zero() : Vec3(0, 0, -world.settings.gravity * defs[i].shape.mass);
    torques_[i].setZero();
    world.contact_force[i].setZero();
  }
  world.max_overlap = 0;
  for (std::size_t j = 0; j < world.pairs.size(); ++j) {
    PairContact& p = world.pairs[j];
    PairSprings& springs = springs_[j];
    const auto& da = defs[p.a];
    const auto& db = defs[p.b];
    const auto& sa = world.states[p.a];
    const auto& sb = world.states[p.b];
    if (world.pair_apart(p, 0.0)) {
      springs.subs.clear();
      continue;
    }
    ++world.stats.pair_tests;
    ++p.tests;
    contact::PlacedHull ha{&world.contact_piece(p.a, p.piece_a), world.piece_vertices(p.a, p.piece_a), Vec3::Zero(),
                           world.rotations[p.a], sa.position};
    contact::PlacedHull hb{&world.contact_piece(p.b, p.piece_b), world.piece_vertices(p.b, p.piece_b), Vec3::Zero(),
                           world.rotations[p.b], sb.position};
    const contact::CommonPlane cp = contact::find_common_plane(ha, hb, p.normal, p.hints);
    p.normal = cp.normal;
    p.overlap = cp.overlap;
    if (cp.overlap <= 0) {
      springs.subs.clear();
      p.points.clear();
      continue;
    }
    p.points.clear();
    contact::collect_subcontacts(ha, hb, cp, p.points);
    const Vec3 wa = world.angular_velocity(p.a);
    const Vec3 wb = world.angular_velocity(p.b);
    const Vec3& n = cp.normal;
    springs.next_subs.clear();
    // stiffness per patch, not per vertex: a patch of many subcontacts (a finely meshed face)
    // shares the springs of the study's four-corner block face (physics.md §11), so a rock and
    // the same rock meshed finer carry the same load on the same indentation. The count is
    // weighted by depth, n = sum (d_i / d_max)^1.5, so a subcontact entering at zero depth changes
    // nothing: the force stays continuous (a jump in it would pump energy into a bouncing block)
    double deepest = 0, sum = 0;
    for (const auto& pt : p.points) {
      const double load = pt.overlap * std::sqrt(pt.overlap);
      deepest = std::max(deepest, load);
      sum += load;
    }
    const double count = deepest > 0 ? sum / deepest : 0.0;
    springs.stiffness_weight = count > 4 ? 4.0 / count : 1.0;
    contact::ContactLaw weighted;
    if (count > 4) {
      weighted = base_law;
      weighted.normal_stiffness *= springs.stiffness_weight;
      weighted.shear_stiffness *= springs.stiffness_weight;
    }
    const contact::ContactLaw& law = count > 4 ? weighted : base_law;
    Vec3 total = Vec3::Zero();
    double pair_slip = 0;
    for (const auto& pt : p.points) {
      Vec3 shear = Vec3::Zero();
      for (const auto& old : springs.subs) {
        if (old.key == pt.key) {
          shear = old.shear_force;
          break;
        }
      }
      const Vec3 ra = pt.point - sa.position;
      const Vec3 rb = pt.point - sb.position;
      const Vec3 relative = (sb.velocity + wb.cross(rb)) - (sa.velocity + wa.cross(ra));
      const double normal_speed = n.dot(relative);
      const Vec3 tangential_step = (relative - normal_speed * n) * dt;
      double slip = 0;
      const Vec3 f = contact::subcontact_force(law, n, pt.overlap, -normal_speed, tangential_step, shear, slip);
      forces_[p.b] += f;
      torques_[p.b] += rb.cross(f);
      forces_[p.a] -= f;
      torques_[p.a] -= ra.cross(f);
      total += f;
      pair_slip = std::max(pair_slip, slip);
      world.max_overlap = std::max(world.max_overlap, pt.overlap);
      springs.next_subs.push_back({pt.key, shear});
    }
    std::swap(springs.subs, springs.next_subs);
    world.contact_force[p.b] += total;
    world.contact_force[p.a] -= total;
    ++world.stats.contact_steps;
    // slip bookkeeping only where some subcontact reached the Coulomb cap (adding 0 is exact)
    if (pair_slip > 0) {
      ++world.stats.sliding_steps;
      if (!da.fixed) world.slip[p.a] += pair_slip;
      if (!db.fixed) world.slip[p.b] += pair_slip;
    }
  }
  if (world.settings.local_damping > 0) {
    // Itasca local damping: oppose the unbalanced force where it drives motion (physics.md §9)
    const double alpha = world.settings.local_damping;
    for (std::size_t i = 0; i < n; ++i) {
      if (defs[i].fixed) continue;
      const Vec3 w = world.angular_velocity(static_cast<int>(i));
      const Vec3& v = world.states[i].velocity;
      for (int k = 0; k < 3; ++k) {
        const double fv = forces_[i][k] * v[k];
        if (fv != 0) forces_[i][k] -= alpha * std::abs(forces_[i][k]) * (v[k] > 0 ? 1 : -1);
        const double tw = torques_[i][k] * w[k];
        if (tw != 0) torques_[i][k] -= alpha * std::abs(torques_[i][k]) * (w[k] > 0 ? 1 : -1);
      }
    }
  }
}

double PenaltyStepper::subcontact_load(const WorldCore& world, std::size_t pair, std::size_t k) const {
  const double d = world.pairs[pair].points[k].overlap;
  return springs_[pair].stiffness_weight * world.law.normal_stiffness * d * std::sqrt(d);
}

double PenaltyStepper::elastic_energy(const WorldCore& world) const {
  double e = 0;
  for (std::size_t j = 0; j < world.pairs.size(); ++j) {
    const PairContact& p = world.pairs[j];
    if (p.overlap <= 0) continue;
    const double w = springs_[j].stiffness_weight;
    for (const auto& sub : springs_[j].subs) e += 0.5 * sub.shear_force.squaredNorm() / (w * world.law.shear_stiffness);
    for (const auto& pt : p.points) e += 0.4 * w * world.law.normal_stiffness * std::pow(pt.overlap, 2.5);
  }
  return e;
}

}  // namespace rigid::dynamics
