// The rigid contact model's time step (physics.md §12): Moreau-Jean time stepping with the
// existing narrow phase (common plane, subcontacts and their persistent keys) giving the rows.
#include "rigid/dynamics/rigid_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigid::dynamics {
namespace {

// Contacts open by less than this fraction of the smaller block's bounding radius are rows of the
// solver already (speculative contacts: they may close within the step, not cross).
constexpr double kMarginFraction = 0.02;
// Penetration left alone (unit: fraction of the smaller bounding radius) and the fraction of the
// rest the split impulse removes per step: small, so the correction never throws a block.
constexpr double kSlopFraction = 1e-5;
constexpr double kCorrectionRate = 0.2;

Mat3 world_inverse_inertia(const Mat3& rotation, const Vec3& inertia) {
  return rotation * inertia.cwiseInverse().asDiagonal() * rotation.transpose();
}

}  // namespace

RigidStepper::RigidStepper(const WorldCore& world) : impulses_(world.pairs.size()) {
  const std::size_t n = world.defs.size();
  const std::size_t pairs = world.pairs.size();
  for (std::size_t j = 0; j < pairs; ++j) {
    const std::size_t cap = world.pairs[j].points.capacity();
    impulses_[j].subs.reserve(cap);
    impulses_[j].next_subs.reserve(cap);
  }
  // the solver's buffers at their final size now, so that a step never allocates (the first
  // position correction or a new patch would otherwise grow them mid-run)
  for (auto* bodies : {&solver_bodies_, &free_bodies_, &pseudo_bodies_, &solver_scratch_}) bodies->reserve(n);
  patches_.reserve(pairs);
  member_begin_.reserve(pairs + 1);
  member_pairs_.reserve(pairs);
  has_compound_ =
      std::any_of(world.defs.begin(), world.defs.end(), [](const BodyDef& d) { return d.pieces.size() > 1; });
  if (has_compound_) {
    merged_patches_.reserve(pairs);
    merged_members_.reserve(pairs);
    merged_begin_.reserve(pairs + 1);
    patch_taken_.reserve(pairs);
  }
}

double RigidStepper::subcontact_load(const WorldCore& world, std::size_t pair, std::size_t k) const {
  return impulses_[pair].subs[k].normal_impulse / world.dt;
}

void RigidStepper::step(WorldCore& world, double dt, const Vec3& ground_velocity_start,
                        const Vec3& ground_velocity_end) {
  // the pedestals move by the exact integral of the ground velocity over the step; the contacts
  // see that mean velocity, so a block stuck to a pedestal moves exactly with it
  const Vec3 ground_velocity = 0.5 * (ground_velocity_start + ground_velocity_end);
  // Moreau's midpoint scheme: half a step of positions with the last velocities, contacts and
  // impulses at the midpoint, the other half with the new velocities. The impact of a closing
  // contact is then centred on the instant it closes, and between impacts the scheme is the
  // symplectic position Verlet (no energy drift), where positions updated with the end velocities
  // alone lost 1-2 % of a rocking block's energy per impact at a 1 ms step.
  advance_to_midpoint(world, dt);
  gather_contacts(world, dt, ground_velocity);
  const double smallest_radius = set_free_velocities(world, dt, ground_velocity);
  const bool corrected = solve_impulses(world, dt, smallest_radius);
  apply_local_damping(world);
  store_impulses(world, dt, ground_velocity);
  advance_from_midpoint(world, dt, ground_velocity, ground_velocity_end, corrected);
  world.time += dt;
  ++world.stats.steps;
}

void RigidStepper::advance_to_midpoint(WorldCore& world, double dt) {
  world.move_pedestals(0.5 * dt, pedestal_velocity_);
  for (std::size_t i = 0; i < world.defs.size(); ++i) {
    if (world.defs[i].fixed) continue;
    auto& s = world.states[i];
    s.position += 0.5 * dt * s.velocity;
    if (world.effects.distance_skin) world.travel[i] += 0.5 * dt * (s.velocity - pedestal_velocity_).norm();
    world.drift_rotation(static_cast<int>(i), 0.5 * dt);
    world.rotations[i] = s.orientation.toRotationMatrix();
    world.update_world_vertices(static_cast<int>(i));
  }
}

void RigidStepper::gather_contacts(WorldCore& world, double dt, const Vec3& ground_velocity) {
  rows_.clear();
  patches_.clear();
  member_begin_.clear();
  member_pairs_.clear();
  world.max_overlap = 0;
  const double restitution = world.law.restitution;
  for (std::size_t j = 0; j < world.pairs.size(); ++j) {
    PairContact& p = world.pairs[j];
    PairImpulses& kept = impulses_[j];
    const auto& da = world.defs[p.a];
    const auto& db = world.defs[p.b];
    const auto& sa = world.states[p.a];
    const auto& sb = world.states[p.b];
    const Vec3 va = da.fixed ? ground_velocity : sa.velocity;
    const Vec3 vb = db.fixed ? ground_velocity : sb.velocity;
    const Vec3 wa = world.angular_velocity(p.a);
    const Vec3 wb = world.angular_velocity(p.b);
    // every point that can close within the step is inside the margin
    const double small = std::min(da.shape.bounding_radius, db.shape.bounding_radius);
    const double reach = (vb - va).norm() + wa.norm() * da.shape.bounding_radius + wb.norm() * db.shape.bounding_radius;
    const double margin = kMarginFraction * small + 2.0 * dt * reach;
    if (world.pair_apart(p, margin)) {
      // the friction impulse stays: it is the warm start should the pair touch again
      kept.subs.clear();
      continue;
    }
    ++world.stats.pair_tests;
    ++p.tests;
    // B is shifted by the margin along last step's normal, into A: pairs open by less than the
    // margin then overlap, and the common plane and subcontacts of the penetrating case apply
    const Vec3 shift = -margin * p.normal;
    contact::PlacedHull ha{&world.contact_piece(p.a, p.piece_a), world.piece_vertices(p.a, p.piece_a), Vec3::Zero(),
                           world.rotations[p.a], sa.position};
    contact::PlacedHull hb{&world.contact_piece(p.b, p.piece_b), world.piece_vertices(p.b, p.piece_b), shift,
                           world.rotations[p.b], sb.position};
    const contact::CommonPlane cp = contact::find_common_plane(ha, hb, p.normal, p.hints);
    const Vec3 n = cp.normal;
    const double shift_along_n = -n.dot(shift);  // how much closer the shift brought them along n
    p.normal = n;
    p.overlap = cp.overlap - shift_along_n;
    p.points.clear();
    kept.next_subs.clear();
    if (cp.overlap <= 0) {
      kept.subs.clear();
      kept.friction_impulse.setZero();
      kept.twist_impulse = 0;
      continue;
    }
    contact::collect_subcontacts(ha, hb, cp, p.points);
    FrictionPatch patch;
    patch.a = p.a;
    patch.b = p.b;
    patch.first_row = static_cast<int>(rows_.size());
    patch.row_count = static_cast<int>(p.points.size());
    patch.normal = n;
    patch.friction = world.law.friction;
    const double slop = kSlopFraction * small;
    const double touching = -slop;
    Vec3 centre = Vec3::Zero(), all = Vec3::Zero();
    int closed = 0;
    for (auto& pt : p.points) {
      // back to the true configuration: the point sat half-way through the shifted overlap
      pt.overlap -= shift_along_n;
      pt.point -= 0.5 * shift;
      PairImpulses::Sub sub{pt.key};
      for (const auto& old : kept.subs) {
        if (old.key == pt.key) {
          sub = old;
          break;
        }
      }
      ContactRow row;
      row.a = p.a;
      row.b = p.b;
      row.ra = pt.point - sa.position;
      row.rb = pt.point - sb.position;
      row.normal = n;
      const Vec3 relative = (vb + wb.cross(row.rb)) - (va + wa.cross(row.ra));
      const double approach = -n.dot(relative);  // > 0 closing
      if (pt.overlap < -slop) {
        // open at the midpoint: no constraint this step (Moreau's activation); a contact closing
        // in the second half takes its impact at the next midpoint, with the velocity it arrives
        // with. Constraining it now to just touch would be a partial inelastic impact before the
        // contact, which cost a rocking block 1-2 % of its energy per impact and an elastic one
        // (e_n = 1) all of it
        row.target_normal_velocity = -std::numeric_limits<double>::infinity();
      } else {
        // closed, or open by less than the slop (a resting contact, which rounding and half a step
        // of gravity open and close by nanometres, stays a constraint instead of chattering).
        // Newton's impact law on a closed contact; a contact merely resting (closing by no more
        // than gravity's pull of a few steps) takes no bounce
        row.target_normal_velocity =
            restitution > 0 && approach > 10.0 * world.settings.gravity * dt ? restitution * approach : 0.0;
        world.max_overlap = std::max(world.max_overlap, pt.overlap);
      }
      row.correction_velocity = pt.overlap > slop ? kCorrectionRate * (pt.overlap - slop) / dt : 0.0;
      row.normal_impulse = sub.normal_impulse;
      kept.next_subs.push_back(sub);
      rows_.push_back(row);
      all += pt.point;
      if (pt.overlap >= touching) {
        centre += pt.point;
        ++closed;
      }
    }
    std::swap(kept.subs, kept.next_subs);
    // the patch: the closed points (all of them while none is closed yet)
    centre = closed > 0 ? Vec3(centre / closed) : Vec3(all / double(p.points.size()));
    double spread = 0;
    for (const auto& pt : p.points) {
      if (closed == 0 || pt.overlap >= touching) {
        const Vec3 d = pt.point - centre;
        spread += (d - n.dot(d) * n).norm();
      }
    }
    patch.radius = spread / (closed > 0 ? closed : double(p.points.size()));
    patch.ra = centre - sa.position;
    patch.rb = centre - sb.position;
    set_tangents(patch);
    // last step's friction of the pair, carried into the new tangent plane
    patch.impulse =
        Eigen::Vector3d(patch.tangent1.dot(kept.friction_impulse), patch.tangent2.dot(kept.friction_impulse),
                        patch.radius > 0 ? kept.twist_impulse : 0.0);
    patches_.push_back(patch);
    member_begin_.push_back(static_cast<int>(member_pairs_.size()));
    member_pairs_.push_back(static_cast<int>(j));
  }
  member_begin_.push_back(static_cast<int>(member_pairs_.size()));
  if (has_compound_) merge_piece_patches(world);
}

// Coulomb's law holds for the whole interface of two bodies, not per convex piece: a compound
// body's pieces resting on one face would otherwise each carry a friction cone of its own, and the
// solver could balance tangential impulses among them (opposite pushes that cancel) and let the
// body slide or walk below mu g. Patches of the same two bodies with the same normal become one
// patch: the rows of all, one friction and twist constraint about the centre of their closed
// points.
void RigidStepper::merge_piece_patches(const WorldCore& world) {
  const std::size_t count = patches_.size();
  patch_taken_.assign(count, 0);
  merged_patches_.clear();
  merged_rows_.clear();
  merged_members_.clear();
  merged_begin_.clear();
  constexpr double kAligned = 1e-6;  // 1 - cos of the angle between normals of one face
  for (std::size_t j = 0; j < count; ++j) {
    if (patch_taken_[j]) continue;
    FrictionPatch patch = patches_[j];
    patch.first_row = static_cast<int>(merged_rows_.size());
    merged_begin_.push_back(static_cast<int>(merged_members_.size()));
    int members = 0;
    for (std::size_t k = j; k < count; ++k) {
      const FrictionPatch& other = patches_[k];
      if (patch_taken_[k] || other.a != patch.a || other.b != patch.b) continue;
      if (1.0 - other.normal.dot(patch.normal) > kAligned) continue;
      patch_taken_[k] = 1;
      ++members;
      merged_rows_.insert(merged_rows_.end(), rows_.begin() + other.first_row,
                          rows_.begin() + other.first_row + other.row_count);
      for (int m = member_begin_[k]; m < member_begin_[k + 1]; ++m) merged_members_.push_back(member_pairs_[m]);
    }
    patch.row_count = static_cast<int>(merged_rows_.size()) - patch.first_row;
    if (members > 1) {
      const Vec3& pa = world.states[patch.a].position;
      const Vec3& n = patch.normal;
      Vec3 centre = Vec3::Zero(), all = Vec3::Zero();
      int closed = 0;
      for (int r = patch.first_row; r < patch.first_row + patch.row_count; ++r) {
        const ContactRow& row = merged_rows_[r];
        all += pa + row.ra;
        if (row.target_normal_velocity > -std::numeric_limits<double>::infinity()) {
          centre += pa + row.ra;
          ++closed;
        }
      }
      centre = closed > 0 ? Vec3(centre / closed) : Vec3(all / double(patch.row_count));
      double spread = 0;
      for (int r = patch.first_row; r < patch.first_row + patch.row_count; ++r) {
        const ContactRow& row = merged_rows_[r];
        if (closed > 0 && row.target_normal_velocity == -std::numeric_limits<double>::infinity()) continue;
        const Vec3 d = pa + row.ra - centre;
        spread += (d - n.dot(d) * n).norm();
      }
      patch.radius = spread / (closed > 0 ? closed : double(patch.row_count));
      patch.ra = centre - pa;
      patch.rb = centre - world.states[patch.b].position;
      set_tangents(patch);
      // each member pair keeps its share of the last merged impulse (see store_impulses)
      Vec3 friction = Vec3::Zero();
      double twist = 0;
      for (int m = merged_begin_.back(); m < static_cast<int>(merged_members_.size()); ++m) {
        friction += impulses_[merged_members_[m]].friction_impulse;
        twist += impulses_[merged_members_[m]].twist_impulse;
      }
      patch.impulse =
          Eigen::Vector3d(patch.tangent1.dot(friction), patch.tangent2.dot(friction), patch.radius > 0 ? twist : 0.0);
    }
    merged_patches_.push_back(patch);
  }
  merged_begin_.push_back(static_cast<int>(merged_members_.size()));
  std::swap(rows_, merged_rows_);
  std::swap(patches_, merged_patches_);
  std::swap(member_pairs_, merged_members_);
  std::swap(member_begin_, merged_begin_);
}

double RigidStepper::set_free_velocities(const WorldCore& world, double dt, const Vec3& ground_velocity) {
  // free velocities: gravity over the step; the angular momentum is unchanged without torque
  const std::size_t n = world.defs.size();
  solver_bodies_.resize(n);
  double smallest_radius = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    SolverBody& b = solver_bodies_[i];
    const BodyDef& def = world.defs[i];
    if (def.fixed) {
      b.velocity = ground_velocity;
      b.angular_velocity.setZero();
      b.inverse_mass = 0;
      b.inverse_inertia.setZero();
      continue;
    }
    const double m = def.shape.mass;
    smallest_radius = std::min(smallest_radius, def.shape.bounding_radius);
    b.velocity = world.states[i].velocity + Vec3(0, 0, -world.settings.gravity * dt);
    b.angular_velocity = world.angular_velocity(static_cast<int>(i));
    b.inverse_mass = 1.0 / m;
    b.inverse_inertia = world_inverse_inertia(world.rotations[i], def.shape.inertia);
  }
  return smallest_radius;
}

bool RigidStepper::solve_impulses(WorldCore& world, double dt, double smallest_radius) {
  prepare(solver_bodies_, rows_, patches_);
  if (world.settings.local_damping > 0) free_bodies_ = solver_bodies_;
  // warm start: last step's impulses of the same subcontacts
  warm_start(solver_bodies_, rows_, patches_);
  // converged when a sweep changes velocities by less than a fraction (1e-7 by default) of what
  // gravity adds in a step, and angular velocities by that over the smallest block's radius (1e-6
  // let a block resting under a slow ramp creep 1e-6 rad before its uplift acceleration)
  SolverSettings solver;
  solver.velocity_tolerance = world.settings.solver_tolerance * world.settings.gravity * dt;
  solver.angular_tolerance = solver.velocity_tolerance / smallest_radius;
  solver.max_iterations = world.settings.solver_max_sweeps;
  const SolverResult result = solve_velocities(solver_bodies_, rows_, patches_, solver, solver_scratch_);
  if (!result.converged) ++world.stats.unconverged_steps;
  world.stats.max_solver_sweeps = std::max(world.stats.max_solver_sweeps, result.iterations);
  if (!patches_.empty()) {
    ++world.stats.solver_solves;
    world.stats.solver_sweeps += result.iterations;
  }
  const bool correct =
      std::any_of(rows_.begin(), rows_.end(), [](const ContactRow& r) { return r.correction_velocity > 0; });
  if (correct) solve_correction(solver_bodies_, pseudo_bodies_, rows_, patches_, solver, solver_scratch_);
  return correct;
}

void RigidStepper::apply_local_damping(const WorldCore& world) {
  if (world.settings.local_damping <= 0) return;
  // Itasca local damping (physics.md §9) on the step's velocity change, which is the unbalanced
  // force times h: each component is reduced by alpha |change|, never past zero
  const double alpha = world.settings.local_damping;
  for (std::size_t i = 0; i < world.defs.size(); ++i) {
    if (world.defs[i].fixed) continue;
    auto damp = [alpha](Vec3& v, const Vec3& before) {
      for (int c = 0; c < 3; ++c) {
        const double cut = alpha * std::abs(v[c] - before[c]);
        v[c] = v[c] > 0 ? std::max(0.0, v[c] - cut) : std::min(0.0, v[c] + cut);
      }
    };
    damp(solver_bodies_[i].velocity, free_bodies_[i].velocity);
    damp(solver_bodies_[i].angular_velocity, free_bodies_[i].angular_velocity);
  }
}

void RigidStepper::store_impulses(WorldCore& world, double dt, const Vec3& ground_velocity) {
  for (auto& force : world.contact_force) force.setZero();
  Vec3 on_pedestals = Vec3::Zero();
  for (std::size_t j = 0; j < patches_.size(); ++j) {
    const FrictionPatch& patch = patches_[j];
    Vec3 impulse = Vec3::Zero();
    double total = 0;
    int row = patch.first_row;
    for (int m = member_begin_[j]; m < member_begin_[j + 1]; ++m) {
      for (auto& sub : impulses_[member_pairs_[m]].subs) {
        const ContactRow& r = rows_[row++];
        sub.normal_impulse = r.normal_impulse;
        impulse += r.normal_impulse * r.normal;
        total += r.normal_impulse;
      }
    }
    const Vec3 friction = patch.impulse.x() * patch.tangent1 + patch.impulse.y() * patch.tangent2;
    const double members = member_begin_[j + 1] - member_begin_[j];
    for (int m = member_begin_[j]; m < member_begin_[j + 1]; ++m) {
      impulses_[member_pairs_[m]].friction_impulse = friction / members;
      impulses_[member_pairs_[m]].twist_impulse = patch.impulse.z() / members;
    }
    impulse += friction;
    world.contact_force[patch.b] += impulse / dt;
    world.contact_force[patch.a] -= impulse / dt;
    if (world.defs[patch.a].fixed) on_pedestals -= impulse;
    if (world.defs[patch.b].fixed) on_pedestals += impulse;
    if (total > 0) ++world.stats.contact_steps;
    // sliding: the friction on its limit and the patch centre still slipping at the end
    const double size =
        std::hypot(patch.impulse.x(), patch.impulse.y(), patch.radius > 0 ? patch.impulse.z() / patch.radius : 0.0);
    if (total > 0 && size >= patch.friction * total * (1 - 1e-9)) {
      Vec3 u = relative_velocity(solver_bodies_[patch.a], solver_bodies_[patch.b], patch.ra, patch.rb);
      u -= patch.normal.dot(u) * patch.normal;
      const double slip = u.norm() * dt;
      if (slip > 0) {
        ++world.stats.sliding_steps;
        if (!world.defs[patch.a].fixed) world.slip[patch.a] += slip;
        if (!world.defs[patch.b].fixed) world.slip[patch.b] += slip;
      }
    }
  }
  // the pedestals push with these impulses while moving at the mean ground velocity
  world.pedestal_work -= on_pedestals.dot(ground_velocity);
}

void RigidStepper::advance_from_midpoint(WorldCore& world, double dt, const Vec3& ground_velocity,
                                         const Vec3& ground_velocity_end, bool corrected) {
  world.move_pedestals(0.5 * dt, ground_velocity);
  pedestal_velocity_ = ground_velocity;
  for (std::size_t i = 0; i < world.defs.size(); ++i) {
    auto& s = world.states[i];
    if (world.defs[i].fixed) {
      s.velocity = ground_velocity_end;
      continue;
    }
    const SolverBody& b = solver_bodies_[i];
    s.velocity = b.velocity;
    // L = R I R^T w with the orientation the solve used
    const Mat3& r = world.rotations[i];
    s.angular_momentum = r * world.defs[i].shape.inertia.cwiseProduct(r.transpose() * b.angular_velocity);
    // the second half with the new velocities, plus the split impulse's pseudo-velocities, which
    // move but carry no momentum
    Vec3 move = 0.5 * dt * s.velocity;
    if (corrected) move += dt * pseudo_bodies_[i].velocity;
    s.position += move;
    if (world.effects.distance_skin) world.travel[i] += (move - 0.5 * dt * ground_velocity).norm();
    world.drift_rotation(static_cast<int>(i), 0.5 * dt);
    if (corrected) {
      const Vec3 turn = dt * pseudo_bodies_[i].angular_velocity;
      const double angle = turn.norm();
      if (angle > 0) s.orientation = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * s.orientation).normalized();
    }
    world.rotations[i] = s.orientation.toRotationMatrix();
    world.update_world_vertices(static_cast<int>(i));
  }
}

}  // namespace rigid::dynamics
