#include "rigid/dynamics/world_core.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rigid::dynamics {

WorldCore::WorldCore(std::vector<BodyDef> bodies, const contact::ContactLaw& contact_law,
                     const StepSettings& step_settings)
    : defs(std::move(bodies)), law(contact_law), settings(step_settings) {
  const std::size_t n = defs.size();
  states.resize(n);
  world_vertices.resize(n);
  world_piece_vertices.resize(n);
  rotations.resize(n);
  contact_force.assign(n, Vec3::Zero());
  slip.assign(n, 0.0);
  travel.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& d = defs[i];
    auto& s = states[i];
    // invariant (debug builds): a free block has positive mass and principal moments
    assert(d.fixed || (d.shape.mass > 0 && (d.shape.inertia.array() > 0).all()));
    s.position = d.position;
    s.orientation = d.orientation.normalized();
    s.velocity = d.velocity;
    const Mat3 r = s.orientation.toRotationMatrix();
    s.angular_momentum = r * d.shape.inertia.asDiagonal() * r.transpose() * d.angular_velocity;
    world_vertices[i].resize(d.shape.vertices.size());
    for (const auto& piece : d.pieces) world_piece_vertices[i].emplace_back(piece.vertices.size());
  }
  // every pair that can ever touch: two fixed blocks never interact
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      if (defs[a].fixed && defs[b].fixed) {
        ++fixed_fixed_pairs;
        continue;
      }
      // one pair per two contact pieces (one piece each for plain blocks)
      const std::size_t pieces_a = std::max<std::size_t>(1, defs[a].pieces.size());
      const std::size_t pieces_b = std::max<std::size_t>(1, defs[b].pieces.size());
      for (std::size_t ka = 0; ka < pieces_a; ++ka) {
        for (std::size_t kb = 0; kb < pieces_b; ++kb) {
          PairContact p;
          p.a = static_cast<int>(a);
          p.b = static_cast<int>(b);
          p.piece_a = static_cast<int>(ka);
          p.piece_b = static_cast<int>(kb);
          const Vec3 d = defs[b].position - defs[a].position;
          p.normal = d.norm() > 0 ? Vec3(d.normalized()) : Vec3(0, 0, 1);
          p.points.reserve(contact_piece(p.a, p.piece_a).vertices.size() +
                           contact_piece(p.b, p.piece_b).vertices.size() + 1);
          pairs.push_back(std::move(p));
        }
      }
    }
  }
}

void WorldCore::refresh_geometry() {
  for (std::size_t i = 0; i < defs.size(); ++i) {
    rotations[i] = states[i].orientation.toRotationMatrix();
    update_world_vertices(static_cast<int>(i));
  }
}

void WorldCore::update_world_vertices(int i) {
  const auto& body = defs[i].shape.vertices;
  const Mat3& r = rotations[i];
  const Vec3& x = states[i].position;
  auto& out = world_vertices[i];
  for (std::size_t k = 0; k < body.size(); ++k) out[k] = r * body[k] + x;
  const auto& pieces = defs[i].pieces;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const auto& local = pieces[p].vertices;
    auto& world = world_piece_vertices[i][p];
    for (std::size_t k = 0; k < local.size(); ++k) world[k] = r * local[k] + x;
  }
}

void WorldCore::shift_world_vertices(int i, const Vec3& shift) {
  for (auto& v : world_vertices[i]) v += shift;
  for (auto& piece : world_piece_vertices[i]) {
    for (auto& v : piece) v += shift;
  }
}

void WorldCore::shift_world_vertices_xy(int i, double dx, double dy) {
  auto shift = [dx, dy](std::vector<Vec3>& vertices) {
    for (auto& v : vertices) {
      v.x() += dx;
      v.y() += dy;
    }
  };
  shift(world_vertices[i]);
  for (auto& piece : world_piece_vertices[i]) shift(piece);
}

Vec3 WorldCore::angular_velocity(int i) const {
  if (defs[i].fixed) return Vec3::Zero();
  const Mat3& r = rotations[i];
  const Vec3 body_l = r.transpose() * states[i].angular_momentum;
  return r * body_l.cwiseQuotient(defs[i].shape.inertia);
}

void WorldCore::drift_rotation(int i, double dt_step) {
  auto& s = states[i];
  const Vec3& inertia = defs[i].shape.inertia;
  const Vec3& l = s.angular_momentum;
  Quat q = s.orientation;
  if (settings.rotation == RotationIntegrator::splitting) {
    // exact rotations about body axes 3,2,1,2,3 with steps h/2,h/2,h,h/2,h/2 (physics.md §8)
    static constexpr int kAxes[5] = {2, 1, 0, 1, 2};
    static constexpr double kFractions[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
    for (int k = 0; k < 5; ++k) {
      const int axis = kAxes[k];
      const Vec3 body_l = q.conjugate() * l;
      const double half_angle = 0.5 * kFractions[k] * dt_step * body_l[axis] / inertia[axis];
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
    const Quat k2 = derivative(add(q, k1, 0.5 * dt_step));
    const Quat k3 = derivative(add(q, k2, 0.5 * dt_step));
    const Quat k4 = derivative(add(q, k3, dt_step));
    q.coeffs() += (dt_step / 6.0) * (k1.coeffs() + 2.0 * k2.coeffs() + 2.0 * k3.coeffs() + k4.coeffs());
  }
  q.normalize();
  s.orientation = q;
}

void WorldCore::move_pedestals(double dt_step, const Vec3& ground_velocity) {
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (!defs[i].fixed) continue;
    auto& s = states[i];
    // pedestals follow the ground: trapezoid of the linearly interpolated velocity
    s.velocity = ground_velocity;
    if (effects.vertical_ground) {
      s.position += dt_step * ground_velocity;
      shift_world_vertices(static_cast<int>(i), dt_step * ground_velocity);
    } else {
      // no vertical component: the same sums in x and y, z left alone (it would add 0 exactly)
      const double dx = dt_step * ground_velocity.x(), dy = dt_step * ground_velocity.y();
      s.position.x() += dx;
      s.position.y() += dy;
      shift_world_vertices_xy(static_cast<int>(i), dx, dy);
    }
  }
}

bool WorldCore::pair_apart(PairContact& p, double margin) {
  const auto& da = defs[p.a];
  const auto& db = defs[p.b];
  // skin: the spheres were further apart than the bodies have travelled since
  const double moved = effects.distance_skin ? travel[p.a] + travel[p.b] : 0.0;
  if (p.skin_gap > 0 && moved - p.skin_travel < p.skin_gap) {
    ++stats.pairs_culled;
    return true;
  }
  // bounding spheres apart: no contact possible this step
  const auto& pa = contact_piece(p.a, p.piece_a);
  const auto& pb = contact_piece(p.b, p.piece_b);
  const double radii = pa.bounding_radius + pb.bounding_radius;
  Vec3 centre_a = states[p.a].position, centre_b = states[p.b].position;
  if (!da.pieces.empty()) centre_a += rotations[p.a] * pa.bounding_centre;
  if (!db.pieces.empty()) centre_b += rotations[p.b] * pb.bounding_centre;
  const double gap = (centre_b - centre_a).norm() - radii;
  if (gap > margin) {
    p.points.clear();
    p.overlap = -gap;
    ++stats.pairs_skipped;
    if (effects.distance_skin) {
      // the margin covers the rounding of positions summed over millions of steps
      p.skin_gap = gap - margin - 1e-6 * radii;
      p.skin_travel = moved;
    }
    return true;
  }
  p.skin_gap = -1;
  return false;
}

void WorldCore::carry_with_ground(double t_end, const Vec3& displacement, const Vec3& v_start, const Vec3& v_end) {
  const Vec3 dv = v_end - v_start;
  for (std::size_t i = 0; i < defs.size(); ++i) {
    auto& s = states[i];
    s.position += displacement;
    shift_world_vertices(static_cast<int>(i), displacement);
    if (defs[i].fixed) {
      s.velocity = v_end;
      continue;
    }
    s.velocity += dv;
    // the contact force carrying the block is m (a_ground + g z), whose work along the ground's
    // path is the change of m |v_ground|^2 / 2 plus m g dz
    const double m = defs[i].shape.mass;
    pedestal_work += 0.5 * m * (v_end.squaredNorm() - v_start.squaredNorm()) + m * settings.gravity * displacement.z();
  }
  time = t_end;
}

double WorldCore::kinetic_energy() const {
  double e = 0;
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    const auto& s = states[i];
    const Vec3 body_l = rotations[i].transpose() * s.angular_momentum;
    e += 0.5 * defs[i].shape.mass * s.velocity.squaredNorm() +
         0.5 * body_l.cwiseProduct(body_l).cwiseQuotient(defs[i].shape.inertia).sum();
  }
  return e;
}

double WorldCore::potential_energy() const {
  double e = 0;
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (!defs[i].fixed) e += defs[i].shape.mass * settings.gravity * states[i].position.z();
  }
  return e;
}

}  // namespace rigid::dynamics
