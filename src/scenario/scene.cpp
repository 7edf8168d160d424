#include "rigid/scenario/scene.hpp"

#include <algorithm>
#include <cmath>

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

GroundDrive ground_drive(const motion::GroundMotion& m) {
  const motion::GroundVelocity v = motion::ground_velocity(m);
  GroundDrive drive;
  drive.dt = v.dt;
  drive.velocity.resize(v.vx.size());
  for (std::size_t i = 0; i < v.vx.size(); ++i) drive.velocity[i] = Vec3(v.vx[i], v.vy[i], v.vz[i]);
  return drive;
}

double tilt(const Quat& initial, const Quat& current) {
  // initial vertical axis in body coordinates, carried to the world by the current pose
  const Vec3 axis = current * (initial.conjugate() * Vec3::UnitZ());
  return std::acos(std::clamp(axis.z(), -1.0, 1.0));
}

namespace {

bool at_rest(const dynamics::World& world, const RunSettings& s) {
  const auto& defs = world.bodies();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    if (world.states()[i].velocity.norm() > s.rest_speed) return false;
    if (world.angular_velocity(static_cast<int>(i)).norm() > s.rest_angular_speed) return false;
  }
  return true;
}

}  // namespace

RunOutcome run(const Scene& scene, const GroundDrive& ground, const RunSettings& settings) {
  dynamics::World world(scene.bodies, scene.law, settings.step);
  RunOutcome out;
  const double dt = world.dt();
  out.dt = dt;
  const double motion_end = ground.duration();
  const double duration = settings.duration > 0 ? settings.duration : motion_end + settings.free_time;
  const long steps = static_cast<long>(std::ceil(duration / dt - 1e-9));
  const auto& defs = scene.bodies;
  double rest_since = -1;
  const long observe_every = std::max(1L, std::lround(settings.observe_interval / dt));
  if (settings.observer) settings.observer(world);
  for (long k = 0; k < steps; ++k) {
    const double t0 = double(k) * dt;
    const double t1 = double(k + 1) * dt;
    world.step(dt, ground.at(t0), ground.at(t1));
    out.steps = k + 1;
    out.simulated = t1;
    if (settings.observer && (k + 1) % observe_every == 0) settings.observer(world);
    out.max_overlap = std::max(out.max_overlap, world.max_overlap());

    // the lowest point of the pedestals, for the study's failure rule
    double lowest_fixed = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (!defs[i].fixed) continue;
      for (const auto& v : world.world_vertices(static_cast<int>(i))) lowest_fixed = std::min(lowest_fixed, v.z());
    }
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (defs[i].fixed) continue;
      const auto& s = world.states()[i];
      if (!s.position.allFinite() || !s.orientation.coeffs().allFinite() ||
          !s.velocity.allFinite() || !s.angular_momentum.allFinite()) {
        out.finite = false;
        return out;
      }
      const double a = tilt(defs[i].orientation, s.orientation);
      out.max_tilt = std::max(out.max_tilt, a);
      const bool failed = scene.failure.kind == FailureRule::Kind::below
                              ? s.position.z() < lowest_fixed
                              : a > scene.failure.tilt_angle;
      if (failed && !out.overturned) {
        out.overturned = true;
        out.failure_time = t1;
        out.failed_block = defs[i].name;
      }
    }
    if (out.overturned) break;
    // after the motion, a scene at rest stays at rest: nothing more can happen
    if (t1 >= motion_end && at_rest(world, settings)) {
      if (rest_since < 0) rest_since = t1;
      if (t1 - rest_since >= settings.rest_time) {
        out.ended_at_rest = true;
        break;
      }
    } else {
      rest_since = -1;
    }
  }
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (!defs[i].fixed) out.max_slip = std::max(out.max_slip, world.slip()[i]);
  }
  if (settings.observer && out.steps % observe_every != 0) settings.observer(world);
  return out;
}

Scene equilibrate(const Scene& scene, const dynamics::StepSettings& step, double max_time,
                  double local_damping) {
  dynamics::StepSettings s = step;
  s.local_damping = local_damping;
  dynamics::World world(scene.bodies, scene.law, s);
  RunSettings rest;
  const double dt = world.dt();
  double rest_since = -1;
  // settle until at rest for a while, checked with tight thresholds
  rest.rest_speed = 1e-6;
  rest.rest_angular_speed = 1e-6;
  for (double t = 0; t < max_time; t += dt) {
    world.step(dt, Vec3::Zero(), Vec3::Zero());
    if (at_rest(world, rest)) {
      if (rest_since < 0) rest_since = t;
      if (t - rest_since > 0.2) break;
    } else {
      rest_since = -1;
    }
  }
  Scene out = scene;
  for (std::size_t i = 0; i < out.bodies.size(); ++i) {
    if (out.bodies[i].fixed) continue;
    out.bodies[i].position = world.states()[i].position;
    out.bodies[i].orientation = world.states()[i].orientation;
    out.bodies[i].velocity.setZero();
    out.bodies[i].angular_velocity.setZero();
  }
  return out;
}

}  // namespace rigid::scenario
