#include "rigid/scenario/scene.hpp"

#include "resting_contacts.hpp"
#include "rigid/core/error.hpp"
#include "rigid/scenario/run_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace rigid::scenario {

Vec3 GroundDrive::at(double t) const {
  if (velocity.empty()) return Vec3::Zero();
  if (t <= 0) return velocity.front();
  const double x = t / dt;
  const std::size_t k = static_cast<std::size_t>(x);
  if (k + 1 >= velocity.size()) return velocity.back();
  const double f = x - double(k);
  return (1 - f) * velocity[k] + f * velocity[k + 1];
}

Vec3 GroundDrive::displacement(double t0, double t1) const {
  Vec3 sum = Vec3::Zero();
  if (velocity.empty() || !(t1 > t0)) return sum;
  // constant velocity before the first sample and after the last
  if (t0 < 0) {
    const double b = std::min(t1, 0.0);
    sum += (b - t0) * velocity.front();
    t0 = b;
  }
  const double end = duration();
  if (t1 > end) {
    const double a = std::max(t0, end);
    sum += (t1 - a) * velocity.back();
    t1 = a;
  }
  if (!(t1 > t0)) return sum;
  // linear between samples: trapezoids are exact
  double a = t0;
  Vec3 va = at(t0);
  for (std::size_t j = static_cast<std::size_t>(t0 / dt) + 1; j < velocity.size() && double(j) * dt < t1; ++j) {
    const double b = double(j) * dt;
    sum += 0.5 * (b - a) * (va + velocity[j]);
    a = b;
    va = velocity[j];
  }
  sum += 0.5 * (t1 - a) * (va + at(t1));
  return sum;
}

GroundDrive ground_drive(const motion::GroundMotion& m) {
  const motion::GroundVelocity v = motion::ground_velocity(m);
  GroundDrive drive;
  drive.dt = v.dt;
  drive.velocity.resize(v.vx.size());
  for (std::size_t i = 0; i < v.vx.size(); ++i) drive.velocity[i] = Vec3(v.vx[i], v.vy[i], v.vz[i]);
  return drive;
}

void offset_centre_of_mass(dynamics::BodyDef& body, const Vec3& offset_mesh) {
  if (body.fixed) throw std::invalid_argument("a fixed block's centre of mass plays no part: offset a free block");
  // the mesh frame is where the block was built; the body frame turns with the block
  const Vec3 offset_body = body.shape.rotation.conjugate() * offset_mesh;
  geometry::offset_mass_centre(body.shape, body.pieces, offset_body);
  body.position += body.orientation * offset_body;
  body.centre_of_mass_offset += offset_body;
}

Vec3 centroid_position(const dynamics::BodyDef& body) {
  return body.position - body.orientation * body.centre_of_mass_offset;
}

double tilt(const Quat& initial, const Quat& current) {
  // initial vertical axis in body coordinates, carried to the world by the current pose
  const Vec3 axis = current * (initial.conjugate() * Vec3::UnitZ());
  return std::acos(std::clamp(axis.z(), -1.0, 1.0));
}

Settled settle(const Scene& scene, const dynamics::StepSettings& step, double max_time, double local_damping) {
  dynamics::StepSettings s = step;
  s.local_damping = local_damping;
  check_run_bounds(scene, s, max_time);
  dynamics::World world(scene.bodies, scene.law, s);
  const double dt = world.dt();
  // below this height a free block has passed every fixed block: nothing can catch it
  double lowest_fixed = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (!scene.bodies[i].fixed) continue;
    for (const Vec3& v : world.world_vertices(int(i))) lowest_fixed = std::min(lowest_fixed, v.z());
  }
  std::optional<std::size_t> fallen;
  double rest_since = -1;
  // settle until at rest for a while, checked with tight thresholds (unit: m/s, rad/s)
  const double rest_speed = 1e-6, rest_angular_speed = 1e-6;
  for (double t = 0; t < max_time && !fallen; t += dt) {
    world.step(dt, Vec3::Zero(), Vec3::Zero());
    for (std::size_t i = 0; i < scene.bodies.size() && !fallen; ++i) {
      const auto& body = scene.bodies[i];
      if (!body.fixed && world.states()[i].position.z() < lowest_fixed - body.shape.bounding_radius) fallen = i;
    }
    if (at_rest(world, rest_speed, rest_angular_speed)) {
      if (rest_since < 0) rest_since = t;
      if (t - rest_since > 0.2) break;
    } else {
      rest_since = -1;
    }
  }
  Settled out{scene, std::nullopt};
  for (std::size_t i = 0; i < out.scene.bodies.size(); ++i) {
    auto& body = out.scene.bodies[i];
    if (body.fixed) continue;
    const auto& state = world.states()[i];
    const bool carried = world.contact_force(int(i)).z() >= 0.1 * body.shape.mass * s.gravity;
    if (!out.loose && (fallen == i || !carried)) {
      out.loose = LooseBlock{body.name, body.position.z() - state.position.z(),
                             tilt(body.orientation, state.orientation), fallen == i};
    }
    body.position = state.position;
    body.orientation = state.orientation;
    body.velocity.setZero();
    body.angular_velocity.setZero();
  }
  return out;
}

Scene equilibrate(const Scene& scene, const dynamics::StepSettings& step, double max_time, double local_damping) {
  Settled settled = settle(scene, step, max_time, local_damping);
  if (settled.loose) throw InputError("", 0, scene.source + ": " + describe(*settled.loose));
  return std::move(settled.scene);
}

std::string describe(const LooseBlock& loose) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "it fell %.3g m%s and turned %.0f deg", loose.drop,
                loose.below_fixed ? " (below every fixed block)" : "", loose.turn * 180 / kPi);
  return "block '" + loose.name + "' rests on nothing after settling: " + buf;
}

}  // namespace rigid::scenario
