#include "rigid/dynamics/world.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rigid::dynamics {

double critical_time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law) {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& body : bodies) {
    if (body.fixed) continue;
    const auto& s = body.shape;
    const double m = s.mass;
    // Hertz tangent stiffness at the peak indentation of a 1 m/s normal impact (physics.md §10)
    const double v_ref = 1.0;
    const double depth = std::pow(5.0 * m * v_ref * v_ref / (4.0 * law.normal_stiffness), 0.4);
    const double k = std::max(law.shear_stiffness, 1.5 * law.normal_stiffness * std::sqrt(depth));
    // largest lever arm over moment of inertia, per principal axis
    double rotational = 0;
    for (int axis = 0; axis < 3; ++axis) {
      double r2 = 0;
      for (const auto& v : s.vertices) r2 = std::max(r2, v.squaredNorm() - v[axis] * v[axis]);
      rotational = std::max(rotational, r2 / s.inertia[axis]);
    }
    const double omega = std::sqrt(4.0 * k * (1.0 / m + rotational));
    dt = std::min(dt, 2.0 / omega);
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

World::World(std::vector<BodyDef> bodies, const contact::ContactLaw& law,
             const StepSettings& settings)
    : defs_(std::move(bodies)), law_(law), settings_(settings) {
  const std::size_t n = defs_.size();
  states_.resize(n);
  world_vertices_.resize(n);
  piece_vertices_.resize(n);
  rotations_.resize(n);
  forces_.assign(n, Vec3::Zero());
  torques_.assign(n, Vec3::Zero());
  contact_force_.assign(n, Vec3::Zero());
  slip_.assign(n, 0.0);
  travel_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& d = defs_[i];
    auto& s = states_[i];
    // invariant (debug builds): a free block has positive mass and principal moments
    assert(d.fixed || (d.shape.mass > 0 && (d.shape.inertia.array() > 0).all()));
    s.position = d.position;
    s.orientation = d.orientation.normalized();
    s.velocity = d.velocity;
    const Mat3 r = s.orientation.toRotationMatrix();
    s.angular_momentum = r * d.shape.inertia.asDiagonal() * r.transpose() * d.angular_velocity;
    world_vertices_[i].resize(d.shape.vertices.size());
    for (const auto& piece : d.pieces) piece_vertices_[i].emplace_back(piece.vertices.size());
  }
  // every pair that can ever touch: two fixed blocks never interact
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      if (defs_[a].fixed && defs_[b].fixed) {
        ++fixed_fixed_pairs_;
        continue;
      }
      // one pair per two contact pieces (one piece each for plain blocks)
      const std::size_t pieces_a = std::max<std::size_t>(1, defs_[a].pieces.size());
      const std::size_t pieces_b = std::max<std::size_t>(1, defs_[b].pieces.size());
      for (std::size_t ka = 0; ka < pieces_a; ++ka) {
        for (std::size_t kb = 0; kb < pieces_b; ++kb) {
          PairContact p;
          p.a = static_cast<int>(a);
          p.b = static_cast<int>(b);
          p.piece_a = static_cast<int>(ka);
          p.piece_b = static_cast<int>(kb);
          const Vec3 d = defs_[b].position - defs_[a].position;
          p.normal = d.norm() > 0 ? Vec3(d.normalized()) : Vec3(0, 0, 1);
          const std::size_t cap =
              contact_piece(p.a, p.piece_a).vertices.size() + contact_piece(p.b, p.piece_b).vertices.size() + 1;
          p.subs.reserve(cap);
          p.next_subs.reserve(cap);
          p.points.reserve(cap);
          pairs_.push_back(std::move(p));
        }
      }
    }
  }
  if (law_.model == contact::ContactModel::rigid) {
    // the solver's buffers at their final size now, so that a step never allocates (the first
    // position correction or a new patch would otherwise grow them mid-run)
    for (auto* bodies : {&solver_bodies_, &free_bodies_, &pseudo_bodies_, &solver_scratch_}) bodies->reserve(n);
    patches_.reserve(pairs_.size());
    member_begin_.reserve(pairs_.size() + 1);
    member_pairs_.reserve(pairs_.size());
    has_compound_ = std::any_of(defs_.begin(), defs_.end(), [](const BodyDef& d) { return d.pieces.size() > 1; });
    if (has_compound_) {
      merged_patches_.reserve(pairs_.size());
      merged_members_.reserve(pairs_.size());
      merged_begin_.reserve(pairs_.size() + 1);
      patch_taken_.reserve(pairs_.size());
    }
  }
  dt_ = time_step(defs_, law_, settings_);
  refresh();
}

double time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law, const StepSettings& settings) {
  if (settings.dt > 0) return settings.dt;
  if (law.model == contact::ContactModel::rigid) return rigid_time_step(bodies, settings.safety);
  return settings.safety * critical_time_step(bodies, law);
}

void World::refresh() {
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    rotations_[i] = states_[i].orientation.toRotationMatrix();
    update_world_vertices(static_cast<int>(i));
  }
  // the rigid model finds its contacts at the start of each step; the penalty model needs the
  // forces of the current state for its first half kick
  if (law_.model == contact::ContactModel::penalty) compute_forces(0.0);
}

void World::update_world_vertices(int i) {
  const auto& body = defs_[i].shape.vertices;
  const Mat3& r = rotations_[i];
  const Vec3& x = states_[i].position;
  auto& out = world_vertices_[i];
  for (std::size_t k = 0; k < body.size(); ++k) out[k] = r * body[k] + x;
  const auto& pieces = defs_[i].pieces;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const auto& local = pieces[p].vertices;
    auto& world = piece_vertices_[i][p];
    for (std::size_t k = 0; k < local.size(); ++k) world[k] = r * local[k] + x;
  }
}

void World::shift_world_vertices(int i, const Vec3& shift) {
  for (auto& v : world_vertices_[i]) v += shift;
  for (auto& piece : piece_vertices_[i]) {
    for (auto& v : piece) v += shift;
  }
}

void World::shift_world_vertices_xy(int i, double dx, double dy) {
  auto shift = [dx, dy](std::vector<Vec3>& vertices) {
    for (auto& v : vertices) {
      v.x() += dx;
      v.y() += dy;
    }
  };
  shift(world_vertices_[i]);
  for (auto& piece : piece_vertices_[i]) shift(piece);
}

Vec3 World::angular_velocity(int i) const {
  if (defs_[i].fixed) return Vec3::Zero();
  const Mat3& r = rotations_[i];
  const Vec3 body_l = r.transpose() * states_[i].angular_momentum;
  return r * body_l.cwiseQuotient(defs_[i].shape.inertia);
}

void World::drift_rotation(int i, double dt) {
  auto& s = states_[i];
  const Vec3& inertia = defs_[i].shape.inertia;
  const Vec3& l = s.angular_momentum;
  Quat q = s.orientation;
  if (settings_.rotation == RotationIntegrator::splitting) {
    // exact rotations about body axes 3,2,1,2,3 with steps h/2,h/2,h,h/2,h/2 (physics.md §8)
    static constexpr int kAxes[5] = {2, 1, 0, 1, 2};
    static constexpr double kFractions[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
    for (int k = 0; k < 5; ++k) {
      const int axis = kAxes[k];
      const Vec3 body_l = q.conjugate() * l;
      const double half_angle = 0.5 * kFractions[k] * dt * body_l[axis] / inertia[axis];
      Quat r(std::cos(half_angle), 0, 0, 0);
      r.vec()[axis] = std::sin(half_angle);
      q = q * r;
    }
  } else {
    // RK4 on q' = q (0, w_body) / 2, w_body = I^-1 q* L q, with L fixed over the step
    auto derivative = [&](const Quat& qq) {
      const Vec3 w = (qq.conjugate() * l).cwiseQuotient(inertia);
      Quat wq(0, w.x(), w.y(), w.z());
      Quat d = qq * wq;
      d.coeffs() *= 0.5;
      return d;
    };
    auto add = [](const Quat& a, const Quat& d, double h) {
      Quat r;
      r.coeffs() = a.coeffs() + h * d.coeffs();
      return r;
    };
    const Quat k1 = derivative(q);
    const Quat k2 = derivative(add(q, k1, 0.5 * dt));
    const Quat k3 = derivative(add(q, k2, 0.5 * dt));
    const Quat k4 = derivative(add(q, k3, dt));
    q.coeffs() += (dt / 6.0) * (k1.coeffs() + 2.0 * k2.coeffs() + 2.0 * k3.coeffs() + k4.coeffs());
  }
  q.normalize();
  s.orientation = q;
}

void World::step(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end) {
  if (law_.model == contact::ContactModel::rigid) {
    step_rigid(dt, ground_velocity_start, ground_velocity_end);
  } else {
    step_penalty(dt, ground_velocity_start, ground_velocity_end);
  }
#ifndef NDEBUG
  // invariant (debug builds): every block's attitude stays a unit quaternion (a non-finite state is
  // an outcome the run reports, not a broken invariant)
  for (const auto& s : states_) {
    assert(!s.orientation.coeffs().allFinite() || std::abs(s.orientation.norm() - 1.0) < 1e-9);
  }
#endif
}

void World::move_pedestals(double dt, const Vec3& ground_velocity) {
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    if (!defs_[i].fixed) continue;
    auto& s = states_[i];
    // pedestals follow the ground: trapezoid of the linearly interpolated velocity
    s.velocity = ground_velocity;
    if (effects_.vertical_ground) {
      s.position += dt * ground_velocity;
      shift_world_vertices(static_cast<int>(i), dt * ground_velocity);
    } else {
      // no vertical component: the same sums in x and y, z left alone (it would add 0 exactly)
      const double dx = dt * ground_velocity.x(), dy = dt * ground_velocity.y();
      s.position.x() += dx;
      s.position.y() += dy;
      shift_world_vertices_xy(static_cast<int>(i), dx, dy);
    }
  }
}

bool World::pair_apart(PairContact& p, double margin) {
  const auto& da = defs_[p.a];
  const auto& db = defs_[p.b];
  // skin: the spheres were further apart than the bodies have travelled since
  const double travel = effects_.distance_skin ? travel_[p.a] + travel_[p.b] : 0.0;
  if (p.skin_gap > 0 && travel - p.skin_travel < p.skin_gap) {
    ++stats_.pairs_culled;
    return true;
  }
  // bounding spheres apart: no contact possible this step
  const auto& pa = contact_piece(p.a, p.piece_a);
  const auto& pb = contact_piece(p.b, p.piece_b);
  const double radii = pa.bounding_radius + pb.bounding_radius;
  Vec3 centre_a = states_[p.a].position, centre_b = states_[p.b].position;
  if (!da.pieces.empty()) centre_a += rotations_[p.a] * pa.bounding_centre;
  if (!db.pieces.empty()) centre_b += rotations_[p.b] * pb.bounding_centre;
  const double gap = (centre_b - centre_a).norm() - radii;
  if (gap > margin) {
    p.subs.clear();
    p.points.clear();
    p.overlap = -gap;
    ++stats_.pairs_skipped;
    if (effects_.distance_skin) {
      // the margin covers the rounding of positions summed over millions of steps
      p.skin_gap = gap - margin - 1e-6 * radii;
      p.skin_travel = travel;
    }
    return true;
  }
  p.skin_gap = -1;
  return false;
}

void World::step_penalty(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end) {
  const Vec3 ground_velocity = 0.5 * (ground_velocity_start + ground_velocity_end);
  // contact force on the pedestals at the start of the step (all move with the same velocity)
  Vec3 pedestal_force_start = Vec3::Zero();
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    if (defs_[i].fixed) pedestal_force_start += contact_force_[i];
  }
  move_pedestals(dt, ground_velocity);
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    auto& s = states_[i];
    if (defs_[i].fixed) continue;
    s.velocity += (0.5 * dt / defs_[i].shape.mass) * forces_[i];
    s.angular_momentum += 0.5 * dt * torques_[i];
    s.position += dt * s.velocity;
    if (effects_.distance_skin) travel_[i] += dt * (s.velocity - ground_velocity).norm();
    drift_rotation(static_cast<int>(i), dt);
    rotations_[i] = s.orientation.toRotationMatrix();
    update_world_vertices(static_cast<int>(i));
  }
  time_ += dt;
  compute_forces(dt);
  // Work of the pedestals on the free blocks over the step: their displacement dt * v_mid against
  // the mean of the contact forces at both ends (trapezoid). This is what the velocity-Verlet kicks
  // transmit, so kinetic + potential + elastic energy changes by exactly this work, up to a bounded
  // O(dt^2) term and the contacts' dissipation. (The end-of-step force alone made an O(dt) error
  // that accumulated: -1.6 J in 30 s for a 166 kg block riding a 0.3 g, 2 Hz pedestal.)
  Vec3 pedestal_force_end = Vec3::Zero();
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    if (defs_[i].fixed) pedestal_force_end += contact_force_[i];
  }
  pedestal_work_ -= 0.5 * dt * (pedestal_force_start + pedestal_force_end).dot(ground_velocity);
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    auto& s = states_[i];
    if (defs_[i].fixed) {
      s.velocity = ground_velocity_end;
      continue;
    }
    s.velocity += (0.5 * dt / defs_[i].shape.mass) * forces_[i];
    s.angular_momentum += 0.5 * dt * torques_[i];
  }
  ++stats_.steps;
}

void World::compute_forces(double dt) {
  const std::size_t n = defs_.size();
  for (std::size_t i = 0; i < n; ++i) {
    forces_[i] = defs_[i].fixed ? Vec3::Zero() : Vec3(0, 0, -settings_.gravity * defs_[i].shape.mass);
    torques_[i].setZero();
    contact_force_[i].setZero();
  }
  max_overlap_ = 0;
  for (auto& p : pairs_) {
    const auto& da = defs_[p.a];
    const auto& db = defs_[p.b];
    const auto& sa = states_[p.a];
    const auto& sb = states_[p.b];
    if (pair_apart(p, 0.0)) continue;
    ++stats_.pair_tests;
    ++p.tests;
    contact::PlacedHull ha{&contact_piece(p.a, p.piece_a), piece_vertices(p.a, p.piece_a), Vec3::Zero(),
                           rotations_[p.a], sa.position};
    contact::PlacedHull hb{&contact_piece(p.b, p.piece_b), piece_vertices(p.b, p.piece_b), Vec3::Zero(),
                           rotations_[p.b], sb.position};
    const contact::CommonPlane cp = contact::find_common_plane(ha, hb, p.normal, p.hints);
    p.normal = cp.normal;
    p.overlap = cp.overlap;
    if (cp.overlap <= 0) {
      p.subs.clear();
      p.points.clear();
      continue;
    }
    p.points.clear();
    contact::collect_subcontacts(ha, hb, cp, p.points);
    const Vec3 wa = angular_velocity(p.a);
    const Vec3 wb = angular_velocity(p.b);
    const Vec3& n = cp.normal;
    p.next_subs.clear();
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
    p.stiffness_weight = count > 4 ? 4.0 / count : 1.0;
    contact::ContactLaw weighted;
    if (count > 4) {
      weighted = law_;
      weighted.normal_stiffness *= p.stiffness_weight;
      weighted.shear_stiffness *= p.stiffness_weight;
    }
    const contact::ContactLaw& law = count > 4 ? weighted : law_;
    Vec3 total = Vec3::Zero();
    double pair_slip = 0;
    for (const auto& pt : p.points) {
      Vec3 shear = Vec3::Zero();
      for (const auto& old : p.subs) {
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
      const Vec3 f = contact::subcontact_force(law, n, pt.overlap, -normal_speed, tangential_step,
                                               shear, slip);
      forces_[p.b] += f;
      torques_[p.b] += rb.cross(f);
      forces_[p.a] -= f;
      torques_[p.a] -= ra.cross(f);
      total += f;
      pair_slip = std::max(pair_slip, slip);
      max_overlap_ = std::max(max_overlap_, pt.overlap);
      p.next_subs.push_back({pt.key, shear});
    }
    std::swap(p.subs, p.next_subs);
    contact_force_[p.b] += total;
    contact_force_[p.a] -= total;
    ++stats_.contact_steps;
    // slip bookkeeping only where some subcontact reached the Coulomb cap (adding 0 is exact)
    if (pair_slip > 0) {
      ++stats_.sliding_steps;
      if (!da.fixed) slip_[p.a] += pair_slip;
      if (!db.fixed) slip_[p.b] += pair_slip;
    }
  }
  if (settings_.local_damping > 0) {
    // Itasca local damping: oppose the unbalanced force where it drives motion (physics.md §9)
    const double alpha = settings_.local_damping;
    for (std::size_t i = 0; i < n; ++i) {
      if (defs_[i].fixed) continue;
      const Vec3 w = angular_velocity(static_cast<int>(i));
      for (int k = 0; k < 3; ++k) {
        const double fv = forces_[i][k] * states_[i].velocity[k];
        if (fv != 0) forces_[i][k] -= alpha * std::abs(forces_[i][k]) * (states_[i].velocity[k] > 0 ? 1 : -1);
        const double tw = torques_[i][k] * w[k];
        if (tw != 0) torques_[i][k] -= alpha * std::abs(torques_[i][k]) * (w[k] > 0 ? 1 : -1);
      }
    }
  }
}

void World::carry_with_ground(double t_end, const Vec3& displacement, const Vec3& v_start,
                              const Vec3& v_end) {
  const Vec3 dv = v_end - v_start;
  pedestal_velocity_ = v_end;
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    auto& s = states_[i];
    s.position += displacement;
    shift_world_vertices(static_cast<int>(i), displacement);
    if (defs_[i].fixed) {
      s.velocity = v_end;
      continue;
    }
    s.velocity += dv;
    // the contact force carrying the block is m (a_ground + g z), whose work along the ground's
    // path is the change of m |v_ground|^2 / 2 plus m g dz
    const double m = defs_[i].shape.mass;
    pedestal_work_ += 0.5 * m * (v_end.squaredNorm() - v_start.squaredNorm()) +
                      m * settings_.gravity * displacement.z();
  }
  time_ = t_end;
}

double World::kinetic_energy() const {
  double e = 0;
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    if (defs_[i].fixed) continue;
    const auto& s = states_[i];
    const Vec3 body_l = rotations_[i].transpose() * s.angular_momentum;
    e += 0.5 * defs_[i].shape.mass * s.velocity.squaredNorm() +
         0.5 * body_l.cwiseProduct(body_l).cwiseQuotient(defs_[i].shape.inertia).sum();
  }
  return e;
}

double World::potential_energy() const {
  double e = 0;
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    if (!defs_[i].fixed) e += defs_[i].shape.mass * settings_.gravity * states_[i].position.z();
  }
  return e;
}

double World::subcontact_load(const PairContact& pair, std::size_t k) const {
  if (law_.model == contact::ContactModel::rigid) return pair.subs[k].normal_impulse / dt_;
  const double d = pair.points[k].overlap;
  return pair.stiffness_weight * law_.normal_stiffness * d * std::sqrt(d);
}

void World::summarize_contacts(ContactSummary& out) const {
  out.pairs.clear();
  out.points.clear();
  for (const auto& p : pairs_) {
    ContactSummary::Pair s;
    s.a = p.a;
    s.b = p.b;
    s.normal = p.normal;
    s.first = out.points.size();
    for (std::size_t k = 0; k < p.points.size(); ++k) {
      const double load = subcontact_load(p, k);
      if (load > 0) out.points.push_back({p.points[k].point, load});
    }
    s.loaded = out.points.size() - s.first;
    out.pairs.push_back(s);
  }
}

double World::elastic_energy() const {
  if (law_.model == contact::ContactModel::rigid) return 0;  // rigid contacts store no energy
  double e = 0;
  for (const auto& p : pairs_) {
    if (p.overlap <= 0) continue;
    const double w = p.stiffness_weight;
    for (const auto& sub : p.subs) e += 0.5 * sub.shear_force.squaredNorm() / (w * law_.shear_stiffness);
    for (const auto& pt : p.points) {
      e += 0.4 * w * law_.normal_stiffness * std::pow(pt.overlap, 2.5);
    }
  }
  return e;
}

}  // namespace rigid::dynamics
